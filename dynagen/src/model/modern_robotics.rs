//! Import from the Modern Robotics code library's lists: `Mlist` (the
//! home configurations M_{i-1,i} of each link frame relative to the previous
//! one, link frames at the centres of mass, the last one the end-effector),
//! `Glist` (the spatial inertia G_i of each link in its frame) and `Slist`
//! (the screw axes S_i in the space frame at home, one per column).

use super::description::{Inertial, JointDescription, JointType, LinkDescription, RobotDescription};
use super::{Model, ModelError};
use crate::spatial::{Mat3, Sym3, Transform, Vec3};
use nalgebra::{DMatrix, Matrix4, Matrix6};

/// The three lists of a serial chain, as the Modern Robotics library takes
/// them.
#[derive(Clone, Debug, PartialEq)]
pub struct ModernRoboticsLists {
    /// M_{i-1,i} for i = 1..n+1 (the last is the end-effector frame in the
    /// frame of link n).
    pub mlist: Vec<Matrix4<f64>>,
    /// G_i for i = 1..n, each in link frame {i}, (angular; linear) order.
    pub glist: Vec<Matrix6<f64>>,
    /// The screw axes S_i in the space frame at home, as the columns of a
    /// 6×n matrix (ω; v).
    pub slist: DMatrix<f64>,
}

fn transform(m: &Matrix4<f64>) -> Transform<f64> {
    Transform::from_homogeneous(&[
        [m[(0, 0)], m[(0, 1)], m[(0, 2)], m[(0, 3)]],
        [m[(1, 0)], m[(1, 1)], m[(1, 2)], m[(1, 3)]],
        [m[(2, 0)], m[(2, 1)], m[(2, 2)], m[(2, 3)]],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// The mass, centre of mass and inertia about it, from a 6×6 spatial inertia
/// `[[Ī, [h]], [[h]ᵀ, m·1]]`; checks the matrix has that form.
fn inertial_from_g(i: usize, g: &Matrix6<f64>) -> Result<Option<Inertial>, ModelError> {
    let bad = |why: &str| ModelError::ModernRobotics(format!("G_{i} (link{i}) is not a spatial inertia: {why}"));
    if !g.iter().all(|x| x.is_finite()) {
        return Err(bad("an entry is not finite"));
    }
    let scale = g.amax().max(f64::MIN_POSITIVE);
    let tol = 1e-9 * scale;
    if (g - g.transpose()).amax() > tol {
        return Err(bad("not symmetric"));
    }
    let m = g[(3, 3)];
    for r in 3..6 {
        for c in 3..6 {
            let want = if r == c { m } else { 0.0 };
            if (g[(r, c)] - want).abs() > tol {
                return Err(bad("the linear block is not m·1"));
            }
        }
    }
    let h = Vec3([g[(2, 4)], g[(0, 5)], g[(1, 3)]]);
    let skew = Mat3::skew(&h);
    for r in 0..3 {
        for c in 0..3 {
            if (g[(r, c + 3)] - skew.0[r][c]).abs() > tol {
                return Err(bad("the coupling block is not skew-symmetric"));
            }
        }
    }
    let ibar = Sym3([g[(0, 0)], g[(1, 1)], g[(2, 2)], g[(0, 1)], g[(0, 2)], g[(1, 2)]]);
    if m == 0.0 {
        if h.norm() > tol {
            return Err(bad("zero mass with a non-zero first moment"));
        }
        return Ok((ibar.0.iter().any(|&x| x != 0.0)).then(|| Inertial {
            mass: 0.0,
            origin: Transform::identity(),
            inertia: ibar,
        }));
    }
    let c = h.scale(1.0 / m);
    let i_c = ibar + Sym3::cross_shift(&c, &c).scale(-0.5 * m);
    Ok(Some(Inertial { mass: m, origin: Transform::translation(c), inertia: i_c }))
}

impl ModernRoboticsLists {
    /// The lists as a description: link `link{i}` is the frame of joint i
    /// (on the joint's axis, with link {i}'s orientation), `link{i}_com` is
    /// the library's link frame {i} and carries G_i, and `ee` is the
    /// end-effector frame. Joints are `joint1`…`jointn`. Screw axes are kept
    /// as given: a revolute axis ω of norm ≠ 1 turns the joint by |ω|·θ, as
    /// the library does.
    pub fn to_description(&self) -> Result<RobotDescription, ModelError> {
        let n = self.glist.len();
        let err = |s: String| ModelError::ModernRobotics(s);
        if self.mlist.len() != n + 1 {
            return Err(err(format!(
                "Mlist has {} matrices, but Glist has {n} (Mlist needs n+1, the last for the end-effector)",
                self.mlist.len()
            )));
        }
        if self.slist.nrows() != 6 || self.slist.ncols() != n {
            return Err(err(format!(
                "Slist is {}×{}, but it must be 6×{n} (one screw axis per column)",
                self.slist.nrows(),
                self.slist.ncols()
            )));
        }
        for (i, m) in self.mlist.iter().enumerate() {
            if m[(3, 0)] != 0.0 || m[(3, 1)] != 0.0 || m[(3, 2)] != 0.0 || m[(3, 3)] != 1.0 {
                return Err(err(format!("M_{}{} does not end in the row [0, 0, 0, 1]", i, i + 1)));
            }
        }
        let mut links = vec![LinkDescription::new("base", None)];
        let mut joints = Vec::new();
        let mut home = Transform::<f64>::identity(); // {i} in the space frame at home
        let mut parent = "base".to_string();
        for i in 1..=n {
            let m = transform(&self.mlist[i - 1]);
            home = home.compose(&m);
            let s = self.slist.column(i - 1);
            let screw = crate::spatial::Motion::new(Vec3([s[0], s[1], s[2]]), Vec3([s[3], s[4], s[5]]));
            if !screw.to_array().iter().all(|x| x.is_finite()) {
                return Err(err(format!("S_{i} is not finite")));
            }
            // the screw axis in {i}: A_i = [Ad_{M_i⁻¹}] S_i
            let a = home.motion_to_child(&screw);
            let (w, v) = (a.ang, a.lin);
            let (joint_type, axis, r) = if w.norm() > 0.0 {
                let w2 = w.norm_squared();
                let pitch = w.dot(&v) / w2;
                if pitch.abs() > 1e-9 * (1.0 + v.norm() / w.norm()) {
                    return Err(ModelError::Unsupported {
                        joint: format!("joint{i}"),
                        what: format!("a screw axis of pitch {pitch} (helical joint) is"),
                    });
                }
                (JointType::Revolute, w, w.cross(&v).scale(1.0 / w2))
            } else {
                (JointType::Prismatic, v, Vec3([0.0; 3]))
            };
            let name = format!("link{i}");
            links.push(LinkDescription::new(&name, None));
            links.push(LinkDescription::new(&format!("{name}_com"), inertial_from_g(i, &self.glist[i - 1])?));
            let mut j = JointDescription::revolute(&format!("joint{i}"), &parent, &name, axis.0);
            j.joint_type = joint_type;
            j.origin = m.compose(&Transform::translation(r));
            joints.push(j);
            let mut fixed = JointDescription::fixed(&format!("{name}_com_joint"), &name, &format!("{name}_com"));
            fixed.origin = Transform::translation(-r);
            joints.push(fixed);
            parent = format!("{name}_com");
        }
        links.push(LinkDescription::new("ee", None));
        let mut ee = JointDescription::fixed("ee_joint", &parent, "ee");
        ee.origin = transform(&self.mlist[n]);
        joints.push(ee);
        Ok(RobotDescription { name: "modern_robotics".into(), links, joints, gravity: None })
    }
}

impl Model {
    /// Builds a serial chain from the Modern Robotics lists (see
    /// [`ModernRoboticsLists::to_description`] for the names given to links,
    /// joints and frames). Gravity is the model default; the library's
    /// functions take it per call, and so do the `*_with` calls here.
    pub fn from_modern_robotics(
        mlist: &[Matrix4<f64>],
        glist: &[Matrix6<f64>],
        slist: &DMatrix<f64>,
    ) -> Result<Model, ModelError> {
        let lists = ModernRoboticsLists { mlist: mlist.to_vec(), glist: glist.to_vec(), slist: slist.clone() };
        Model::from_description(&lists.to_description()?)
    }
}
