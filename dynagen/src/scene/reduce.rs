//! [`Scene::apply`]: from a model and a scene to the reduced model.
//!
//! The reduction goes through a [`RobotDescription`]: the model's bodies and
//! frames are written back as links and joints (locked joints and joints
//! below a tip as fixed joints at their positions, the sub-tree root as the
//! root link, constant payloads folded into their links), and
//! [`Model::from_description`] builds the reduced model with the same checks
//! and the same merging of fixed joints as any other robot.

use super::{Gravity, PayloadInertia, PayloadValue, Scene, SceneError, SceneWarning};
use crate::algorithms::joint::joint_transform;
use crate::algorithms::{kinematics, Workspace};
use crate::model::{
    BuildOptions, Inertial, JointDescription, JointKind, JointType, LinkDescription, MimicDescription, Model,
    ModelWarning, RobotDescription,
};
use crate::spatial::{Inertia, Sym3, Transform, Vec3};
use std::collections::{HashMap, HashSet};

/// Gravity after the scene: a constant in the reduced model's base frame,
/// none, or a run-time input (in that frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ResolvedGravity {
    /// No gravity terms.
    None,
    /// This vector, in the reduced model's base frame (m/s²).
    Constant([f64; 3]),
    /// An argument of every call that has gravity terms.
    Input,
}

/// A payload whose mass properties are a run-time input.
#[derive(Clone, Debug, PartialEq)]
pub struct InputPayload {
    /// The link it is fixed to.
    pub link: String,
    /// That link's frame in the reduced model.
    pub frame: usize,
    /// The reduced model's body the link belongs to (`None`: the base, where
    /// a payload moves nothing unless the base floats).
    pub body: Option<usize>,
    /// The link's frame in the body's frame.
    pub placement: Transform<f64>,
}

impl InputPayload {
    /// The payload's spatial inertia in its body's frame, to add to the
    /// body's inertia.
    pub fn inertia_in_body(&self, p: &PayloadInertia) -> Inertia<f64> {
        let local = Inertia::from_mass_com_inertia(p.mass, Vec3(p.com), Sym3(p.inertia));
        self.placement.inertia_to_parent(&local)
    }
}

/// A scene applied to a model: what the generic solver runs and code
/// generation consumes. Every per-joint vector follows the reduced model's
/// joint order ([`SceneModel::joint_names`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneModel {
    /// The reduced model: kept joints only, locked and merged bodies folded
    /// in, constant payloads added, the sub-tree root as its base, and
    /// `gravity` set to the resolved constant (zero when gravity is none or
    /// an input).
    pub model: Model,
    /// The scene as given (for a generated file's header,
    /// [`Scene::to_toml_string`] writes it out).
    pub scene: Scene,
    /// Gravity, resolved.
    pub gravity: ResolvedGravity,
    /// The frame (index into the reduced model's frames) of the tip wrench
    /// input, if any.
    pub tip_wrench_frame: Option<usize>,
    /// Armature per joint.
    pub armature: Vec<f64>,
    /// Viscous friction coefficient per joint.
    pub viscous_friction: Vec<f64>,
    /// Coulomb friction per joint.
    pub coulomb_friction: Vec<f64>,
    /// Smoothing velocity of Coulomb friction.
    pub coulomb_velocity: f64,
    /// Payloads given at run time, in the scene's order.
    pub input_payloads: Vec<InputPayload>,
    /// The original model's frames (links) that the reduced model does not
    /// have, with why (for errors that name them).
    pub left_out_frames: Vec<(String, &'static str)>,
    /// The original moving joints that are fixed in the reduced model
    /// (locked, or merged below a tip), with the position they are fixed at.
    pub fixed_joints: Vec<(String, f64)>,
    /// The original moving joints that are gone: above the sub-tree root,
    /// outside the sub-tree, or on a dropped branch.
    pub removed_joints: Vec<String>,
    /// The links of the dropped bodies.
    pub dropped_links: Vec<String>,
    /// What was accepted with a warning.
    pub warnings: Vec<SceneWarning>,
}

impl SceneModel {
    /// The number of joints of the reduced model.
    pub fn dof(&self) -> usize {
        self.model.dof()
    }
    /// The reduced model's joint names, in the order of every vector.
    pub fn joint_names(&self) -> Vec<&str> {
        self.model.joint_names()
    }
    /// The index of frame `name` in the reduced model, for the option
    /// `what` (`frame_pose`, …); the error says why a frame of the original
    /// model is not there.
    pub fn frame(&self, what: &'static str, name: &str) -> Result<usize, SceneError> {
        if let Some(f) = self.model.frame_index(name) {
            return Ok(f);
        }
        match self.left_out_frames.iter().find(|(f, _)| f == name) {
            Some((_, why)) => Err(SceneError::LinkNotInScene { what, link: name.to_string(), why }),
            None => Err(SceneError::UnknownLink { what, name: name.to_string() }),
        }
    }
    /// Whether the scene adds nothing to the rigid-body equations: no
    /// armature, friction, tip wrench, gravity input or payload input (its
    /// functions are those of the contract, on the reduced model).
    pub fn is_plain(&self) -> bool {
        !self.has_armature()
            && !self.has_friction()
            && self.tip_wrench_frame.is_none()
            && self.gravity != ResolvedGravity::Input
            && self.input_payloads.is_empty()
    }
    /// Whether any joint has armature.
    pub fn has_armature(&self) -> bool {
        self.armature.iter().any(|&a| a != 0.0)
    }
    /// Whether any joint has friction.
    pub fn has_friction(&self) -> bool {
        self.viscous_friction.iter().chain(&self.coulomb_friction).any(|&x| x != 0.0)
    }
    /// The gravity vector the algorithms take: `None` when the scene has no
    /// gravity, `input` when gravity is an input (`None` if it is missing).
    pub fn gravity_vector(&self, input: Option<[f64; 3]>) -> Option<Vec3<f64>> {
        match self.gravity {
            ResolvedGravity::None => None,
            ResolvedGravity::Constant(g) => Some(Vec3(g)),
            ResolvedGravity::Input => input.map(Vec3),
        }
    }
    /// The reduced model with values for the input payloads (one per entry
    /// of [`input_payloads`](Self::input_payloads), in order) added to their
    /// bodies: what a scene with these payloads as constants gives.
    pub fn model_with_payloads(&self, values: &[PayloadInertia]) -> Result<Model, SceneError> {
        if values.len() != self.input_payloads.len() {
            return Err(SceneError::PayloadSpec {
                link: self.input_payloads.iter().map(|p| p.link.as_str()).collect::<Vec<_>>().join(", "),
                why: "the number of payload values differs from the number of input payloads",
            });
        }
        let mut model = self.model.clone();
        for (p, v) in self.input_payloads.iter().zip(values) {
            v.check(&p.link)?;
            match p.body {
                Some(b) => model.bodies[b].inertia = model.bodies[b].inertia.add(&p.inertia_in_body(v)),
                None if model.is_floating() => model.base_inertia = model.base_inertia.add(&p.inertia_in_body(v)),
                None => {}
            }
        }
        Ok(model)
    }
}

/// What the scene does with an original body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Fate {
    /// Kept, its joint moving.
    Moving,
    /// On a kept path, its joint locked: merged into its parent.
    Locked,
    /// Below a tip: merged into the tip's body.
    BelowTip,
    /// The sub-tree root's body: part of the new base.
    Base,
    /// An ancestor of the root's body.
    Above,
    /// Neither below the root nor above it.
    Outside,
    /// Below the root, but off the paths to the tips.
    Dropped,
}

impl Fate {
    fn kept(self) -> bool {
        matches!(self, Fate::Moving | Fate::Locked | Fate::BelowTip)
    }
    fn why(self) -> &'static str {
        match self {
            Fate::Moving | Fate::Locked => "kept",
            Fate::BelowTip => "merged into a tip's body",
            Fate::Base | Fate::Above => "above the sub-tree root",
            Fate::Outside => "outside the sub-tree",
            Fate::Dropped => "on a branch the sub-tree drops",
        }
    }
}

pub(super) fn apply(scene: &Scene, model: &Model) -> Result<SceneModel, SceneError> {
    scene.check()?;
    let n = model.bodies.len();
    // the body of a named joint; a mimic joint has no lock, armature or
    // friction of its own (its master's move it)
    let joint_index = |what: &'static str, name: &str| {
        let b =
            model.joint_body_index(name).ok_or_else(|| SceneError::UnknownJoint { what, name: name.to_string() })?;
        match model.mimic(b) {
            Some(m) => Err(SceneError::MimicJoint {
                joint: name.to_string(),
                master: model.bodies[m.master].joint.name.clone(),
                why: format!("it has no {what} of its own; give the {what} to its master"),
            }),
            None => Ok(b),
        }
    };
    let frame_index = |what: &'static str, name: &str| {
        model.frame_index(name).ok_or_else(|| SceneError::UnknownLink { what, name: name.to_string() })
    };

    let mut lock: Vec<Option<f64>> = vec![None; n];
    for (j, q) in &scene.locks {
        lock[joint_index("lock", j)?] = Some(*q);
    }
    // Every body's position where the scene fixes it: its lock, else zero;
    // a mimic joint's from its master's (so a locked master locks it).
    let fixed_at: Vec<f64> = (0..n)
        .map(|b| match model.mimic(b) {
            Some(m) => m.multiplier * lock[m.master].unwrap_or(0.0) + m.offset,
            None => lock[b].unwrap_or(0.0),
        })
        .collect();
    for b in 0..n {
        if model.mimic(b).is_some_and(|m| lock[m.master].is_some()) {
            lock[b] = Some(fixed_at[b]);
        }
    }
    // Armature, viscous and Coulomb coefficients by original joint.
    let mut coef = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let mut named: Vec<(usize, &'static str, &str)> = Vec::new();
    for (k, (what, list)) in scene.coefficients().into_iter().enumerate() {
        for (j, x) in list {
            let i = joint_index(what, j)?;
            coef[k][i] = *x;
            named.push((i, what, j));
        }
    }

    // The fate of every body.
    let root_frame = match &scene.subtree {
        Some(st) => frame_index("sub-tree root", &st.root)?,
        None => frame_index("the model's root", &model.root)?,
    };
    let br = model.frames[root_frame].body;
    // A floating base stays floating when the sub-tree root is its root
    // link; a sub-tree rooted anywhere else is a fixed-base robot (see the
    // module docs).
    let floating = model.is_floating() && model.frames[root_frame].name == model.root;
    let mut fate: Vec<Fate> = (0..n).map(|i| if lock[i].is_some() { Fate::Locked } else { Fate::Moving }).collect();
    if let Some(st) = &scene.subtree {
        let mut on_path = vec![false; n];
        let mut is_tip = vec![false; n];
        for tip in &st.tips {
            let t = frame_index("sub-tree tip", tip)?;
            let bt = match model.frames[t].body {
                Some(bt) if Some(bt) != br && br.is_none_or(|r| model.is_in_subtree(r, bt)) => bt,
                _ => return Err(SceneError::TipNotBelowRoot { tip: tip.clone(), root: st.root.clone() }),
            };
            is_tip[bt] = true;
            let mut b = Some(bt);
            while let Some(i) = b {
                if Some(i) == br {
                    break;
                }
                on_path[i] = true;
                b = model.bodies[i].parent;
            }
        }
        for b in 0..n {
            fate[b] = if Some(b) == br {
                Fate::Base
            } else if br.is_some_and(|r| model.is_in_subtree(b, r)) {
                Fate::Above
            } else if !br.is_none_or(|r| model.is_in_subtree(r, b)) {
                Fate::Outside
            } else if on_path[b] {
                fate[b]
            } else {
                match model.bodies[b].parent {
                    Some(p) if is_tip[p] || fate[p] == Fate::BelowTip => Fate::BelowTip,
                    _ => Fate::Dropped,
                }
            };
        }
    }
    for &(i, what, j) in &named {
        if !matches!(fate[i], Fate::Moving | Fate::Locked) {
            return Err(SceneError::RemovedJointParameter { joint: j.to_string(), what, why: fate[i].why() });
        }
    }
    mimic_fates(model, &mut fate, &mut lock, &fixed_at)?;
    // Whether an original frame is in the reduced model, or why not.
    let frame_kept = |f: usize| -> Result<(), &'static str> {
        let body = model.frames[f].body;
        if f == root_frame || body == br {
            return Ok(());
        }
        match body {
            Some(b) if fate[b].kept() => Ok(()),
            Some(b) => Err(fate[b].why()),
            None => Err(Fate::Above.why()),
        }
    };
    let check_frame = |what: &'static str, name: &str| -> Result<(), SceneError> {
        let f = frame_index(what, name)?;
        frame_kept(f).map_err(|why| SceneError::LinkNotInScene { what, link: name.to_string(), why })
    };
    if let Some(tip) = &scene.tip_wrench {
        check_frame("tip wrench", tip)?;
    }
    for p in &scene.payloads {
        check_frame("payload", &p.link)?;
    }
    let left_out_frames: Vec<(String, &'static str)> = (0..model.frames.len())
        .filter_map(|f| frame_kept(f).err().map(|why| (model.frames[f].name.clone(), why)))
        .collect();

    let mut warnings = Vec::new();
    if model.is_floating() && !floating {
        warnings.push(SceneWarning::SubTreeOffFloatingBase {
            root: model.frames[root_frame].name.clone(),
            base: model.root.clone(),
        });
    }
    for b in 0..n {
        let parent_dropped = model.bodies[b].parent.is_some_and(|p| fate[p] == Fate::Dropped);
        if fate[b] == Fate::Dropped && !parent_dropped {
            let links = (b..n).filter(|&j| model.is_in_subtree(b, j)).map(|j| model.bodies[j].name.clone()).collect();
            warnings.push(SceneWarning::DroppedBranch { joint: model.bodies[b].joint.name.clone(), links });
        }
        let locked_by_scene = lock[b].is_some() && model.mimic(b).is_none();
        if locked_by_scene && matches!(fate[b], Fate::Dropped | Fate::Outside) {
            warnings.push(SceneWarning::LockOnDroppedJoint { joint: model.bodies[b].joint.name.clone() });
        }
    }

    // Gravity in the root's frame, with the joints above it at their lock
    // positions or zero (a mimic joint where its master puts it; a floating
    // base's in the world, as given; a sub-tree rooted below one sees the
    // base as it is at q = 0).
    let q0: Vec<f64> = (0..model.dof()).map(|k| fixed_at[model.joint_body(k)]).collect();
    let mut ws = Workspace::<f64>::new(model);
    kinematics::forward_kinematics(model, &mut ws, &q0);
    let root_rot = kinematics::frame_pose(model, &ws, root_frame).rot;
    let to_root = |g: [f64; 3]| if floating { g } else { root_rot.tr_mul_vec(&Vec3(g)).0 };
    let gravity = match scene.gravity {
        Gravity::Default => ResolvedGravity::Constant(to_root(model.gravity.0)),
        Gravity::Constant(g) => ResolvedGravity::Constant(to_root(g)),
        Gravity::None => ResolvedGravity::None,
        Gravity::Input => ResolvedGravity::Input,
    };

    // The reduced description.
    let root_name = model.frames[root_frame].name.clone();
    let from_root = model.frames[root_frame].placement.inverse();
    let mut desc = RobotDescription {
        name: model.name.clone(),
        links: Vec::new(),
        joints: Vec::new(),
        gravity: Some(match gravity {
            ResolvedGravity::Constant(g) => g,
            _ => [0.0; 3],
        }),
    };
    let base_inertial = match br {
        Some(b) => inertial_of(&from_root.inertia_to_parent(&model.bodies[b].inertia)),
        // the floating base's own inertia (on a fixed base it moves nothing)
        None if floating => inertial_of(&from_root.inertia_to_parent(&model.base_inertia)),
        None => None,
    };
    desc.links.push(LinkDescription::new(&root_name, base_inertial));
    let mut used_names: HashSet<String> = model.bodies.iter().map(|b| b.joint.name.clone()).collect();
    let (mut fixed_joints, mut removed_joints, mut dropped_links) = (Vec::new(), Vec::new(), Vec::new());
    for (b, body) in model.bodies.iter().enumerate() {
        match fate[b] {
            Fate::Moving | Fate::Locked | Fate::BelowTip => {}
            Fate::Base | Fate::Above => {
                removed_joints.push(body.joint.name.clone());
                continue;
            }
            Fate::Outside | Fate::Dropped => {
                removed_joints.push(body.joint.name.clone());
                dropped_links.push(body.name.clone());
                continue;
            }
        }
        desc.links.push(LinkDescription::new(&body.name, inertial_of(&body.inertia)));
        let on_root = body.parent == br;
        let parent = match body.parent {
            Some(p) if !on_root => model.bodies[p].name.clone(),
            _ => root_name.clone(),
        };
        let moving = fate[b] == Fate::Moving;
        let x = if moving {
            body.joint.placement
        } else {
            let q = fixed_at[b];
            fixed_joints.push((body.joint.name.clone(), q));
            joint_transform::<f64>(&body.joint, q)
        };
        let joint_type = match (moving, body.joint.kind) {
            (false, _) => JointType::Fixed,
            (true, JointKind::Revolute) => JointType::Revolute,
            (true, JointKind::Continuous) => JointType::Continuous,
            (true, JointKind::Prismatic) => JointType::Prismatic,
        };
        desc.joints.push(JointDescription {
            name: body.joint.name.clone(),
            joint_type,
            parent,
            child: body.name.clone(),
            origin: if on_root { from_root.compose(&x) } else { x },
            axis: body.joint.axis,
            // a joint whose angle is q (a URDF joint's) stays one
            axis_is_direction: body.joint.axis_norm == 1.0,
            limits: body.joint.limits,
            mimic: model.mimic(b).filter(|_| moving).map(|m| MimicDescription {
                joint: model.bodies[m.master].joint.name.clone(),
                multiplier: m.multiplier,
                offset: m.offset,
            }),
            file_origin: None,
            file_axis: None,
        });
    }
    // Every other kept frame, as a massless link fixed where it was.
    for (f, frame) in model.frames.iter().enumerate() {
        if f == root_frame || frame_kept(f).is_err() {
            continue;
        }
        let (parent, origin) = match frame.body {
            b if b == br => (root_name.clone(), from_root.compose(&frame.placement)),
            Some(b) if frame.name == model.bodies[b].name => continue, // the body's own link
            Some(b) => (model.bodies[b].name.clone(), frame.placement),
            None => continue,
        };
        desc.links.push(LinkDescription::new(&frame.name, None));
        let mut jname = format!("{}_fixed", frame.name);
        while !used_names.insert(jname.clone()) {
            jname.push('_');
        }
        let mut j = JointDescription::fixed(&jname, &parent, &frame.name);
        j.origin = origin;
        desc.joints.push(j);
    }
    // Constant payloads, folded into their links.
    let link_index: HashMap<String, usize> = desc.links.iter().enumerate().map(|(i, l)| (l.name.clone(), i)).collect();
    for p in &scene.payloads {
        if let PayloadValue::Constant(v) = &p.value {
            // Checked above: every kept frame is a link of the description.
            let Some(&li) = link_index.get(&p.link) else { continue };
            let link = &mut desc.links[li];
            let total = inertia_of(link.inertial.as_ref()).add(&Inertia::from_mass_com_inertia(
                v.mass,
                Vec3(v.com),
                Sym3(v.inertia),
            ));
            link.inertial = inertial_of(&total);
        }
    }

    // A scene that reduces nothing keeps the model as it is, bit for bit:
    // rebuilding it from the description would round its constants anew.
    let reduces = scene.subtree.is_some()
        || !scene.locks.is_empty()
        || scene.payloads.iter().any(|p| matches!(p.value, PayloadValue::Constant(_)));
    let reduced = if reduces {
        // a non-physical inertia the model was loaded with stays accepted
        let nonphysical = model.warnings.iter().any(|w| matches!(w, ModelWarning::NonPhysicalInertia { .. }));
        let m = Model::from_description_with(&desc, &BuildOptions::default().allow_nonphysical_inertia(nonphysical))?;
        if floating {
            m.with_floating_base()
        } else {
            m
        }
    } else {
        let mut m = model.clone();
        m.gravity = Vec3(desc.gravity.unwrap_or([0.0; 3]));
        m
    };
    let mut input_payloads = Vec::new();
    for p in &scene.payloads {
        let frame = reduced.frame_index(&p.link).ok_or_else(|| SceneError::LinkNotInScene {
            what: "payload",
            link: p.link.clone(),
            why: "merged away",
        })?;
        let body = reduced.frames[frame].body;
        if body.is_none() && !floating {
            warnings.push(SceneWarning::PayloadOnBase { link: p.link.clone() });
        }
        if p.value == PayloadValue::Input {
            input_payloads.push(InputPayload {
                link: p.link.clone(),
                frame,
                body,
                placement: reduced.frames[frame].placement,
            });
        }
    }
    let tip_wrench_frame = scene.tip_wrench.as_ref().and_then(|t| reduced.frame_index(t));
    if let (Some(f), Some(link)) = (tip_wrench_frame, &scene.tip_wrench) {
        if reduced.frames[f].body.is_none() && !floating {
            warnings.push(SceneWarning::TipWrenchOnBase { link: link.clone() });
        }
    }
    let per_joint = |k: usize| -> Vec<f64> {
        reduced.joint_names().iter().map(|j| model.joint_body_index(j).map_or(0.0, |i| coef[k][i])).collect()
    };
    Ok(SceneModel {
        armature: per_joint(0),
        viscous_friction: per_joint(1),
        coulomb_friction: per_joint(2),
        model: reduced,
        scene: scene.clone(),
        gravity,
        tip_wrench_frame,
        coulomb_velocity: scene.coulomb_velocity,
        input_payloads,
        left_out_frames,
        fixed_joints,
        removed_joints,
        dropped_links,
        warnings,
    })
}

/// What a scene makes of the mimic joints: a mimic joint whose master is
/// fixed (locked, above the root, or merged below a tip) is fixed too, at
/// its position there (`lock`, from `fixed_at`); one that stays while its
/// master is dropped, or is merged rigidly while its master moves, is an
/// error naming both.
fn mimic_fates(model: &Model, fate: &mut [Fate], lock: &mut [Option<f64>], fixed_at: &[f64]) -> Result<(), SceneError> {
    for b in 0..model.bodies.len() {
        let Some(m) = model.mimic(b) else { continue };
        let names = || (model.bodies[b].joint.name.clone(), model.bodies[m.master].joint.name.clone());
        match (fate[m.master], fate[b]) {
            (_, Fate::Base | Fate::Above | Fate::Outside | Fate::Dropped) => {}
            (Fate::Moving, Fate::BelowTip) => {
                let (joint, master) = names();
                return Err(SceneError::MimicJoint {
                    joint,
                    master,
                    why: "the sub-tree merges it rigidly below a tip, but its master moves: lock the master, or list \
                          a tip below the mimic joint"
                        .to_string(),
                });
            }
            (Fate::Outside | Fate::Dropped, _) => {
                let (joint, master) = names();
                return Err(SceneError::MimicJoint {
                    joint,
                    master,
                    why: format!(
                        "the sub-tree keeps it but not its master (which is {}): lock the master, or keep it by \
                         listing a tip below it",
                        fate[m.master].why()
                    ),
                });
            }
            (Fate::Moving, _) => {}
            (Fate::Locked | Fate::BelowTip | Fate::Base | Fate::Above, Fate::Moving) => {
                fate[b] = Fate::Locked;
                lock[b] = Some(fixed_at[b]);
            }
            (Fate::Locked | Fate::BelowTip | Fate::Base | Fate::Above, _) => {}
        }
    }
    Ok(())
}

/// A link's inertial as a spatial inertia in the link's frame.
fn inertia_of(i: Option<&Inertial>) -> Inertia<f64> {
    match i {
        Some(i) => Inertia::from_mass_com_inertia(i.mass, i.origin.trans, i.inertia.rotate(&i.origin.rot)),
        None => Inertia::zero(),
    }
}

/// A spatial inertia as an inertial (mass, centre of mass, inertia about
/// it), `None` when it is zero. Rounding in the shift to the centre of mass
/// is cleaned up, so that a point mass stays a point mass and a valid
/// inertia stays positive semi-definite.
fn inertial_of(i: &Inertia<f64>) -> Option<Inertial> {
    if i.mass == 0.0 && i.h.0.iter().chain(&i.ibar.0).all(|&x| x == 0.0) {
        return None;
    }
    let Some(com) = i.com() else {
        return Some(Inertial { mass: 0.0, origin: Transform::identity(), inertia: i.ibar });
    };
    let scale = i.ibar.0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut ic = i.inertia_at_com();
    for x in ic.0.iter_mut() {
        if x.abs() <= 1e-13 * scale {
            *x = 0.0;
        }
    }
    let low = ic.eigenvalues()[0];
    if low < 0.0 && -low <= 1e-12 * scale {
        for x in &mut ic.0[..3] {
            *x -= low;
        }
    }
    Some(Inertial { mass: i.mass, origin: Transform::translation(com), inertia: ic })
}
