//! From a checked description to a [`Model`]: the tree's topology, the
//! depth-first joint order, and fixed joints merged away.

use super::description::{JointDescription, JointType, LinkDescription, RobotDescription};
use super::file_values::{ExactAxis, FileInertia, FileTransform, FileValue, JointFileValues};
use super::{
    validate, AxisAlignment, Body, BuildOptions, Coupling, Frame, Joint, JointKind, Mimic, MimicJoints, Model,
    ModelError, ModelWarning, RootJoint, DEFAULT_GRAVITY,
};
use crate::spatial::{Inertia, Mat3, Sym3, Transform, Vec3};
use crate::DoubleDouble;
use std::collections::HashMap;

impl Model {
    /// Validates a description and builds the model, with default options.
    pub fn from_description(desc: &RobotDescription) -> Result<Model, ModelError> {
        Self::from_description_with(desc, &BuildOptions::default())
    }

    /// Validates a description and builds the model.
    ///
    /// Links attached by fixed joints are merged into the body they are
    /// fixed to (mass, centre of mass and inertia combined exactly), and
    /// every link is kept as a named [`Frame`].
    pub fn from_description_with(desc: &RobotDescription, opts: &BuildOptions) -> Result<Model, ModelError> {
        let mut warnings = Vec::new();
        validate::check(desc, opts, &mut warnings)?;

        let link_index: HashMap<&str, usize> =
            desc.links.iter().enumerate().map(|(i, l)| (l.name.as_str(), i)).collect();
        let mut parent_joint: Vec<Option<usize>> = vec![None; desc.links.len()];
        let mut child_joints: Vec<Vec<usize>> = vec![Vec::new(); desc.links.len()];
        for (ji, j) in desc.joints.iter().enumerate() {
            let c = link_index[j.child.as_str()];
            if let Some(first) = parent_joint[c] {
                return Err(ModelError::MultipleParents {
                    link: j.child.clone(),
                    first: desc.joints[first].name.clone(),
                    second: j.name.clone(),
                });
            }
            parent_joint[c] = Some(ji);
            child_joints[link_index[j.parent.as_str()]].push(ji);
        }
        let roots: Vec<usize> = (0..desc.links.len()).filter(|&l| parent_joint[l].is_none()).collect();
        let parent_link = |l: usize| parent_joint[l].map(|j| link_index[desc.joints[j].parent.as_str()]);
        let root = match roots[..] {
            [root] => root,
            // No root at all: every link has a parent, so the joints close a
            // cycle (links is not empty: validate::check refuses that).
            [] => return Err(ModelError::Cycle(cycle_above(0, &parent_link, desc))),
            _ => return Err(ModelError::MultipleRoots(roots.iter().map(|&r| desc.links[r].name.clone()).collect())),
        };
        let (root, world) = floating_root(desc, root, &child_joints, &link_index)?;

        // Depth-first walk from the root with an explicit stack (a long chain
        // must not overflow the call stack), children in file order. Every
        // pose and inertia is computed twice: in f64, and in double-double
        // from the file's values while every one on the way has them.
        let mut bodies: Vec<Body> = Vec::new();
        // the description's joint of each body
        let mut body_joint: Vec<usize> = Vec::new();
        let mut frames: Vec<Frame> = Vec::new();
        let mut base_mass = 0.0;
        // the base's inertia, then each body's: f64, and from the file's values
        let mut inertias: Vec<(Inertia<f64>, Option<Inertia<DoubleDouble>>)> = vec![(Inertia::zero(), exact_zero())];
        let mut visited = vec![false; desc.links.len()];
        if let Some(w) = world {
            visited[w] = true;
        }
        let identity = (Transform::identity(), Some(Transform::identity()));
        let mut stack: Vec<WalkEntry> = vec![WalkEntry { link: root, parent_body: None, pose: identity, moving: None }];
        while let Some(WalkEntry { link, parent_body, pose, moving }) = stack.pop() {
            visited[link] = true;
            let (body, pose) = match moving {
                Some(ji) => {
                    bodies.push(Body {
                        name: desc.links[link].name.clone(),
                        parent: parent_body,
                        joint: joint_from(&desc.joints[ji], pose),
                        inertia: Inertia::zero(),
                        file_inertia: None,
                    });
                    body_joint.push(ji);
                    inertias.push((Inertia::zero(), exact_zero()));
                    (Some(bodies.len() - 1), identity)
                }
                None => (parent_body, pose),
            };
            let l = &desc.links[link];
            let file_placement = pose.1.map(|p| Box::new(FileValue::new(pose.0, p)));
            frames.push(Frame { name: l.name.clone(), body, placement: pose.0, file_placement });
            let total = &mut inertias[body.map_or(0, |b| b + 1)];
            add_link_inertia(total, l, &pose);
            if body.is_none() {
                base_mass += l.inertial.map_or(0.0, |i| i.mass);
            }
            for &ji in child_joints[link].iter().rev() {
                let j = &desc.joints[ji];
                let moving = (j.joint_type != JointType::Fixed).then_some(ji);
                let file_origin = j.file_origin.as_ref().and_then(|f| f.value_for(&j.origin));
                let child_pose = (pose.0.compose(&j.origin), pose.1.zip(file_origin).map(|(p, o)| p.compose(o)));
                let parent_body = body;
                stack.push(WalkEntry { link: link_index[j.child.as_str()], parent_body, pose: child_pose, moving });
            }
        }
        let file_inertia = |(f64, exact): &(Inertia<f64>, Option<Inertia<DoubleDouble>>)| {
            exact.map(|e| Box::new(FileInertia::new(*f64, e)))
        };
        for (b, total) in bodies.iter_mut().zip(&inertias[1..]) {
            b.inertia = total.0;
            b.file_inertia = file_inertia(total);
        }
        let (base_inertia, file_base_inertia) = (inertias[0].0, file_inertia(&inertias[0]));
        // A link the walk did not reach has a parent (the one root was
        // reached), and so has that parent: going up from it must close a
        // cycle, apart from the tree.
        if let Some(l) = (0..desc.links.len()).find(|&l| !visited[l]) {
            return Err(ModelError::Cycle(cycle_above(l, &parent_link, desc)));
        }
        check_finite(&bodies, &frames, base_mass, &desc.links[root].name)?;
        let coupling = Coupling::new(&bodies, mimics(desc, opts, &bodies, &body_joint));

        let model = Model {
            name: desc.name.clone(),
            root: desc.links[root].name.clone(),
            bodies,
            frames,
            gravity: Vec3(desc.gravity.unwrap_or(DEFAULT_GRAVITY)),
            warnings,
            base_mass,
            root_joint: RootJoint::Fixed,
            base_inertia,
            coupling,
            file_base_inertia,
        };
        let mut model = model;
        let nonphysical = model.warnings.iter().any(|w| matches!(w, ModelWarning::NonPhysicalInertia { .. }));
        let more = check_every_joint_moves_mass(&model, nonphysical)?;
        model.warnings.extend(more);
        // a floating joint at the root floats the model, which checks its
        // inertia and its dependent joints with the base moving
        if world.is_some() {
            return Ok(model.with_floating_base());
        }
        let dependent = super::dependent::dependent_joints(&model);
        model.warnings.extend(dependent.into_iter().map(|joints| ModelWarning::DependentJoints { joints }));
        Ok(model)
    }
}

/// Each body's [`Mimic`] (with [`MimicJoints::Follow`]): its description's
/// `<mimic>`, the master found by name among the bodies' joints (checked by
/// `validate::check`: it exists, moves and follows no other).
fn mimics(desc: &RobotDescription, opts: &BuildOptions, bodies: &[Body], body_joint: &[usize]) -> Vec<Option<Mimic>> {
    body_joint
        .iter()
        .map(|&ji| match &desc.joints[ji].mimic {
            Some(m) if opts.mimic == MimicJoints::Follow => {
                let master = bodies.iter().position(|b| b.joint.name == m.joint).expect("a validated master moves");
                Some(Mimic { master, multiplier: m.multiplier, offset: m.offset })
            }
            _ => None,
        })
        .collect()
}

/// The root link and, when the root's joint is `floating`, the world link
/// above it: a URDF floats its robot by a `floating` joint from an empty
/// world link to the floating body, which then becomes the root. A
/// `floating` joint anywhere else, a world link with mass or other children,
/// or a floating joint with an origin (q holds the base's pose in the world
/// directly) is an error naming the joint.
fn floating_root(
    desc: &RobotDescription,
    root: usize,
    child_joints: &[Vec<usize>],
    link_index: &HashMap<&str, usize>,
) -> Result<(usize, Option<usize>), ModelError> {
    let mut floating = None;
    for (ji, j) in desc.joints.iter().enumerate() {
        if j.joint_type != JointType::Floating {
            continue;
        }
        let err = |why: String| Err(ModelError::Floating { joint: j.name.clone(), why });
        if link_index[j.parent.as_str()] != root {
            return err(format!(
                "a floating joint must connect the root link (\"{}\") to the floating body; this one is below it, under link \"{}\"",
                desc.links[root].name, j.parent
            ));
        }
        if child_joints[root].len() != 1 {
            return err(format!(
                "the root link \"{}\" of a floating joint is the world: it must carry nothing but this joint",
                desc.links[root].name
            ));
        }
        if desc.links[root].inertial.as_ref().is_some_and(|i| i.mass != 0.0) {
            return err(format!(
                "the root link \"{}\" of a floating joint is the world: it must have no mass",
                j.parent
            ));
        }
        if j.origin != Transform::identity() {
            return err("a floating joint's origin must be the identity (q holds the base's pose in the world)".into());
        }
        floating = Some(ji);
    }
    Ok(match floating {
        Some(ji) => (link_index[desc.joints[ji].child.as_str()], Some(root)),
        None => (root, None),
    })
}

/// The cycle met going up from link `start` through parents, each link of
/// which has a parent: its link names, from parent to child.
fn cycle_above(start: usize, parent_link: &dyn Fn(usize) -> Option<usize>, desc: &RobotDescription) -> Vec<String> {
    let mut position = vec![usize::MAX; desc.links.len()];
    let mut walk = Vec::new();
    let mut l = start;
    while position[l] == usize::MAX {
        position[l] = walk.len();
        walk.push(l);
        match parent_link(l) {
            Some(p) => l = p,
            None => break, // not reached when the caller is right
        }
    }
    let from = position[l].min(walk.len());
    walk[from..].iter().rev().map(|&l| desc.links[l].name.clone()).collect()
}

/// Finite numbers can combine into infinite ones (a long chain of huge
/// offsets, a huge mass far from its body's origin): refuse those too.
fn check_finite(bodies: &[Body], frames: &[Frame], base_mass: f64, root: &str) -> Result<(), ModelError> {
    for b in bodies {
        if !b.joint.placement.is_finite() {
            return Err(ModelError::NonFinite {
                item: format!("joint \"{}\"", b.joint.name),
                what: "placement (composed with the fixed joints above it)",
            });
        }
        let i = &b.inertia;
        if !(i.mass.is_finite() && i.h.is_finite() && i.ibar.is_finite()) {
            return Err(ModelError::NonFinite {
                item: format!("link \"{}\"", b.name),
                what: "spatial inertia (with the links fixed to it)",
            });
        }
    }
    for f in frames {
        if !f.placement.is_finite() {
            return Err(ModelError::NonFinite {
                item: format!("link \"{}\"", f.name),
                what: "placement in the body it is fixed to",
            });
        }
    }
    if !base_mass.is_finite() {
        return Err(ModelError::NonFinite { item: format!("link \"{root}\""), what: "mass fixed to the base" });
    }
    Ok(())
}

/// A pose in f64, and from the file's values when every pose composed into
/// it has them.
type Pose = (Transform<f64>, Option<Transform<DoubleDouble>>);

/// A link to visit in the walk over the tree.
struct WalkEntry {
    link: usize,
    /// The body it hangs from (`None`: the base).
    parent_body: Option<usize>,
    /// The link's pose in that body's frame.
    pose: Pose,
    /// The moving joint that starts a new body at this link.
    moving: Option<usize>,
}

fn exact_zero() -> Option<Inertia<DoubleDouble>> {
    Some(Inertia::zero())
}

/// Adds a link's inertia, at `pose` in its body's frame, to the body's
/// total (f64, and from the file's values while the pose has them). The
/// same formulas in both scalars. A link without its file's inertia (one
/// described in Rust) has exact f64 numbers: they are taken as they are.
fn add_link_inertia(total: &mut (Inertia<f64>, Option<Inertia<DoubleDouble>>), link: &LinkDescription, pose: &Pose) {
    let Some(inertial) = &link.inertial else { return };
    let at_com = inertial.inertia.rotate(&inertial.origin.rot);
    let at_link = Inertia::from_mass_com_inertia(inertial.mass, inertial.origin.trans, at_com);
    total.0 = total.0.add(&pose.0.inertia_to_parent(&at_link));
    let exact = link.file_inertia.as_ref().and_then(|f| f.value_for(inertial)).copied().unwrap_or_else(|| {
        let dd = DoubleDouble::from;
        let rot = Mat3(inertial.origin.rot.0.map(|row| row.map(dd)));
        let inertia = Sym3(inertial.inertia.0.map(dd));
        Inertia::from_mass_com_inertia(dd(inertial.mass), Vec3::from_f64(&inertial.origin.trans), inertia.rotate(&rot))
    });
    total.1 = match (total.1, pose.1) {
        (Some(sum), Some(p)) => Some(sum.add(&p.inertia_to_parent(&exact))),
        _ => None,
    };
}

fn joint_from(desc: &JointDescription, pose: Pose) -> Joint {
    let (placement, file_placement) = pose;
    let kind = match desc.joint_type {
        JointType::Revolute => JointKind::Revolute,
        JointType::Continuous => JointKind::Continuous,
        _ => JointKind::Prismatic,
    };
    let n = desc.axis.norm();
    // (x/n for a subnormal length, whose inverse overflows)
    let unit_axis = if (1.0 / n).is_finite() { desc.axis.scale(1.0 / n) } else { Vec3(desc.axis.0.map(|x| x / n)) };
    // A direction (URDF) turns by exactly q: its axis is the unit one and
    // its scale exactly 1, whatever ulp its length was off by.
    let (axis, axis_norm) = if desc.axis_is_direction { (unit_axis, 1.0) } else { (desc.axis, n) };
    let placement_rotation_is_identity = placement.rot == Mat3::identity();
    // The file's placement, unless its f64 rotation is the identity and the
    // file's is not (the algorithms then skip the rotation); the file's unit
    // axis, of a direction.
    let file_placement = file_placement
        .filter(|p| !placement_rotation_is_identity || p.rot == Mat3::identity())
        .map(|p| FileTransform::new(placement, p));
    // (an axis without the file's value, one given in Rust, is exact as it is)
    let file_axis = desc.file_axis.as_ref().and_then(|f| f.value_for(&desc.axis)).copied();
    let file_axis = file_axis.unwrap_or_else(|| Vec3::from_f64(&desc.axis));
    let file_axis = Some(FileValue::new(axis, ExactAxis::new(file_axis, desc.axis_is_direction)));
    let file_values = (file_placement.is_some() || file_axis.is_some())
        .then(|| Box::new(JointFileValues { placement: file_placement, axis: file_axis }));
    Joint {
        name: desc.name.clone(),
        kind,
        placement,
        axis,
        limits: desc.limits,
        unit_axis,
        axis_norm,
        alignment: AxisAlignment::of(&desc.axis),
        placement_rotation_is_identity,
        file_values,
    }
}

/// The error of a joint that moves no inertia, saying what to add to which
/// link: a mass where there is none, else inertia about the axis.
fn massless(b: &Body, mass: f64) -> ModelError {
    let link = &b.name;
    let fix = if mass > 0.0 {
        format!(
            "the {mass} kg it moves lie on its axis, without inertia about it: give link \"{link}\" a moment of \
             inertia about the joint's axis (URDF: the <inertia> of its <inertial>)"
        )
    } else {
        format!(
            "its child link \"{link}\" has no mass, nor has anything fixed to it or below it: give link \"{link}\" \
             a mass and an inertia (URDF: an <inertial> element), or fix a link with mass to it; if the joint moves \
             nothing, make it fixed"
        )
    };
    ModelError::MasslessSubtree { joint: b.joint.name.clone(), link: link.clone(), fix }
}

/// A joint whose subtree has no inertia along its motion gives a zero
/// diagonal in M(q): refuse it. Checked at q = 0 with the composite
/// inertia of each subtree, which is exact for a prismatic joint (its entry
/// is the subtree's mass, whatever q) and for a revolute joint whose own
/// body has inertia about the axis (that part turns with the axis, so it
/// does not depend on q) or whose subtree holds a body with a positive-
/// definite rotational inertia about its centre of mass (a moment of inertia
/// about any axis at all). Otherwise (point masses and rods moved by later
/// joints) the entry could vanish in another configuration: a warning names
/// the joint.
///
/// With non-physical inertias accepted (`nonphysical`), a diagonal entry
/// may be negative: that is what the warning about them says, not an
/// error (a zero one still is).
///
/// A joint that shares its column with mimic joints (a master, or a joint
/// that follows one) is checked as the column: M's diagonal entry at q = 0,
/// the motion of all of them together.
fn check_every_joint_moves_mass(model: &Model, nonphysical: bool) -> Result<Vec<ModelWarning>, ModelError> {
    let along = |ic: &Inertia<f64>, s: &[f64; 6]| {
        let a = Vec3([s[0], s[1], s[2]]);
        let l = Vec3([s[3], s[4], s[5]]);
        let f = ic.mul_motion(&crate::spatial::Motion::new(a, l));
        a.dot(&f.ang) + l.dot(&f.lin)
    };
    // Whether a body, then (summed up the tree below) its subtree, holds a
    // positive-definite rotational inertia about a centre of mass.
    let mut solid: Vec<bool> = model
        .bodies
        .iter()
        .map(|b| {
            let [lo, _, hi] = b.inertia.inertia_at_com().eigenvalues();
            b.inertia.mass > 0.0 && hi > 0.0 && lo > 1e-9 * hi
        })
        .collect();
    let mut warnings = Vec::new();
    let mut composite: Vec<Inertia<f64>> = model.bodies.iter().map(|b| b.inertia).collect();
    let coupled = coupled_columns(model);
    for i in (0..model.bodies.len()).rev() {
        let b = &model.bodies[i];
        let s = b.joint.motion_subspace();
        let ic = composite[i];
        let diag = along(&ic, &s);
        if !diag.is_finite() {
            return Err(ModelError::NonFinite {
                item: format!("joint \"{}\"", b.joint.name),
                what: "inertia moved by the joint (its subtree's)",
            });
        }
        if let Some(p) = b.parent {
            let moved = b.joint.placement.inertia_to_parent(&ic);
            composite[p] = composite[p].add(&moved);
            solid[p] |= solid[i];
        }
        if coupled[model.column(i)] {
            continue;
        }
        let negative_by_nonphysical_inertia = nonphysical && diag < 0.0;
        if diag.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) && !negative_by_nonphysical_inertia {
            return Err(massless(b, ic.mass));
        }
        let revolute = b.joint.kind != JointKind::Prismatic;
        let provably_positive = !revolute || along(&b.inertia, &s) > 0.0 || solid[i];
        if !provably_positive {
            warnings.push(ModelWarning::MassMatrixMayBeSingular { joint: b.joint.name.clone() });
        }
    }
    warnings.reverse();
    if coupled.iter().any(|&c| c) {
        check_coupled_columns(model, &coupled, nonphysical)?;
    }
    Ok(warnings)
}

/// Per column of the joint vectors: whether mimic joints share it.
fn coupled_columns(model: &Model) -> Vec<bool> {
    let mut coupled = vec![false; model.dof()];
    for i in 0..model.bodies.len() {
        if let Some(m) = model.mimic(i) {
            coupled[model.column(m.master)] = true;
        }
    }
    coupled
}

/// The diagonal of M at q = 0 in each column that mimic joints share: a
/// master and its followers that together move no mass are refused, naming
/// them all.
fn check_coupled_columns(model: &Model, coupled: &[bool], nonphysical: bool) -> Result<(), ModelError> {
    use crate::algorithms::{crba, Loads, Workspace};
    let n = model.dof();
    let mut m = vec![0.0; n * n];
    crba::crba(model, &mut Workspace::new(model), &vec![0.0; n], Loads::none(), &mut m);
    for (a, _) in coupled.iter().enumerate().filter(|(_, &c)| c) {
        let d = m[a * n + a];
        if d > 0.0 || (nonphysical && d < 0.0) {
            continue;
        }
        let master = &model.bodies[model.joint_body(a)];
        let followers: Vec<String> = (0..model.bodies.len())
            .filter(|&i| model.mimic(i).is_some() && model.column(i) == a)
            .map(|i| model.bodies[i].joint.name.clone())
            .collect();
        let fix = format!(
            "neither it nor the joints that follow it ({}) move anything with mass or inertia along their motion \
             (its link \"{}\" and theirs have none, nor has anything fixed to them or below them): give one of \
             these links a mass and an inertia (URDF: an <inertial> element)",
            super::quoted_names(&followers),
            master.name
        );
        return Err(ModelError::MasslessSubtree { joint: master.joint.name.clone(), link: master.name.clone(), fix });
    }
    Ok(())
}
