use dynagen::{Model, Robot};
use nalgebra::{dmatrix, dvector, Matrix4, Matrix6, Vector3, Vector6};

fn mr_example() -> Robot {
    let m01 = Matrix4::new(1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0.089159, 0., 0., 0., 1.);
    let m12 = Matrix4::new(0., 0., 1., 0.28, 0., 1., 0., 0.13585, -1., 0., 0., 0., 0., 0., 0., 1.);
    let m23 = Matrix4::new(1., 0., 0., 0., 0., 1., 0., -0.1197, 0., 0., 1., 0.395, 0., 0., 0., 1.);
    let m34 = Matrix4::new(1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0.14225, 0., 0., 0., 1.);
    let g1 = Matrix6::from_diagonal(&Vector6::new(0.010267, 0.010267, 0.00666, 3.7, 3.7, 3.7));
    let g2 = Matrix6::from_diagonal(&Vector6::new(0.22689, 0.22689, 0.0151074, 8.393, 8.393, 8.393));
    let g3 = Matrix6::from_diagonal(&Vector6::new(0.0494433, 0.0494433, 0.004095, 2.275, 2.275, 2.275));
    let slist = dmatrix![1., 0., 0.; 0., 1., 1.; 1., 0., 0.; 0., -0.089, -0.089; 1., 0., 0.; 0., 0., 0.425];
    Robot::new(Model::from_modern_robotics(&[m01, m12, m23, m34], &[g1, g2, g3], &slist).unwrap())
}

#[test]
fn inverse_dynamics_docstring() {
    let mut r = mr_example();
    r.set_gravity(Vector3::new(0., 0., -9.8)).unwrap();
    r.set_tip_wrench("ee", Vector6::new(1., 1., 1., 1., 1., 1.)).unwrap();
    let tau = r.inverse_dynamics(&dvector![0.1, 0.1, 0.1], &dvector![0.1, 0.2, 0.3], &dvector![2., 1.5, 1.]).unwrap();
    let want = [74.69616155, -33.06766016, -3.23057314];
    for i in 0..3 {
        assert!((tau[i] - want[i]).abs() < 1e-8, "{tau} vs {want:?}");
    }
}
