//! The UR5 module written by dynagen's code generator (see build.rs),
//! compiled and compared with the generic solver on random states.

use dynagen::Robot;
use nalgebra::DVector;

#[allow(dead_code)]
mod ur5 {
    include!(concat!(env!("OUT_DIR"), "/ur5.rs"));
}

#[allow(dead_code)]
mod ur5_f32 {
    include!(concat!(env!("OUT_DIR"), "/ur5_f32.rs"));
}

/// xorshift64*, uniform in [-1, 1).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn array(&mut self, scale: f64) -> [f64; ur5::DOF] {
        core::array::from_fn(|_| scale * self.next())
    }
}

fn robot() -> Robot {
    Robot::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/../dynagen/robots/ur5.urdf")).unwrap()
}

/// |got − want| / |want| (Euclidean norms).
fn rel_err(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len());
    let norm = want.iter().map(|x| x * x).sum::<f64>().sqrt();
    let diff = got.iter().zip(want).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
    diff / norm
}

#[test]
fn generated_ur5_matches_generic_solver() {
    let mut robot = robot();
    assert_eq!(ur5::DOF, robot.dof());
    assert_eq!(ur5::JOINT_NAMES.to_vec(), robot.joint_names());
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut worst = [0.0f64; 5];
    for _ in 0..1000 {
        let (q, qd, qdd, tau) = (rng.array(3.0), rng.array(2.0), rng.array(5.0), rng.array(30.0));
        let v = |a: &[f64; 6]| DVector::from_column_slice(a);
        let checks: [(&str, Vec<f64>, Vec<f64>); 5] = [
            (
                "inverse_dynamics",
                ur5::inverse_dynamics(&q, &qd, &qdd).to_vec(),
                robot.inverse_dynamics(&v(&q), &v(&qd), &v(&qdd)).unwrap().as_slice().to_vec(),
            ),
            (
                "mass_matrix",
                ur5::mass_matrix(&q).concat(),
                // row-major, as the generated [[row]; DOF]
                robot.mass_matrix(&v(&q)).unwrap().transpose().as_slice().to_vec(),
            ),
            (
                "bias_forces",
                ur5::bias_forces(&q, &qd).to_vec(),
                robot.bias_forces(&v(&q), &v(&qd)).unwrap().as_slice().to_vec(),
            ),
            (
                "gravity_torques",
                ur5::gravity_torques(&q).to_vec(),
                robot.gravity_torques(&v(&q)).unwrap().as_slice().to_vec(),
            ),
            (
                "forward_dynamics",
                ur5::forward_dynamics(&q, &qd, &tau).to_vec(),
                robot.forward_dynamics(&v(&q), &v(&qd), &v(&tau)).unwrap().as_slice().to_vec(),
            ),
        ];
        for (k, (name, got, want)) in checks.iter().enumerate() {
            let e = rel_err(got, want);
            worst[k] = worst[k].max(e);
            assert!(e < 1e-12, "{name} at q = {q:?}: relative error {e:e}\n got {got:?}\nwant {want:?}");
        }
    }
    println!("worst relative errors (τ, M, h, g, q̈): {worst:?}");
}

#[test]
fn generated_ur5_f32_is_close() {
    let mut robot = robot();
    let mut rng = Rng(7);
    for _ in 0..100 {
        let (q, qd, qdd) = (rng.array(3.0), rng.array(2.0), rng.array(5.0));
        let f = |a: &[f64; 6]| a.map(|x| x as f32);
        let got = ur5_f32::inverse_dynamics(&f(&q), &f(&qd), &f(&qdd)).map(f64::from);
        let v = |a: &[f64; 6]| DVector::from_column_slice(a);
        let want = robot.inverse_dynamics(&v(&q), &v(&qd), &v(&qdd)).unwrap();
        let e = rel_err(&got, want.as_slice());
        assert!(e < 1e-4, "f32 inverse dynamics: relative error {e:e}");
    }
}
