//! URDF import: dynagen's own reading of the raw XML, then urdf-rs, then the
//! checks every description goes through.
//!
//! urdf-rs 0.10 loses information dynagen needs, so the XML is read once by
//! [`precheck`] (with quick-xml, which urdf-rs already depends on) before
//! urdf-rs sees it:
//!
//! - its vectors keep only the tokens that parse as numbers, so
//!   `xyz="1 2 abc 4"` becomes (1, 2, 4) and `xyz="0 0 1x 1"` (0, 0, 1)
//!   without a word; it accepts `nan`, `inf` and `1e400` (infinite) in
//!   origins, axes, masses and inertias, and in limits before URDF 1.2;
//! - a link without `<inertial>` reads as mass 0 with zero inertia, and a
//!   joint without `<limit>` as limits (0, 0, 0, 0): absent and zero look
//!   the same;
//! - it does not check that the root element is `<robot>`, and ignores a
//!   second root element;
//! - its errors for a missing attribute or element ("missing field
//!   `parent`") do not say which link or joint;
//! - it recurses once per level of nesting, so a deeply nested document
//!   overflows the stack.
//!
//! The pre-check refuses each of these with an error that names the link or
//! joint, the attribute and the text; what urdf-rs then reads is only used
//! for what the pre-check has vouched for, `<mimic>` included (its joint
//! required, multiplier and offset finite, 1 and 0 when absent).
//!
//! urdf-rs is given only what dynagen reads: the links without their
//! visuals and collisions, and the joints. So what urdfdom and Pinocchio
//! load and dynagen has no use for cannot stop it (a `<material>` inside a
//! `<geometry>`, as in PyBullet's racecar; a visual's mesh scale that does
//! not parse; a transmission). Where urdf-rs still refuses something (a
//! joint's `<dynamics damping="abc">`), the error gives the line, the
//! column and the link or joint, found by giving urdf-rs each alone.

use super::description::{
    Inertial, JointDescription, JointLimits, JointType, LinkDescription, MimicDescription, RobotDescription,
};
use super::urdf_decimals::{self as decimals, InertialDecimals, RawInertial};
use super::{BuildOptions, Model, ModelError, ModelWarning};
use crate::spatial::{Mat3, Sym3, Transform, Vec3};
use crate::DoubleDouble;
use quick_xml::events::{BytesStart, Event};
use std::path::Path;

/// Elements may nest at most this deep (`<robot><link><visual><geometry>
/// <mesh>` is 5): urdf-rs and the XML crates under it recurse per level.
const MAX_NESTING: usize = 64;

/// What the pre-check learnt, in part what urdf-rs does not say, and in
/// part to check that urdf-rs read the same document.
#[derive(Debug, Default)]
struct RawFacts {
    /// The `<link>` children of `<robot>`, in file order.
    links: Vec<RawLink>,
    /// The `<joint>` children of `<robot>`, in file order.
    joints: Vec<RawJoint>,
    /// Every child element of `<robot>`: its byte range, what it is, and
    /// whether urdf-rs is given it (links and joints only).
    children: Vec<Child>,
    /// Byte ranges urdf-rs is not given inside links: `<visual>` and
    /// `<collision>`, which dynagen does not read.
    skipped: Vec<(usize, usize)>,
}

/// A child element of `<robot>` as the pre-check found it.
#[derive(Debug)]
struct Child {
    start: usize,
    end: usize,
    /// `link "name"`, `joint "name"` or `<element>`.
    item: String,
    /// A link or a joint (given to urdf-rs); anything else (materials,
    /// transmissions, gazebo extensions) dynagen does not read.
    read: bool,
}

impl RawFacts {
    /// The document urdf-rs reads: the links (without visuals and
    /// collisions) and joints, in the `<robot>` element as written. What
    /// dynagen does not use cannot then stop it: a `<material>` inside a
    /// `<geometry>` (PyBullet's racecar), a visual's unreadable mesh scale,
    /// a transmission's unknown element; urdfdom and Pinocchio load those.
    fn filtered(&self, xml: &str) -> String {
        let mut cut: Vec<(usize, usize)> = self
            .children
            .iter()
            .filter(|c| !c.read)
            .map(|c| (c.start, c.end))
            .chain(self.skipped.iter().copied())
            .collect();
        cut.sort_unstable();
        let mut out = String::with_capacity(xml.len());
        let mut at = 0;
        for (start, end) in cut {
            if start >= at {
                out.push_str(&xml[at..start]);
                at = end;
            }
        }
        out.push_str(&xml[at..]);
        out
    }

    /// An error of urdf-rs with its place: the first child of `<robot>`
    /// that urdf-rs refuses on its own, by line, column and name.
    fn locate(&self, xml: &str, error: &urdf_rs::UrdfError) -> ModelError {
        let why = error.to_string();
        let why = why.strip_prefix("custom: ").unwrap_or(&why);
        for c in self.children.iter().filter(|c| c.read) {
            let inside: Vec<(usize, usize)> = self
                .skipped
                .iter()
                .filter(|&&(s, e)| s >= c.start && e <= c.end)
                .map(|&(s, e)| (s - c.start, e - c.start))
                .collect();
            let text = RawFacts { skipped: inside, ..Default::default() }.filtered(&xml[c.start..c.end]);
            if let Err(e) = urdf_rs::read_from_string(&format!("<robot name=\"r\">{text}</robot>")) {
                let why = e.to_string();
                let why = why.strip_prefix("custom: ").unwrap_or(&why).to_string();
                let (line, column) = line_column(xml, c.start);
                return ModelError::Urdf(format!("line {line} column {column}: {}: {why}", c.item));
            }
        }
        ModelError::Urdf(why.to_string())
    }
}

/// The line and column (both from 1, the column in characters) of a byte offset.
fn line_column(xml: &str, pos: usize) -> (usize, usize) {
    let before = &xml[..pos.min(xml.len())];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (before.matches('\n').count() + 1, before[line_start..].chars().count() + 1)
}

/// A `<link>` as the pre-check read it.
#[derive(Debug, Default)]
struct RawLink {
    name: String,
    has_inertial: bool,
    /// The `<inertial>` from the file's decimals.
    file_inertial: Option<RawInertial>,
}

/// A `<joint>` as the pre-check read it.
#[derive(Debug, Default)]
struct RawJoint {
    name: String,
    joint_type: String,
    parent: String,
    child: String,
    has_limit: bool,
    /// The `<mimic>` element, with URDF's defaults (multiplier 1, offset 0).
    mimic: Option<MimicDescription>,
    /// The `<origin>` and `<axis>` from the file's decimals.
    file_origin: Option<Transform<DoubleDouble>>,
    file_axis: Option<[DoubleDouble; 3]>,
}

/// The URDF joint types, as urdf-rs spells them.
const JOINT_TYPES: [&str; 7] = ["revolute", "continuous", "prismatic", "fixed", "floating", "planar", "spherical"];

/// The element being read, as far as the pre-check cares.
enum Ctx {
    Robot,
    Link,
    Joint,
    Inertial,
    /// An element whose attributes the pre-check reads (`<origin>`,
    /// `<mass>`, ...), in a joint (`true`) or a link: it must not have child
    /// elements, which serde-xml-rs could read in place of an attribute.
    Leaf(&'static str, bool),
    /// Anything else (visuals, collisions, extensions): not looked into.
    Other,
}

/// The state of the `<link>` being read.
#[derive(Default)]
struct LinkState {
    item: String,
    name: String,
    inertial: bool,
    origin: bool,
    mass: bool,
    inertia: bool,
    file: InertialDecimals,
}

/// The state of the `<joint>` being read.
#[derive(Default)]
struct JointState {
    item: String,
    name: String,
    joint_type: String,
    origin: bool,
    axis: bool,
    limit: bool,
    parent: Option<String>,
    child: Option<String>,
    mimic: Option<MimicDescription>,
    file_origin: Option<Transform<DoubleDouble>>,
    file_axis: Option<[DoubleDouble; 3]>,
}

/// Reads the attributes of an element as (local name, unescaped value).
fn attributes(
    e: &BytesStart<'_>,
    reader: &quick_xml::Reader<&[u8]>,
    xml: &str,
) -> Result<Vec<(String, String)>, ModelError> {
    let mut out = Vec::new();
    for a in e.attributes().with_checks(true) {
        let a = a.map_err(|err| malformed(xml, reader, &err.to_string()))?;
        let key = String::from_utf8_lossy(a.key.local_name().as_ref()).into_owned();
        let value =
            a.decode_and_unescape_value(reader.decoder()).map_err(|err| malformed(xml, reader, &err.to_string()))?;
        out.push((key, value.into_owned()));
    }
    Ok(out)
}

/// The line (1-based) of a byte offset.
fn line_of(xml: &str, pos: u64) -> usize {
    let pos = usize::try_from(pos).unwrap_or(usize::MAX).min(xml.len());
    xml.as_bytes()[..pos].iter().filter(|&&b| b == b'\n').count() + 1
}

fn malformed(xml: &str, reader: &quick_xml::Reader<&[u8]>, why: &str) -> ModelError {
    ModelError::Urdf(format!("line {}: {why}", line_of(xml, reader.buffer_position())))
}

/// Parses `text` as exactly `N` finite numbers separated by white space.
fn numbers<const N: usize>(item: &str, what: &str, text: &str) -> Result<[f64; N], ModelError> {
    let bad = || ModelError::BadNumber { item: item.to_string(), what: what.to_string(), text: text.to_string() };
    let mut out = [0.0; N];
    let mut tokens = text.split_whitespace();
    for x in &mut out {
        *x = tokens.next().and_then(|t| t.parse::<f64>().ok()).filter(|x| x.is_finite()).ok_or_else(bad)?;
    }
    if tokens.next().is_some() {
        return Err(bad());
    }
    Ok(out)
}

fn get<'a>(attrs: &'a [(String, String)], key: &str) -> Option<&'a str> {
    attrs.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
}

/// Checks the numbers of an element: each of `keys` that is present must be
/// `N` finite numbers (every attribute with that local name, so a prefixed
/// duplicate cannot slip past); those in `required` must be present.
fn check_numbers<const N: usize>(
    attrs: &[(String, String)],
    item: &str,
    element: &str,
    keys: &[&str],
    required: &[&str],
) -> Result<(), ModelError> {
    for (k, v) in attrs {
        if keys.contains(&k.as_str()) {
            numbers::<N>(item, &format!("{element} {k}"), v)?;
        }
    }
    for k in required {
        if get(attrs, k).is_none() {
            return Err(ModelError::Urdf(format!("{item}: <{element}> has no {k} attribute")));
        }
    }
    Ok(())
}

/// Checks an `<origin>`: xyz and rpy three finite numbers each; from URDF
/// 1.1 on, `quat_xyzw` four, not all zero, and not together with rpy.
fn check_origin(attrs: &[(String, String)], item: &str, element: &str, version: (u32, u32)) -> Result<(), ModelError> {
    check_numbers::<3>(attrs, item, element, &["xyz", "rpy"], &[])?;
    if version >= (1, 1) {
        if let Some(q) = get(attrs, "quat_xyzw") {
            let v = numbers::<4>(item, &format!("{element} quat_xyzw"), q)?;
            if v.iter().all(|&x| x == 0.0) {
                return Err(ModelError::BadNumber {
                    item: item.to_string(),
                    what: format!("{element} quat_xyzw (a zero quaternion is no rotation)"),
                    text: q.to_string(),
                });
            }
            if get(attrs, "rpy").is_some() {
                return Err(ModelError::Urdf(format!("{item}: <{element}> has both rpy and quat_xyzw")));
            }
        }
    }
    Ok(())
}

/// The `version` attribute of `<robot>` as urdf-rs reads it: "major.minor",
/// anything else (or nothing) is 1.0.
fn urdf_version(attrs: &[(String, String)]) -> (u32, u32) {
    get(attrs, "version")
        .and_then(|v| {
            let (major, minor) = v.trim().split_once('.')?;
            Some((major.parse().ok()?, minor.parse().ok()?))
        })
        .unwrap_or((1, 0))
}

/// Reads the raw XML for what urdf-rs would lose or not name: every number
/// dynagen uses, the structure of links and joints, the root element and the
/// nesting depth.
fn precheck(xml: &str) -> Result<RawFacts, ModelError> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut facts = RawFacts::default();
    let mut stack: Vec<Ctx> = Vec::new();
    let mut names: Vec<String> = Vec::new();
    let mut seen_root = false;
    let mut version = (1, 0);
    let mut link = LinkState::default();
    let mut joint = JointState::default();
    // where the element being read started, for each open element
    let mut starts: Vec<usize> = Vec::new();
    loop {
        let before = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX);
        let event = reader.read_event().map_err(|e| malformed(xml, &reader, &e.to_string()))?;
        // RustyXML (which urdf-rs reads with) ends a processing instruction
        // at the first '>' after any '?', and a DOCTYPE at its first '>':
        // where that differs from the XML rules, the two readers would see
        // different elements.
        if matches!(event, Event::PI(_) | Event::Decl(_))
            && event.iter().skip_while(|&&b| b != b'?').any(|&b| b == b'>')
        {
            return Err(malformed(xml, &reader, "a processing instruction with '?' and then '>' inside"));
        }
        if matches!(event, Event::DocType(_)) && event.contains(&b'>') {
            return Err(malformed(xml, &reader, "a DOCTYPE with an internal subset"));
        }
        let (e, empty) = match event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                names.pop();
                let end = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX).min(xml.len());
                span(&mut facts, &stack, starts.pop().unwrap_or(0), end, &link, &joint);
                close(stack.pop(), &mut facts, &link, &joint)?;
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        if stack.len() >= MAX_NESTING {
            return Err(malformed(xml, &reader, &format!("elements nested more than {MAX_NESTING} deep")));
        }
        let name = String::from_utf8_lossy(e.local_name().as_ref()).into_owned();
        // only the attributes of elements the pre-check reads (visuals and
        // collisions are most of a file, and urdf-rs reads them anyway)
        let attrs = if matches!(stack.last(), None | Some(Ctx::Robot | Ctx::Joint | Ctx::Inertial)) {
            attributes(&e, &reader, xml)?
        } else {
            Vec::new()
        };
        let ctx = match stack.last() {
            None => {
                if seen_root {
                    return Err(malformed(xml, &reader, &format!("a second root element <{name}> after </robot>")));
                }
                seen_root = true;
                if name != "robot" {
                    return Err(ModelError::Urdf(format!("the root element is <{name}>, not <robot>")));
                }
                version = urdf_version(&attrs);
                Ctx::Robot
            }
            Some(Ctx::Robot) if name == "link" => {
                let n = facts.links.len() + 1;
                let name = match get(&attrs, "name") {
                    None => return Err(ModelError::Urdf(format!("link number {n} has no name attribute"))),
                    Some("") => return Err(ModelError::Urdf(format!("link number {n} has an empty name"))),
                    Some(s) => s.to_string(),
                };
                link = LinkState { item: format!("link \"{name}\""), name, ..Default::default() };
                Ctx::Link
            }
            Some(Ctx::Robot) if name == "joint" => {
                let n = facts.joints.len() + 1;
                let name = match get(&attrs, "name") {
                    None => return Err(ModelError::Urdf(format!("joint number {n} has no name attribute"))),
                    Some("") => return Err(ModelError::Urdf(format!("joint number {n} has an empty name"))),
                    Some(s) => s.to_string(),
                };
                let item = format!("joint \"{name}\"");
                let joint_type = match get(&attrs, "type") {
                    None => return Err(ModelError::Urdf(format!("{item} has no type attribute"))),
                    Some(t) if !JOINT_TYPES.contains(&t) => {
                        return Err(ModelError::Urdf(format!(
                            "{item}: unknown joint type \"{t}\" (URDF knows {})",
                            JOINT_TYPES.join(", ")
                        )))
                    }
                    Some(t) => t.to_string(),
                };
                joint = JointState { item, name, joint_type, ..Default::default() };
                Ctx::Joint
            }
            Some(Ctx::Link) if name == "inertial" => {
                once(&mut link.inertial, &link.item, "inertial")?;
                Ctx::Inertial
            }
            Some(Ctx::Inertial) => {
                let item = link.item.as_str();
                match name.as_str() {
                    "origin" => {
                        once(&mut link.origin, item, "inertial><origin")?;
                        check_origin(&attrs, item, "inertial origin", version)?;
                        link.file.origin = Some(decimals::origin(&attrs, version));
                        Ctx::Leaf("inertial><origin", false)
                    }
                    "mass" => {
                        once(&mut link.mass, item, "inertial><mass")?;
                        check_numbers::<1>(&attrs, item, "mass", &["value"], &["value"])?;
                        link.file.mass = get(&attrs, "value").and_then(decimals::decimals::<1>).map(|[m]| m);
                        Ctx::Leaf("mass", false)
                    }
                    "inertia" => {
                        once(&mut link.inertia, item, "inertial><inertia")?;
                        let keys = ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"];
                        check_numbers::<1>(&attrs, item, "inertia", &keys, &keys)?;
                        link.file.inertia = decimals::inertia(&attrs);
                        Ctx::Leaf("inertia", false)
                    }
                    _ => Ctx::Other,
                }
            }
            Some(Ctx::Joint) => {
                let item = joint.item.as_str();
                match name.as_str() {
                    "origin" => {
                        once(&mut joint.origin, item, "origin")?;
                        check_origin(&attrs, item, "origin", version)?;
                        joint.file_origin = decimals::origin(&attrs, version);
                        Ctx::Leaf("origin", true)
                    }
                    "axis" => {
                        once(&mut joint.axis, item, "axis")?;
                        check_numbers::<3>(&attrs, item, "axis", &["xyz"], &["xyz"])?;
                        joint.file_axis = get(&attrs, "xyz").and_then(decimals::decimals::<3>);
                        Ctx::Leaf("axis", true)
                    }
                    "limit" => {
                        once(&mut joint.limit, item, "limit")?;
                        // urdf-rs needs the velocity before URDF 1.2, and
                        // takes a missing one as infinite from 1.2 on.
                        let required: &[&str] = if version < (1, 2) { &["velocity"] } else { &[] };
                        check_numbers::<1>(&attrs, item, "limit", &["lower", "upper", "effort", "velocity"], required)?;
                        Ctx::Leaf("limit", true)
                    }
                    "mimic" => {
                        if joint.mimic.is_some() {
                            return Err(ModelError::Urdf(format!("{item} has more than one <mimic>")));
                        }
                        joint.mimic = Some(mimic_element(&attrs, item)?);
                        Ctx::Leaf("mimic", true)
                    }
                    "parent" | "child" => {
                        let (seen, role) =
                            if name == "parent" { (&mut joint.parent, "parent") } else { (&mut joint.child, "child") };
                        if seen.is_some() {
                            return Err(ModelError::Urdf(format!("{item} has more than one <{role}>")));
                        }
                        match get(&attrs, "link") {
                            None => return Err(ModelError::Urdf(format!("{item}: <{role}> has no link attribute"))),
                            Some(l) => *seen = Some(l.to_string()),
                        }
                        Ctx::Leaf(if role == "parent" { "parent" } else { "child" }, true)
                    }
                    _ => Ctx::Other,
                }
            }
            Some(&Ctx::Leaf(parent, in_joint)) => {
                let item = if in_joint { &joint.item } else { &link.item };
                return Err(ModelError::Urdf(format!("{item}: <{parent}> must not contain an element (<{name}>)")));
            }
            Some(_) => Ctx::Other,
        };
        stack.push(ctx);
        names.push(name);
        starts.push(before);
        if empty {
            names.pop();
            let end = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX).min(xml.len());
            span(&mut facts, &stack, starts.pop().unwrap_or(0), end, &link, &joint);
            close(stack.pop(), &mut facts, &link, &joint)?;
        }
    }
    if !seen_root {
        return Err(ModelError::Urdf("no <robot> element".into()));
    }
    if let Some(open) = names.last() {
        return Err(ModelError::Urdf(format!("the document ends inside <{open}>")));
    }
    Ok(facts)
}

/// Records the byte range of an element that ends, while `stack` still holds
/// it: a child of `<robot>`, or a visual or collision of a link.
fn span(facts: &mut RawFacts, stack: &[Ctx], start: usize, end: usize, link: &LinkState, joint: &JointState) {
    match stack {
        [Ctx::Robot, top] => {
            let (item, read) = match top {
                Ctx::Link => (link.item.clone(), true),
                Ctx::Joint => (joint.item.clone(), true),
                _ => (String::new(), false),
            };
            facts.children.push(Child { start, end, item, read });
        }
        [Ctx::Robot, Ctx::Link, Ctx::Other] => facts.skipped.push((start, end)),
        _ => {}
    }
}

/// A joint's `<mimic joint="..." multiplier="..." offset="..."/>`: the
/// master's name is required, the numbers default to URDF's 1 and 0.
fn mimic_element(attrs: &[(String, String)], item: &str) -> Result<MimicDescription, ModelError> {
    check_numbers::<1>(attrs, item, "mimic", &["multiplier", "offset"], &["joint"])?;
    let Some(joint) = get(attrs, "joint").filter(|j| !j.is_empty()) else {
        return Err(ModelError::Urdf(format!("{item}: <mimic> has an empty joint attribute")));
    };
    let number = |key: &str, default: f64| match get(attrs, key) {
        Some(text) => numbers::<1>(item, &format!("mimic {key}"), text).map(|[x]| x),
        None => Ok(default),
    };
    Ok(MimicDescription {
        joint: joint.to_string(),
        multiplier: number("multiplier", 1.0)?,
        offset: number("offset", 0.0)?,
    })
}

/// Marks an element seen, refusing a second one.
fn once(seen: &mut bool, item: &str, element: &str) -> Result<(), ModelError> {
    if std::mem::replace(seen, true) {
        return Err(ModelError::Urdf(format!("{item} has more than one <{element}>")));
    }
    Ok(())
}

/// What to check and record when an element ends.
fn close(ctx: Option<Ctx>, facts: &mut RawFacts, link: &LinkState, joint: &JointState) -> Result<(), ModelError> {
    match ctx {
        Some(Ctx::Link) => facts.links.push(RawLink {
            name: link.name.clone(),
            has_inertial: link.inertial,
            file_inertial: link.file.read(),
        }),
        Some(Ctx::Joint) => {
            let (Some(parent), Some(child)) = (&joint.parent, &joint.child) else {
                let role = if joint.parent.is_none() { "parent" } else { "child" };
                return Err(ModelError::Urdf(format!("{} has no <{role} link=\"...\"/>", joint.item)));
            };
            facts.joints.push(RawJoint {
                name: joint.name.clone(),
                joint_type: joint.joint_type.clone(),
                parent: parent.clone(),
                child: child.clone(),
                has_limit: joint.limit,
                mimic: joint.mimic.clone(),
                // a missing origin is the identity, a missing axis x (as urdf-rs reads them)
                file_origin: if joint.origin { joint.file_origin } else { Some(Transform::identity()) },
                file_axis: if joint.axis { joint.file_axis } else { Some([1.0, 0.0, 0.0].map(DoubleDouble::from)) },
            });
        }
        Some(Ctx::Inertial) => {
            for (seen, what) in [(link.mass, "mass value=\"...\""), (link.inertia, "inertia .../")] {
                if !seen {
                    return Err(ModelError::Urdf(format!("{}: <inertial> has no <{what}>", link.item)));
                }
            }
        }
        _ => {}
    }
    Ok(())
}

fn pose(p: &urdf_rs::Pose) -> Transform<f64> {
    Transform::new(Mat3::from_rpy(p.rpy[0], p.rpy[1], p.rpy[2]), Vec3(*p.xyz))
}

/// Converts a parsed URDF to a description, using what the pre-check found
/// for what urdf-rs cannot tell apart. Axes are normalised (as the URDF
/// specification requires and Pinocchio does); each normalisation is
/// returned as a warning.
fn description_from_urdf(
    robot: &urdf_rs::Robot,
    facts: &RawFacts,
) -> Result<(RobotDescription, Vec<ModelWarning>), ModelError> {
    // What urdf-rs read must be what the pre-check vouched for. They differ
    // only where RustyXML, under urdf-rs, misreads malformed XML.
    let differ = |what: String| {
        ModelError::Urdf(format!("the XML reads differently to urdf-rs and to dynagen ({what}): is it well-formed?"))
    };
    if robot.links.len() != facts.links.len() || robot.joints.len() != facts.joints.len() {
        return Err(differ(format!(
            "{} links and {} joints against {} and {}",
            robot.links.len(),
            robot.joints.len(),
            facts.links.len(),
            facts.joints.len()
        )));
    }
    for (l, raw) in robot.links.iter().zip(&facts.links) {
        if l.name != raw.name {
            return Err(differ(format!("link \"{}\" against \"{}\"", l.name, raw.name)));
        }
    }
    for (j, raw) in robot.joints.iter().zip(&facts.joints) {
        let joint_type = format!("{:?}", j.joint_type).to_lowercase();
        if (&j.name, &joint_type, &j.parent.link, &j.child.link, j.mimic.is_some())
            != (&raw.name, &raw.joint_type, &raw.parent, &raw.child, raw.mimic.is_some())
        {
            return Err(differ(format!("joint \"{}\" against \"{}\"", j.name, raw.name)));
        }
    }
    let mut warnings = Vec::new();
    let links = robot
        .links
        .iter()
        .zip(&facts.links)
        .map(|(l, raw)| {
            let i = &l.inertial;
            let inertia =
                Sym3([i.inertia.ixx, i.inertia.iyy, i.inertia.izz, i.inertia.ixy, i.inertia.ixz, i.inertia.iyz]);
            let inertial = raw.has_inertial.then(|| Inertial { mass: i.mass.value, origin: pose(&i.origin), inertia });
            let file_inertia = inertial.and_then(|i| decimals::file_inertial(raw.file_inertial, &i));
            LinkDescription { name: l.name.clone(), inertial, file_inertia }
        })
        .collect();
    let joints = robot
        .joints
        .iter()
        .zip(&facts.joints)
        .map(|(j, raw)| {
            let joint_type = match j.joint_type {
                urdf_rs::JointType::Revolute => JointType::Revolute,
                urdf_rs::JointType::Continuous => JointType::Continuous,
                urdf_rs::JointType::Prismatic => JointType::Prismatic,
                urdf_rs::JointType::Fixed => JointType::Fixed,
                urdf_rs::JointType::Floating => JointType::Floating,
                urdf_rs::JointType::Planar => JointType::Planar,
                urdf_rs::JointType::Spherical => JointType::Spherical,
            };
            let mut axis = Vec3(*j.axis.xyz);
            let norm = axis.norm();
            if joint_type != JointType::Fixed && norm.is_finite() && norm > 0.0 && (norm - 1.0).abs() > 1e-9 {
                warnings.push(ModelWarning::AxisNormalised { joint: j.name.clone(), norm });
                axis = if (1.0 / norm).is_finite() { axis.scale(1.0 / norm) } else { Vec3(axis.0.map(|x| x / norm)) };
            }
            let limits = (raw.has_limit && matches!(joint_type, JointType::Revolute | JointType::Prismatic)).then_some(
                JointLimits {
                    lower: j.limit.lower,
                    upper: j.limit.upper,
                    velocity: j.limit.velocity,
                    effort: j.limit.effort,
                },
            );
            let origin = pose(&j.origin);
            JointDescription {
                name: j.name.clone(),
                joint_type,
                parent: j.parent.link.clone(),
                child: j.child.link.clone(),
                origin,
                axis,
                axis_is_direction: true,
                limits,
                mimic: raw.mimic.clone(),
                file_origin: decimals::file_transform(raw.file_origin, &origin),
                file_axis: decimals::file_axis(raw.file_axis, &j.axis.xyz, &axis),
            }
        })
        .collect();
    Ok((RobotDescription { name: robot.name.clone(), links, joints, gravity: None }, warnings))
}

impl RobotDescription {
    /// Reads a URDF document as a description, without building the model
    /// (to inspect or edit it first), with the warnings of the import (axes
    /// normalised). A link without `<inertial>` has `inertial: None`, and a
    /// joint without `<limit>` has `limits: None`.
    pub fn from_urdf_str(xml: &str) -> Result<(RobotDescription, Vec<ModelWarning>), ModelError> {
        let facts = precheck(xml)?;
        let robot = urdf_rs::read_from_string(&facts.filtered(xml)).map_err(|e| facts.locate(xml, &e))?;
        description_from_urdf(&robot, &facts)
    }
}

impl Model {
    /// Reads a URDF document from a string.
    pub fn from_urdf_str(xml: &str) -> Result<Model, ModelError> {
        Self::from_urdf_str_with(xml, &BuildOptions::default())
    }

    /// Reads a URDF document from a string, with options.
    ///
    /// Every number dynagen uses (origins, axes, masses, inertias, limits)
    /// must be written in full as finite numbers, or the error
    /// [`ModelError::BadNumber`] names the link or joint, the attribute and
    /// the text. A link without `<inertial>` is massless.
    pub fn from_urdf_str_with(xml: &str, opts: &BuildOptions) -> Result<Model, ModelError> {
        let (desc, warnings) = RobotDescription::from_urdf_str(xml)?;
        let mut model = Model::from_description_with(&desc, opts)?;
        model.warnings.splice(0..0, warnings);
        Ok(model)
    }

    /// Reads a URDF file.
    pub fn from_urdf_file(path: impl AsRef<Path>) -> Result<Model, ModelError> {
        Self::from_urdf_file_with(path, &BuildOptions::default())
    }

    /// Reads a URDF file, with options.
    pub fn from_urdf_file_with(path: impl AsRef<Path>, opts: &BuildOptions) -> Result<Model, ModelError> {
        let path = path.as_ref();
        let xml =
            std::fs::read_to_string(path).map_err(|source| ModelError::Io { path: path.to_path_buf(), source })?;
        Self::from_urdf_str_with(&xml, opts)
    }
}
