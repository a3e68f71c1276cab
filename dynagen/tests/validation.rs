//! Every way a robot description can be refused (each variant of
//! `ModelError`, from a small URDF, or from the builder or the Modern
//! Robotics lists where URDF cannot say it), each error's message naming the
//! link or joint; and what import and validation must get right when they
//! accept: fixed-joint merging, axis normalisation, joint order, frames.

mod support;

use dynagen::model::{
    BuildOptions, Inertial, JointDescription, JointType, ModernRoboticsLists, RobotBuilder, RobotDescription,
};
use dynagen::spatial::{Mat3, Transform, Vec3};
use dynagen::{Model, ModelError, ModelWarning, Robot};
use nalgebra::{DMatrix, DVector, Matrix3, Matrix4, Matrix6, Rotation3, Vector3};

// ---------------------------------------------------------------------------
// helpers

/// A unit-mass inertial with a physical inertia, as URDF.
const INERTIAL: &str =
    r#"<inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>"#;

fn robot(body: &str) -> String {
    format!(r#"<robot name="t">{body}</robot>"#)
}

/// `base` and a massive `arm` joined by the revolute joint `j`, with `extra`
/// inside `<joint>`.
fn one_joint(extra: &str) -> String {
    robot(&format!(
        r#"<link name="base"/><link name="arm">{INERTIAL}</link>
        <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>{extra}</joint>"#
    ))
}

/// `base` and the link `arm` with `inertial` inside it, joined by a
/// continuous joint.
fn one_link(inertial: &str) -> String {
    robot(&format!(
        r#"<link name="base"/><link name="arm">{inertial}</link>
        <joint name="j" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>"#
    ))
}

fn inertial(mass: &str, inertia: [&str; 6]) -> String {
    let [xx, xy, xz, yy, yz, zz] = inertia;
    format!(
        r#"<inertial><mass value="{mass}"/><inertia ixx="{xx}" ixy="{xy}" ixz="{xz}" iyy="{yy}" iyz="{yz}" izz="{zz}"/></inertial>"#
    )
}

fn err(xml: &str) -> ModelError {
    match Model::from_urdf_str(xml) {
        Ok(m) => panic!("accepted: {m:?}\n{xml}"),
        Err(e) => e,
    }
}

/// Asserts that the error's message names each of `names` (quoted, as the
/// messages write names).
fn names(e: &ModelError, names: &[&str]) {
    let msg = e.to_string();
    for n in names {
        assert!(msg.contains(&format!("\"{n}\"")) || msg.contains(n), "message {msg:?} does not name {n:?}");
    }
}

fn massive(name: &str) -> (String, Option<Inertial>) {
    (name.to_string(), Some(Inertial::new(1.0, [0.0, 0.0, 0.1], [0.1, 0.1, 0.1, 0.0, 0.0, 0.0])))
}

fn builder(links: &[(String, Option<Inertial>)], joints: Vec<JointDescription>) -> RobotBuilder {
    let mut b = RobotBuilder::new("t");
    for (n, i) in links {
        b = b.link(n, *i);
    }
    for j in joints {
        b = b.joint(j);
    }
    b
}

fn build_err(b: &RobotBuilder) -> ModelError {
    match b.build() {
        Ok(m) => panic!("accepted: {m:?}"),
        Err(e) => e,
    }
}

// ---------------------------------------------------------------------------
// reading the file

#[test]
fn io_error_names_the_file() {
    let e = Model::from_urdf_file("/nonexistent/dir/robot.urdf").unwrap_err();
    assert!(matches!(&e, ModelError::Io { path, .. } if path.ends_with("robot.urdf")));
    names(&e, &["/nonexistent/dir/robot.urdf"]);
}

#[test]
fn non_utf8_file_is_an_io_error() {
    let path = std::env::temp_dir().join(format!("dynagen_non_utf8_{}.urdf", std::process::id()));
    std::fs::write(&path, b"<robot name=\"r\"><link name=\"\xff\xfe\"/></robot>").unwrap();
    let e = Model::from_urdf_file(&path).unwrap_err();
    std::fs::remove_file(&path).unwrap();
    assert!(matches!(e, ModelError::Io { .. }), "{e}");
}

#[test]
fn malformed_xml_is_refused_with_a_line() {
    for (xml, says) in [
        ("", "no <robot>"),
        ("just text", "no <robot>"),
        ("<robot name=\"r\">\n<link name=\"a\">\n</robot>", "line 3"),
        ("<robot name=\"r\"><link name=\"a\"/>", "ends inside <robot>"),
        ("<robot name=\"r\"><link name=a/></robot>", "line 1"),
        ("<robot name=\"r\"><link name=\"a\" name=\"b\"/></robot>", "line 1"),
        ("<robot name=\"r\"><link name=\"a&bogus;\"/></robot>", "bogus"),
        ("<robot name=\"r\"><link name=\"a\"/></robot><robot name=\"s\"/>", "second root element"),
    ] {
        let e = err(xml);
        assert!(matches!(e, ModelError::Urdf(_)), "{xml}: {e:?}");
        assert!(e.to_string().contains(says), "{xml}: {e} does not say {says:?}");
    }
}

#[test]
fn a_document_that_is_not_a_robot_is_refused() {
    // urdf-rs reads any root element as the robot
    let e = err(r#"<model name="r"><link name="a"/></model>"#);
    assert!(matches!(e, ModelError::Urdf(_)));
    assert!(e.to_string().contains("<model>, not <robot>"), "{e}");
}

#[test]
fn deep_nesting_is_refused_without_overflowing_the_stack() {
    // urdf-rs and RustyXML recurse per level: 100 000 levels overflow the
    // stack of a test thread if they ever see it
    let n = 100_000;
    let xml = robot(&format!(r#"<link name="a"><visual>{}{}</visual></link>"#, "<g>".repeat(n), "</g>".repeat(n)));
    let e = err(&xml);
    assert!(matches!(e, ModelError::Urdf(_)));
    assert!(e.to_string().contains("nested more than"), "{e}");
}

#[test]
fn joint_structure_errors_name_the_joint() {
    let links = r#"<link name="base"/><link name="arm"/>"#;
    for (joint, says) in [
        (
            r#"<joint name="j" type="screw"><parent link="base"/><child link="arm"/></joint>"#,
            "unknown joint type \"screw\"",
        ),
        (r#"<joint name="j" type="Revolute"><parent link="base"/><child link="arm"/></joint>"#, "unknown joint type"),
        (r#"<joint name="j"><parent link="base"/><child link="arm"/></joint>"#, "no type"),
        (r#"<joint name="j" type="fixed"><child link="arm"/></joint>"#, "no <parent"),
        (r#"<joint name="j" type="fixed"><parent link="base"/></joint>"#, "no <child"),
        (r#"<joint name="j" type="fixed"><parent/><child link="arm"/></joint>"#, "<parent> has no link"),
        (
            r#"<joint name="j" type="fixed"><parent link="base"/><parent link="arm"/><child link="arm"/></joint>"#,
            "more than one <parent>",
        ),
        (
            r#"<joint name="j" type="fixed"><parent link="base"/><child link="arm"/><origin/><origin/></joint>"#,
            "more than one <origin>",
        ),
        (
            r#"<joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis/></joint>"#,
            "<axis> has no xyz",
        ),
        (
            r#"<joint name="j" type="revolute"><parent link="base"/><child link="arm"/><limit lower="0"/></joint>"#,
            "no velocity",
        ),
        // serde-xml-rs would read this child element in place of the attribute
        (
            r#"<joint name="j" type="fixed"><parent link="base"/><child link="arm"/><origin><xyz>1 2 x 3</xyz></origin></joint>"#,
            "must not contain",
        ),
    ] {
        let e = err(&robot(&format!("{links}{joint}")));
        assert!(matches!(e, ModelError::Urdf(_)), "{joint}: {e:?}");
        names(&e, &["j"]);
        assert!(e.to_string().contains(says), "{joint}: {e} does not say {says:?}");
    }
}

#[test]
fn link_structure_errors_name_the_link() {
    for (link, says) in [
        (
            r#"<link name="arm"><inertial><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>"#,
            "no <mass",
        ),
        (r#"<link name="arm"><inertial><mass value="1"/></inertial></link>"#, "no <inertia"),
        (
            r#"<link name="arm"><inertial><mass value="1"/><inertia ixx="1" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>"#,
            "no ixy",
        ),
        (
            r#"<link name="arm"><inertial><mass/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>"#,
            "no value",
        ),
        (&format!(r#"<link name="arm">{INERTIAL}{INERTIAL}</link>"#), "more than one <inertial>"),
    ] {
        let e = err(&robot(&format!(r#"<link name="base"/>{link}"#)));
        assert!(matches!(e, ModelError::Urdf(_)), "{link}: {e:?}");
        names(&e, &["arm"]);
        assert!(e.to_string().contains(says), "{link}: {e} does not say {says:?}");
    }
}

#[test]
fn missing_and_empty_names_are_refused() {
    for (body, says) in [
        (r#"<link name="a"/><link/>"#, "link number 2 has no name"),
        (r#"<link name="a"/><link name=""/>"#, "link number 2 has an empty name"),
        (
            r#"<link name="a"/><link name="b"/><joint type="fixed"><parent link="a"/><child link="b"/></joint>"#,
            "joint number 1 has no name",
        ),
        (
            r#"<link name="a"/><link name="b"/><joint name="" type="fixed"><parent link="a"/><child link="b"/></joint>"#,
            "joint number 1 has an empty name",
        ),
    ] {
        let e = err(&robot(body));
        assert!(matches!(e, ModelError::Urdf(_)), "{body}: {e:?}");
        assert!(e.to_string().contains(says), "{body}: {e} does not say {says:?}");
    }
}

// ---------------------------------------------------------------------------
// numbers

/// Asserts a BadNumber error with these fields.
fn bad_number(xml: &str, item: &str, what: &str, text: &str) {
    match err(xml) {
        ModelError::BadNumber { item: i, what: w, text: t } => {
            assert_eq!((i.as_str(), w.as_str(), t.as_str()), (item, what, text), "{xml}");
        }
        e => panic!("{xml}: expected BadNumber, got {e:?}"),
    }
    let msg = err(xml).to_string();
    assert!(msg.contains(item) && msg.contains(what), "{msg}");
}

#[test]
fn joint_numbers_must_parse_completely_as_finite_numbers() {
    let j = "joint \"j\"";
    for (elem, attr, what, texts) in [
        (
            "origin",
            "xyz",
            "origin xyz",
            // urdf-rs reads "1 2 abc 4" as (1, 2, 4), and "0 0 1x 1" as (0, 0, 1)
            &["1 2 abc 4", "0 0 1x 1", "1 2 abc", "1 2", "1 2 3 4", "NaN 0 0", "0 inf 0", "0 0 1e400", "1,2,3", ""][..],
        ),
        ("origin", "rpy", "origin rpy", &["nan 0 0", "0 -inf 0", "0 0 infinity", "0 0 0 0", "0 0 pi"][..]),
        ("axis", "xyz", "axis xyz", &["0 0 1x", "0 nan 1", "0 0 1 0", "1e999 0 0"][..]),
    ] {
        for text in texts {
            let extra = match elem {
                "axis" => format!(r#"<axis {attr}="{text}"/>"#),
                _ => format!(r#"<{elem} {attr}="{text}"/><axis xyz="0 0 1"/>"#),
            };
            bad_number(&one_joint(&extra), j, what, text);
        }
    }
    for attr in ["lower", "upper", "effort", "velocity"] {
        for text in ["abc", "nan", "inf", "-inf", "1 2", "1e400", ""] {
            let mut attrs = [("lower", "-1"), ("upper", "1"), ("effort", "10"), ("velocity", "2")];
            attrs.iter_mut().find(|(k, _)| *k == attr).unwrap().1 = text;
            let limit: String = attrs.iter().map(|(k, v)| format!(r#" {k}="{v}""#)).collect();
            bad_number(&one_joint(&format!("<limit{limit}/>")), j, &format!("limit {attr}"), text);
        }
    }
}

#[test]
fn link_numbers_must_parse_completely_as_finite_numbers() {
    let l = "link \"arm\"";
    let good = ["0.1", "0", "0", "0.1", "0", "0.1"];
    for text in ["1kg", "nan", "inf", "-inf", "1 2", ""] {
        bad_number(&one_link(&inertial(text, good)), l, "mass value", text);
    }
    for (k, name) in ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"].iter().enumerate() {
        for text in ["abc", "NaN", "inf", "1e400", "0.1 0"] {
            let mut i = good;
            i[k] = text;
            bad_number(&one_link(&inertial("1", i)), l, &format!("inertia {name}"), text);
        }
    }
    for (attr, text) in [("xyz", "0 0 abc 1"), ("xyz", "nan 0 0"), ("rpy", "0 inf 0"), ("rpy", "0 0")] {
        let xml = one_link(&format!(
            r#"<inertial><origin {attr}="{text}"/><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>"#
        ));
        bad_number(&xml, l, &format!("inertial origin {attr}"), text);
    }
}

#[test]
fn quaternions_are_checked_from_urdf_1_1_on() {
    let doc = |version: &str, origin: &str| {
        format!(
            r#"<robot name="t" version="{version}"><link name="base"/><link name="arm">{INERTIAL}</link>
            <joint name="j" type="continuous"><parent link="base"/><child link="arm"/>{origin}<axis xyz="0 0 1"/></joint></robot>"#
        )
    };
    bad_number(&doc("1.1", r#"<origin quat_xyzw="0 0 x 1"/>"#), "joint \"j\"", "origin quat_xyzw", "0 0 x 1");
    bad_number(&doc("1.2", r#"<origin quat_xyzw="0 0 nan 1"/>"#), "joint \"j\"", "origin quat_xyzw", "0 0 nan 1");
    match err(&doc("1.1", r#"<origin quat_xyzw="0 0 0 0"/>"#)) {
        ModelError::BadNumber { item, what, .. } => {
            assert_eq!(item, "joint \"j\"");
            assert!(what.contains("zero quaternion"), "{what}");
        }
        e => panic!("{e:?}"),
    }
    let e = err(&doc("1.1", r#"<origin rpy="0 0 0" quat_xyzw="0 0 0 1"/>"#));
    assert!(matches!(e, ModelError::Urdf(_)) && e.to_string().contains("both rpy and quat_xyzw"), "{e}");
    names(&e, &["j"]);
    // URDF 1.0 ignores quat_xyzw (as urdfdom and urdf-rs do)
    let m = Model::from_urdf_str(&doc("1.0", r#"<origin quat_xyzw="junk"/>"#)).unwrap();
    assert_eq!(m.bodies[0].joint.placement, Transform::identity());
    // and from 1.1 on it is read: a quarter turn about z
    let m = Model::from_urdf_str(&doc("1.1", r#"<origin quat_xyzw="0 0 0.7071067811865476 0.7071067811865476"/>"#))
        .unwrap();
    let r = m.bodies[0].joint.placement.rot.0;
    let want = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    for (a, b) in r.iter().flatten().zip(want.iter().flatten()) {
        assert!((a - b).abs() < 1e-12, "{r:?}");
    }
}

#[test]
fn numbers_urdf_rs_reads_are_kept_exactly() {
    // what the pre-check accepts, urdf-rs must read to the same values
    let xml = one_joint(
        r#"<origin xyz="+1 .5 5." rpy="-0 1e-3 2E-1"/><axis xyz="  0&#32;0   1 "/>
        <limit lower="-1.5" upper="2.25" effort="1e2" velocity="3"/>"#,
    );
    let (desc, warnings) = RobotDescription::from_urdf_str(&xml).unwrap();
    assert!(warnings.is_empty());
    let j = &desc.joints[0];
    assert_eq!(j.origin.trans, Vec3([1.0, 0.5, 5.0]));
    assert_eq!(j.origin.rot, Mat3::from_rpy(0.0, 1e-3, 0.2));
    assert_eq!(j.axis, Vec3([0.0, 0.0, 1.0]));
    let l = j.limits.unwrap();
    assert_eq!((l.lower, l.upper, l.effort, l.velocity), (-1.5, 2.25, 100.0, 3.0));
}

#[test]
fn absent_inertial_and_limit_differ_from_explicit_zeros() {
    let xml = robot(&format!(
        r#"<link name="base"/><link name="none"/><link name="zero">{}</link><link name="arm">{INERTIAL}</link>
        <joint name="j1" type="revolute"><parent link="base"/><child link="none"/><axis xyz="0 0 1"/></joint>
        <joint name="j2" type="revolute"><parent link="none"/><child link="zero"/><axis xyz="0 0 1"/>
            <limit lower="0" upper="0" effort="0" velocity="0"/></joint>
        <joint name="j3" type="fixed"><parent link="zero"/><child link="arm"/><origin xyz="1 0 0"/></joint>"#,
        inertial("0", ["0"; 6])
    ));
    let (desc, _) = RobotDescription::from_urdf_str(&xml).unwrap();
    let link = |n: &str| desc.links.iter().find(|l| l.name == n).unwrap();
    assert_eq!(link("none").inertial, None);
    let zero = link("zero").inertial.expect("an explicit <inertial> is kept");
    assert_eq!(zero.mass, 0.0);
    assert_eq!(desc.joints[0].limits, None, "no <limit>: no limits (urdf-rs says 0, 0, 0, 0)");
    let l = desc.joints[1].limits.expect("an explicit <limit> is kept");
    assert_eq!((l.lower, l.upper, l.effort, l.velocity), (0.0, 0.0, 0.0, 0.0));
    // and both build: the arm, fixed to "zero", gives both joints inertia
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(m.joint_names(), ["j1", "j2"]);
}

// ---------------------------------------------------------------------------
// names and topology

#[test]
fn no_links() {
    let e = err(r#"<robot name="t"/>"#);
    assert!(matches!(e, ModelError::NoLinks), "{e:?}");
    assert!(matches!(RobotBuilder::new("t").build(), Err(ModelError::NoLinks)));
}

#[test]
fn duplicate_link() {
    let e = err(&robot(r#"<link name="base"/><link name="dup"/><link name="dup"/>"#));
    assert!(matches!(&e, ModelError::DuplicateLink(l) if l == "dup"), "{e:?}");
    names(&e, &["dup"]);
}

#[test]
fn duplicate_joint() {
    let e = err(&robot(&format!(
        r#"<link name="base"/><link name="a">{INERTIAL}</link><link name="b">{INERTIAL}</link>
        <joint name="twice" type="continuous"><parent link="base"/><child link="a"/></joint>
        <joint name="twice" type="continuous"><parent link="a"/><child link="b"/></joint>"#
    )));
    assert!(matches!(&e, ModelError::DuplicateJoint(j) if j == "twice"), "{e:?}");
    names(&e, &["twice"]);
}

#[test]
fn missing_parent_or_child_link() {
    for (parent, child, role, missing) in [("nowhere", "arm", "parent", "nowhere"), ("base", "ghost", "child", "ghost")]
    {
        let e = err(&robot(&format!(
            r#"<link name="base"/><link name="arm">{INERTIAL}</link>
            <joint name="j" type="continuous"><parent link="{parent}"/><child link="{child}"/></joint>"#
        )));
        match &e {
            ModelError::MissingLink { joint, role: r, link } => {
                assert_eq!((joint.as_str(), *r, link.as_str()), ("j", role, missing));
            }
            _ => panic!("{e:?}"),
        }
        names(&e, &["j", missing]);
    }
}

#[test]
fn a_link_with_two_parents() {
    let e = err(&robot(&format!(
        r#"<link name="base"/><link name="a">{INERTIAL}</link><link name="b">{INERTIAL}</link>
        <joint name="ja" type="continuous"><parent link="base"/><child link="a"/></joint>
        <joint name="jb" type="continuous"><parent link="base"/><child link="b"/></joint>
        <joint name="again" type="continuous"><parent link="a"/><child link="b"/></joint>"#
    )));
    match &e {
        ModelError::MultipleParents { link, first, second } => {
            assert_eq!((link.as_str(), first.as_str(), second.as_str()), ("b", "jb", "again"));
        }
        _ => panic!("{e:?}"),
    }
    names(&e, &["b", "jb", "again"]);
}

#[test]
fn several_roots() {
    let e = err(&robot(&format!(
        r#"<link name="base"/><link name="arm">{INERTIAL}</link><link name="stray"/>
        <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>"#
    )));
    assert!(matches!(&e, ModelError::MultipleRoots(r) if r == &["base", "stray"]), "{e:?}");
    names(&e, &["base", "stray"]);
}

fn cycle_links(xml: &str) -> Vec<String> {
    match err(xml) {
        ModelError::Cycle(links) => links,
        e => panic!("expected a cycle, got {e:?}\n{xml}"),
    }
}

#[test]
fn cycles_are_reported_with_exactly_their_links() {
    let joint = |name: &str, p: &str, c: &str| {
        format!(r#"<joint name="{name}" type="continuous"><parent link="{p}"/><child link="{c}"/></joint>"#)
    };
    let links = |ns: &[&str]| ns.iter().map(|n| format!(r#"<link name="{n}">{INERTIAL}</link>"#)).collect::<String>();
    // no root at all: every link is in the cycle
    let xml = robot(&format!(
        "{}{}{}{}",
        links(&["a", "b", "c"]),
        joint("ab", "a", "b"),
        joint("bc", "b", "c"),
        joint("ca", "c", "a")
    ));
    let mut c = cycle_links(&xml);
    c.sort();
    assert_eq!(c, ["a", "b", "c"]);
    // no root, and a link hanging off the cycle that is not part of it
    let xml = robot(&format!(
        "{}{}{}{}",
        links(&["a", "b", "tail"]),
        joint("ab", "a", "b"),
        joint("ba", "b", "a"),
        joint("bt", "b", "tail")
    ));
    let mut c = cycle_links(&xml);
    c.sort();
    assert_eq!(c, ["a", "b"], "the tail is not in the cycle");
    // a proper tree from the root, plus a separate two-link cycle with a tail
    let xml = robot(&format!(
        "{}{}{}{}{}",
        links(&["base", "arm", "tail", "x", "y"]),
        joint("j", "base", "arm"),
        joint("yt", "y", "tail"),
        joint("xy", "x", "y"),
        joint("yx", "y", "x")
    ));
    let mut c = cycle_links(&xml);
    c.sort();
    assert_eq!(c, ["x", "y"]);
    let msg = err(&xml).to_string();
    assert!(msg.contains('x') && msg.contains('y') && !msg.contains("tail"), "{msg}");
    // a joint whose parent is its child, beside a tree
    let xml = robot(&format!(
        "{}{}{}",
        links(&["base", "arm", "loop"]),
        joint("j", "base", "arm"),
        joint("self", "loop", "loop")
    ));
    assert_eq!(cycle_links(&xml), ["loop"]);
    // a joint whose parent is its child, and nothing else
    let xml = robot(&format!("{}{}", links(&["only"]), joint("self", "only", "only")));
    assert_eq!(cycle_links(&xml), ["only"]);
}

#[test]
fn cycle_order_follows_the_joints() {
    // parent to child along the cycle, starting anywhere
    let b = builder(
        &[massive("base"), massive("p"), massive("q"), massive("r")],
        vec![
            JointDescription::continuous("j", "base", "p", [0.0, 0.0, 1.0]),
            JointDescription::continuous("qr", "q", "r", [0.0, 0.0, 1.0]),
            JointDescription::continuous("rq", "r", "q", [0.0, 0.0, 1.0]),
        ],
    );
    match build_err(&b) {
        ModelError::Cycle(c) => assert!(c == ["q", "r"] || c == ["r", "q"], "{c:?}"),
        e => panic!("{e:?}"),
    }
}

// ---------------------------------------------------------------------------
// numbers that only the builder and the MR lists can carry

#[test]
fn non_finite_numbers_in_a_description() {
    let j = |name: &str| JointDescription::revolute(name, "base", "arm", [0.0, 0.0, 1.0]);
    let arm = massive("arm");
    let cases: Vec<(RobotBuilder, &str, &str)> = vec![
        (
            builder(&[massive("base"), arm.clone()], vec![j("j").origin([f64::NAN, 0.0, 0.0], [0.0; 3])]),
            "joint \"j\"",
            "origin xyz",
        ),
        (
            builder(&[massive("base"), arm.clone()], vec![j("j").origin([0.0; 3], [0.0, f64::INFINITY, 0.0])]),
            "joint \"j\"",
            "origin rotation",
        ),
        (
            builder(
                &[massive("base"), arm.clone()],
                vec![JointDescription::revolute("j", "base", "arm", [0.0, f64::NAN, 1.0])],
            ),
            "joint \"j\"",
            "axis",
        ),
        (
            builder(&[massive("base"), ("arm".into(), Some(Inertial::point_mass(f64::NAN, [0.0; 3])))], vec![j("j")]),
            "link \"arm\"",
            "mass",
        ),
        (
            builder(
                &[
                    massive("base"),
                    ("arm".into(), Some(Inertial::new(1.0, [0.0; 3], [1.0, 1.0, f64::INFINITY, 0.0, 0.0, 0.0]))),
                ],
                vec![j("j")],
            ),
            "link \"arm\"",
            "inertia",
        ),
        (
            builder(
                &[massive("base"), ("arm".into(), Some(Inertial::point_mass(1.0, [0.0, f64::NEG_INFINITY, 0.0])))],
                vec![j("j")],
            ),
            "link \"arm\"",
            "inertial origin",
        ),
        (
            builder(&[massive("base"), arm.clone()], vec![j("j").limits(f64::NAN, 1.0, 1.0, 1.0)]),
            "joint \"j\"",
            "limit",
        ),
    ];
    for (b, item, what) in cases {
        let e = build_err(&b);
        match &e {
            ModelError::NonFinite { item: i, what: w } => assert_eq!((i.as_str(), *w), (item, what)),
            _ => panic!("{item} {what}: {e:?}"),
        }
        assert!(e.to_string().contains(item), "{e}");
    }
}

#[test]
fn finite_numbers_that_overflow_when_combined_are_refused() {
    // each offset is finite; their sum through two fixed joints is not
    let xml = robot(&format!(
        r#"<link name="base"/><link name="m1"/><link name="m2"/><link name="arm">{INERTIAL}</link>
        <joint name="f1" type="fixed"><parent link="base"/><child link="m1"/><origin xyz="1e308 0 0"/></joint>
        <joint name="f2" type="fixed"><parent link="m1"/><child link="m2"/><origin xyz="1e308 0 0"/></joint>
        <joint name="j" type="continuous"><parent link="m2"/><child link="arm"/></joint>"#
    ));
    let e = err(&xml);
    assert!(
        matches!(&e, ModelError::NonFinite { item, .. } if item.contains("\"j\"") || item.contains("\"m2\"")),
        "{e:?}"
    );
    // a finite mass whose centre of mass is so far away that m·c² is not finite
    let e = err(&one_link(
        r#"<inertial><origin xyz="1e200 0 0"/><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>"#,
    ));
    assert!(matches!(&e, ModelError::NonFinite { item, .. } if item == "link \"arm\""), "{e:?}");
    names(&e, &["arm"]);
}

#[test]
fn huge_inertias_are_judged_like_small_ones() {
    // The closed-form eigenvalues square the entries: without scaling, 1e200
    // overflows and an indefinite inertia slips through every comparison.
    let e = err(&one_link(&inertial("1", ["1e200", "2e200", "0", "1e200", "0", "1e200"])));
    assert!(matches!(&e, ModelError::InertiaNotPositive { link, .. } if link == "arm"), "{e:?}");
    let m = Model::from_urdf_str(&one_link(&inertial("1", ["1e200", "0", "0", "1e200", "0", "1e200"]))).unwrap();
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    // and tiny (subnormal) ones
    let e = err(&one_link(&inertial("1", ["1e-310", "2e-310", "0", "1e-310", "0", "1e-310"])));
    assert!(matches!(&e, ModelError::InertiaNotPositive { link, .. } if link == "arm"), "{e:?}");
}

#[test]
fn reversed_limits_name_the_joint() {
    let e = err(&one_joint(r#"<axis xyz="0 0 1"/><limit lower="1.0" upper="-1.0" effort="10" velocity="1"/>"#));
    assert!(
        matches!(&e, ModelError::LimitsReversed { joint, lower, upper } if joint == "j" && *lower == 1.0 && *upper == -1.0),
        "{e:?}"
    );
    names(&e, &["j"]);
    // an empty range of one point is a joint held in place: allowed
    assert!(Model::from_urdf_str(&one_joint(
        r#"<axis xyz="0 0 1"/><limit lower="0.5" upper="0.5" effort="1" velocity="1"/>"#
    ))
    .is_ok());
}

#[test]
fn zero_axis() {
    let e = err(&one_joint(r#"<axis xyz="0 0 0"/>"#));
    assert!(matches!(&e, ModelError::ZeroAxis(j) if j == "j"), "{e:?}");
    names(&e, &["j"]);
    let e = build_err(&builder(
        &[massive("base"), massive("arm")],
        vec![JointDescription::prismatic("slide", "base", "arm", [0.0; 3])],
    ));
    assert!(matches!(&e, ModelError::ZeroAxis(j) if j == "slide"), "{e:?}");
    // a fixed joint has no axis to check
    assert!(Model::from_urdf_str(&robot(
        r#"<link name="a"/><link name="b"/><joint name="f" type="fixed"><parent link="a"/><child link="b"/><axis xyz="0 0 0"/></joint>"#
    ))
    .is_ok());
}

#[test]
fn not_a_rotation_in_the_builder() {
    let mut j = JointDescription::revolute("j", "base", "arm", [0.0, 0.0, 1.0]);
    j.origin = Transform::new(Mat3([[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), Vec3([0.0; 3]));
    let e = build_err(&builder(&[massive("base"), massive("arm")], vec![j]));
    assert!(matches!(&e, ModelError::NotARotation { item, what: "origin" } if item == "joint \"j\""), "{e:?}");
    names(&e, &["j"]);
    // a reflection is orthonormal, but not a rotation
    let mut j = JointDescription::revolute("j", "base", "arm", [0.0, 0.0, 1.0]);
    j.origin = Transform::new(Mat3([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]]), Vec3([0.0; 3]));
    let e = build_err(&builder(&[massive("base"), massive("arm")], vec![j]));
    assert!(matches!(&e, ModelError::NotARotation { .. }), "{e:?}");
    // the inertial frame of a link
    let mut i = Inertial::point_mass(1.0, [0.0; 3]);
    i.origin.rot = Mat3([[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    let e = build_err(&builder(
        &[massive("base"), ("arm".into(), Some(i))],
        vec![JointDescription::prismatic("j", "base", "arm", [0.0, 0.0, 1.0])],
    ));
    assert!(
        matches!(&e, ModelError::NotARotation { item, what: "inertial origin" } if item == "link \"arm\""),
        "{e:?}"
    );
}

/// The lists of a one-joint arm: joint about z at the origin, a unit mass at
/// (1, 0, 0), the end-effector at (2, 0, 0).
fn mr_lists() -> (Vec<Matrix4<f64>>, Vec<Matrix6<f64>>, DMatrix<f64>) {
    let mut m1 = Matrix4::identity();
    m1[(0, 3)] = 1.0;
    let mut m2 = Matrix4::identity();
    m2[(0, 3)] = 1.0;
    let g = Matrix6::from_diagonal(&nalgebra::Vector6::new(0.1, 0.1, 0.1, 1.0, 1.0, 1.0));
    let s = DMatrix::from_column_slice(6, 1, &[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    (vec![m1, m2], vec![g], s)
}

#[test]
fn not_a_rotation_in_the_modern_robotics_lists() {
    let (mut ml, gl, sl) = mr_lists();
    assert_eq!(Model::from_modern_robotics(&ml, &gl, &sl).unwrap().dof(), 1);
    ml[0][(0, 0)] = 1.5;
    let e = Model::from_modern_robotics(&ml, &gl, &sl).unwrap_err();
    assert!(matches!(&e, ModelError::NotARotation { item, .. } if item == "joint \"joint1\""), "{e:?}");
    names(&e, &["joint1"]);
    let (mut ml, gl, sl) = mr_lists();
    ml[1][(1, 1)] = -1.0; // the end-effector frame: a reflection
    let e = Model::from_modern_robotics(&ml, &gl, &sl).unwrap_err();
    assert!(matches!(&e, ModelError::NotARotation { item, .. } if item == "joint \"ee_joint\""), "{e:?}");
}

#[test]
fn modern_robotics_lists_that_do_not_fit() {
    let (ml, gl, sl) = mr_lists();
    let e = Model::from_modern_robotics(&ml[..1], &gl, &sl).unwrap_err();
    assert!(matches!(&e, ModelError::ModernRobotics(m) if m.contains("Mlist")), "{e:?}");
    let e = Model::from_modern_robotics(&ml, &gl, &DMatrix::zeros(6, 2)).unwrap_err();
    assert!(matches!(&e, ModelError::ModernRobotics(m) if m.contains("Slist")), "{e:?}");
    let mut g = gl.clone();
    g[0][(0, 3)] = 0.5; // not symmetric
    let e = Model::from_modern_robotics(&ml, &g, &sl).unwrap_err();
    assert!(matches!(&e, ModelError::ModernRobotics(m) if m.contains("link1")), "{e:?}");
    // a screw axis with pitch: a helical joint
    let s = DMatrix::from_column_slice(6, 1, &[0.0, 0.0, 1.0, 0.0, 0.0, 0.3]);
    let e = Model::from_modern_robotics(&ml, &gl, &s).unwrap_err();
    assert!(matches!(&e, ModelError::Unsupported { joint, .. } if joint == "joint1"), "{e:?}");
    assert!(e.to_string().contains("not supported yet"), "{e}");
    // a lists-level description can be read back by name
    let desc = ModernRoboticsLists { mlist: ml, glist: gl, slist: sl }.to_description().unwrap();
    assert_eq!(desc.joints[0].joint_type, JointType::Revolute);
}

// ---------------------------------------------------------------------------
// mass properties

#[test]
fn negative_mass() {
    let e = err(&one_link(&inertial("-2", ["0.1", "0", "0", "0.1", "0", "0.1"])));
    assert!(matches!(&e, ModelError::NegativeMass { link, mass } if link == "arm" && *mass == -2.0), "{e:?}");
    names(&e, &["arm"]);
}

#[test]
fn inertia_not_positive_semi_definite() {
    for i in [["-0.1", "0", "0", "0.1", "0", "0.1"], ["1", "2", "0", "1", "0", "1"], ["1", "0", "0", "1", "0", "-1e-6"]]
    {
        let e = err(&one_link(&inertial("1", i)));
        match &e {
            ModelError::InertiaNotPositive { link, moments } => {
                assert_eq!(link, "arm");
                assert!(moments[0] < 0.0, "{moments:?}");
            }
            _ => panic!("{i:?}: {e:?}"),
        }
        names(&e, &["arm"]);
    }
    // (1, 2, 0 | ...) has moments -1, 1, 3: check the reported ones
    match err(&one_link(&inertial("1", ["1", "2", "0", "1", "0", "1"]))) {
        ModelError::InertiaNotPositive { moments, .. } => {
            for (m, want) in moments.iter().zip([-1.0, 1.0, 3.0]) {
                assert!((m - want).abs() < 1e-12, "{moments:?}");
            }
        }
        e => panic!("{e:?}"),
    }
    // rounding in printed digits is not an error: a moment of -1e-12 against 1
    Model::from_urdf_str(&one_link(&inertial("1", ["-1e-12", "0", "0", "1", "0", "1"]))).unwrap();
}

#[test]
fn triangle_inequality_warns_by_default_and_is_refused_in_strict_mode() {
    // moments 1, 1, 3: 1 + 1 < 3, no body has them
    let xml = one_link(&inertial("1", ["1", "0", "0", "1", "0", "3"]));
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(m.warnings.len(), 1, "{:?}", m.warnings);
    match &m.warnings[0] {
        ModelWarning::TriangleInequality { link, moments } => {
            assert_eq!(link, "arm");
            for (m, want) in moments.iter().zip([1.0, 1.0, 3.0]) {
                assert!((m - want).abs() < 1e-12, "{moments:?}");
            }
        }
        w => panic!("{w:?}"),
    }
    assert!(m.warnings[0].to_string().contains("\"arm\""));
    let e = Model::from_urdf_str_with(&xml, &BuildOptions { strict: true, ..Default::default() }).unwrap_err();
    assert!(matches!(&e, ModelError::TriangleInequality { link, .. } if link == "arm"), "{e:?}");
    names(&e, &["arm"]);
    // the same through the builder
    let arm = Inertial::new(1.0, [0.0; 3], [1.0, 1.0, 3.0, 0.0, 0.0, 0.0]);
    let b = builder(
        &[massive("base"), ("arm".into(), Some(arm))],
        vec![JointDescription::continuous("j", "base", "arm", [1.0, 0.0, 0.0])],
    );
    assert_eq!(b.build().unwrap().warnings.len(), 1);
    assert!(matches!(build_err(&b.strict(true)), ModelError::TriangleInequality { .. }));
    // the equality case (a flat plate: 1 + 2 = 3) is physical
    let plate = one_link(&inertial("1", ["1", "0", "0", "2", "0", "3"]));
    assert!(Model::from_urdf_str_with(&plate, &BuildOptions { strict: true, ..Default::default() })
        .unwrap()
        .warnings
        .is_empty());
}

#[test]
fn inertia_without_mass_warns() {
    let xml = robot(&format!(
        r#"<link name="base"/><link name="ghost">{}</link><link name="arm">{INERTIAL}</link>
        <joint name="j" type="continuous"><parent link="base"/><child link="ghost"/></joint>
        <joint name="f" type="fixed"><parent link="ghost"/><child link="arm"/></joint>"#,
        inertial("0", ["0.1", "0", "0", "0.1", "0", "0.1"])
    ));
    let m = Model::from_urdf_str(&xml).unwrap();
    assert!(
        matches!(&m.warnings[..], [ModelWarning::InertiaWithoutMass { link }] if link == "ghost"),
        "{:?}",
        m.warnings
    );
    assert!(m.warnings[0].to_string().contains("\"ghost\""));
}

#[test]
fn an_actuated_joint_that_moves_nothing() {
    // the child has no inertial, and nothing below it
    let xml = robot(&format!(
        r#"<link name="base"/><link name="arm">{INERTIAL}</link><link name="finger"/><link name="nail"/>
        <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
        <joint name="jf" type="prismatic"><parent link="arm"/><child link="finger"/><axis xyz="1 0 0"/>
            <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
        <joint name="fixed_nail" type="fixed"><parent link="finger"/><child link="nail"/></joint>"#
    ));
    let e = err(&xml);
    assert!(
        matches!(&e, ModelError::MasslessSubtree { joint, link, .. } if joint == "jf" && link == "finger"),
        "{e:?}"
    );
    names(&e, &["jf"]);
    assert!(
        e.to_string().ends_with(
            "its child link \"finger\" has no mass, nor has anything fixed to it or below it: give link \"finger\" a \
             mass and an inertia (URDF: an <inertial> element), or fix a link with mass to it; if the joint moves \
             nothing, make it fixed"
        ),
        "{e}"
    );
    // a point mass on a revolute joint's axis has no inertia about it
    let xml = robot(
        r#"<link name="base"/><link name="bead"><inertial><origin xyz="0 0 0.7"/><mass value="1"/>
        <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
        <joint name="spin" type="continuous"><parent link="base"/><child link="bead"/><axis xyz="0 0 1"/></joint>"#,
    );
    let e = err(&xml);
    assert!(
        matches!(&e, ModelError::MasslessSubtree { joint, link, .. } if joint == "spin" && link == "bead"),
        "{e:?}"
    );
    assert!(
        e.to_string().ends_with(
            "the 1 kg it moves lie on its axis, without inertia about it: give link \"bead\" a moment of inertia \
             about the joint's axis (URDF: the <inertia> of its <inertial>)"
        ),
        "{e}"
    );
    // a massless link whose child carries mass is fine: its subtree moves it
    let xml = robot(&format!(
        r#"<link name="base"/><link name="hub"/><link name="arm">{INERTIAL}</link>
        <joint name="j1" type="continuous"><parent link="base"/><child link="hub"/><axis xyz="0 0 1"/></joint>
        <joint name="j2" type="continuous"><parent link="hub"/><child link="arm"/><origin xyz="1 0 0"/><axis xyz="0 1 0"/></joint>"#
    ));
    assert_eq!(Model::from_urdf_str(&xml).unwrap().dof(), 2);
}

/// M's diagonal entry of a revolute joint whose subtree is point masses on
/// later joints: positive at q = 0 but not everywhere.
#[test]
fn a_diagonal_of_m_that_may_vanish_away_from_q_zero_is_a_warning() {
    // `spin` turns about z; its own link is massless; a point mass sits at
    // the end of a prismatic slide along x that starts 0.5 m off the axis:
    // at slide = -0.5 the mass is on the axis and M[0][0] = 0.
    let point = r#"<inertial><mass value="2"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>"#;
    let xml = robot(&format!(
        r#"<link name="base"/><link name="hub"/><link name="bead">{point}</link>
        <joint name="spin" type="continuous"><parent link="base"/><child link="hub"/><axis xyz="0 0 1"/></joint>
        <joint name="slide" type="prismatic"><parent link="hub"/><child link="bead"/><origin xyz="0.5 0 0"/>
            <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>"#
    ));
    let m = Model::from_urdf_str(&xml).unwrap();
    assert!(
        matches!(&m.warnings[..], [ModelWarning::MassMatrixMayBeSingular { joint }] if joint == "spin"),
        "{:?}",
        m.warnings
    );
    assert!(m.warnings[0].to_string().contains("\"spin\""));
    // The warning is not idle: there is such a configuration.
    let mut solver = Robot::new(m);
    let mass = solver.mass_matrix(&DVector::from_vec(vec![0.3, -0.5])).unwrap();
    assert!(mass[(0, 0)].abs() < 1e-15 && mass[(1, 1)] == 2.0, "{mass}");
    // The same bead with a moment of inertia of its own (a small ball) is
    // safe everywhere: no warning.
    let ball =
        r#"<inertial><mass value="2"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>"#;
    let safe = xml.replace(point, ball);
    assert!(Model::from_urdf_str(&safe).unwrap().warnings.is_empty());
    // So is a point mass on the joint's own link (its distance to the axis
    // is fixed), and the mass on later joints does not matter then.
    let own = robot(&format!(
        r#"<link name="base"/><link name="arm"><inertial><origin xyz="0.4 0 0"/><mass value="1"/>
            <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link><link name="bead">{point}</link>
        <joint name="spin" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
        <joint name="slide" type="prismatic"><parent link="arm"/><child link="bead"/><origin xyz="0.5 0 0"/>
            <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>"#
    ));
    assert!(Model::from_urdf_str(&own).unwrap().warnings.is_empty());
}

#[test]
fn unsupported_joints() {
    // A floating joint at the root floats the robot (issue 17; tests/floating_base.rs
    // has the floating joints that are still refused).
    let xml = robot(&format!(
        r#"<link name="base"/><link name="arm">{INERTIAL}</link>
        <joint name="free" type="floating"><parent link="base"/><child link="arm"/></joint>"#
    ));
    let m = Model::from_urdf_str(&xml).unwrap();
    assert!(m.is_floating() && m.root == "arm" && m.dof() == 0 && m.base_inertia.mass == 1.0);
    for (ty, what) in [("planar", "planar"), ("spherical", "spherical")] {
        let xml = robot(&format!(
            r#"<link name="base"/><link name="arm">{INERTIAL}</link>
            <joint name="free" type="{ty}"><parent link="base"/><child link="arm"/></joint>"#
        ));
        let e = err(&xml);
        assert!(
            matches!(&e, ModelError::Unsupported { joint, what: w } if joint == "free" && w.contains(what)),
            "{e:?}"
        );
        assert!(e.to_string().contains("not supported yet"), "{e}");
        names(&e, &["free"]);
    }
    let xml = robot(&format!(
        r#"<link name="base"/><link name="a">{INERTIAL}</link><link name="b">{INERTIAL}</link>
        <joint name="lead" type="continuous"><parent link="base"/><child link="a"/></joint>
        <joint name="follow" type="continuous"><parent link="a"/><child link="b"/><mimic joint="lead" multiplier="2"/></joint>"#
    ));
    // a mimic joint follows its master (tests/mimic.rs): one coordinate
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(
        (m.dof(), m.bodies.len(), m.mimic(1).map(|c| (c.master, c.multiplier, c.offset))),
        (1, 2, Some((0, 2.0, 0.0)))
    );
}

#[test]
fn unknown_names() {
    let m = Model::from_urdf_str(&one_joint(r#"<axis xyz="0 0 1"/>"#)).unwrap();
    assert!(m.frame("arm").is_ok());
    let e = m.frame("hand").unwrap_err();
    assert!(matches!(&e, ModelError::UnknownName(n) if n == "hand"), "{e:?}");
    names(&e, &["hand"]);
}

// ---------------------------------------------------------------------------
// what must come out right when the model is accepted

fn rpy(r: f64, p: f64, y: f64) -> Matrix3<f64> {
    // nalgebra's roll-pitch-yaw is R = Rz(yaw)·Ry(pitch)·Rx(roll), as URDF's
    *Rotation3::from_euler_angles(r, p, y).matrix()
}

#[test]
fn fixed_joint_merging_combines_mass_com_and_inertia_exactly() {
    // "upper" moves; "tool" is fixed to it, a quarter turn about z and 0.5 up,
    // and its inertial frame is turned a quarter about x.
    let xml = robot(
        r#"<link name="base"/>
        <link name="upper"><inertial><origin xyz="0.1 0 0"/><mass value="2"/>
            <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial></link>
        <link name="tool"><inertial><origin xyz="0.2 0 0" rpy="1.5707963267948966 0 0"/><mass value="1"/>
            <inertia ixx="0.004" ixy="0" ixz="0" iyy="0.005" iyz="0" izz="0.006"/></inertial></link>
        <joint name="j" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 1" rpy="0.3 0 0"/>
            <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
        <joint name="weld" type="fixed"><parent link="upper"/><child link="tool"/>
            <origin xyz="0 0 0.5" rpy="0 0 1.5707963267948966"/></joint>"#,
    );
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(m.dof(), 1);
    let i = &m.bodies[0].inertia;
    // By hand, in upper's frame: tool's centre of mass is Rz(90°)(0.2, 0, 0)
    // + (0, 0, 0.5) = (0, 0.2, 0.5); its inertia axes are Rz(90°)Rx(90°):
    // Rx swaps y and z, Rz swaps x and y, so diag(0.004, 0.005, 0.006)
    // becomes diag(0.006, 0.004, 0.005). Total mass 3, centre of mass
    // (2(0.1, 0, 0) + (0, 0.2, 0.5))/3 = (0.2, 0.2, 0.5)/3. Offsets from it:
    // d_upper = (0.1, -0.2, -0.5)/3, d_tool = (-0.2, 0.4, 1.0)/3, and the
    // parallel-axis terms m(|d|² 1 - d dᵀ) give
    //   Ixx = 0.016 + (2·0.29 + 1.16)/9 = 0.016 + 1.74/9
    //   Iyy = 0.024 + (2·0.26 + 1.04)/9 = 0.024 + 1.56/9
    //   Izz = 0.035 + (2·0.05 + 0.20)/9 = 0.035 + 0.30/9
    //   Ixy = -(2·(0.1)(-0.2) + (-0.2)(0.4))/9 = 0.12/9
    //   Ixz = -(2·(0.1)(-0.5) + (-0.2)(1.0))/9 = 0.30/9
    //   Iyz = -(2·(-0.2)(-0.5) + (0.4)(1.0))/9 = -0.60/9
    assert!((i.mass - 3.0).abs() < 1e-15);
    let com = i.com().unwrap();
    for (a, b) in com.0.iter().zip([0.2 / 3.0, 0.2 / 3.0, 0.5 / 3.0]) {
        assert!((a - b).abs() < 1e-14, "{com:?}");
    }
    let want = [0.016 + 1.74 / 9.0, 0.024 + 1.56 / 9.0, 0.035 + 0.30 / 9.0, 0.12 / 9.0, 0.30 / 9.0, -0.60 / 9.0];
    let got = i.inertia_at_com().0;
    for (a, b) in got.iter().zip(want) {
        assert!((a - b).abs() < 1e-14, "got {got:?}\nwant {want:?}");
    }
    // the same with nalgebra, as a second, independent computation
    let (r_w, p_w) = (rpy(0.0, 0.0, std::f64::consts::FRAC_PI_2), Vector3::new(0.0, 0.0, 0.5));
    let r_tool = r_w * rpy(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
    let c1 = Vector3::new(0.1, 0.0, 0.0);
    let c2 = p_w + r_w * Vector3::new(0.2, 0.0, 0.0);
    let c = (2.0 * c1 + c2) / 3.0;
    let shift = |m: f64, d: Vector3<f64>| m * (Matrix3::identity() * d.dot(&d) - d * d.transpose());
    let total = Matrix3::from_diagonal(&Vector3::new(0.01, 0.02, 0.03))
        + r_tool * Matrix3::from_diagonal(&Vector3::new(0.004, 0.005, 0.006)) * r_tool.transpose()
        + shift(2.0, c1 - c)
        + shift(1.0, c2 - c);
    let t = [total[(0, 0)], total[(1, 1)], total[(2, 2)], total[(0, 1)], total[(0, 2)], total[(1, 2)]];
    for (a, b) in got.iter().zip(t) {
        assert!((a - b).abs() < 1e-14, "got {got:?}\nnalgebra {t:?}");
    }
    // the merged link is still a frame, placed where the fixed joint says
    let f = m.frame("tool").unwrap();
    assert_eq!(f.body, Some(0));
    assert!((f.placement.trans.0[2] - 0.5).abs() < 1e-15);
    let r = f.placement.rot.0;
    for (row, want_row) in r.iter().zip([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]) {
        for (a, b) in row.iter().zip(want_row) {
            assert!((a - b).abs() < 1e-15, "{r:?}");
        }
    }
}

#[test]
fn merging_through_fixed_joints_to_the_base_and_between_bodies() {
    // base -f0-> mount -j1-> a -f1-> a_plate -f2-> a_tip -j2-> b ; b -f3-> b_tip
    let xml = robot(&format!(
        r#"<link name="base"/><link name="mount">{INERTIAL}</link>
        <link name="a">{INERTIAL}</link><link name="a_plate">{INERTIAL}</link><link name="a_tip"/>
        <link name="b">{INERTIAL}</link><link name="b_tip"/>
        <joint name="f0" type="fixed"><parent link="base"/><child link="mount"/><origin xyz="0 0 2" rpy="0 0 1"/></joint>
        <joint name="j1" type="continuous"><parent link="mount"/><child link="a"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/></joint>
        <joint name="f1" type="fixed"><parent link="a"/><child link="a_plate"/><origin xyz="1 0 0" rpy="0 0.5 0"/></joint>
        <joint name="f2" type="fixed"><parent link="a_plate"/><child link="a_tip"/><origin xyz="0 0 1" rpy="0.2 0 0"/></joint>
        <joint name="j2" type="continuous"><parent link="a_tip"/><child link="b"/><origin xyz="0 0.3 0"/><axis xyz="1 0 0"/></joint>
        <joint name="f3" type="fixed"><parent link="b"/><child link="b_tip"/><origin xyz="0 0 0.25"/></joint>"#
    ));
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(m.joint_names(), ["j1", "j2"]);
    assert_eq!(m.root, "base");
    assert_eq!(m.base_mass, 1.0, "mount is fixed to the base");
    assert_eq!(m.bodies[0].inertia.mass, 2.0, "a and a_plate");
    assert_eq!(m.bodies[1].inertia.mass, 1.0);
    assert_eq!(m.bodies[1].parent, Some(0));
    // every link is a frame
    let mut frames: Vec<&str> = m.frames.iter().map(|f| f.name.as_str()).collect();
    frames.sort_unstable();
    assert_eq!(frames, ["a", "a_plate", "a_tip", "b", "b_tip", "base", "mount"]);
    // placements against homogeneous matrices multiplied out with nalgebra
    let h = |xyz: [f64; 3], r: [f64; 3]| {
        let mut t = Matrix4::identity();
        t.fixed_view_mut::<3, 3>(0, 0).copy_from(&rpy(r[0], r[1], r[2]));
        t.fixed_view_mut::<3, 1>(0, 3).copy_from(&Vector3::from(xyz));
        t
    };
    let f0 = h([0.0, 0.0, 2.0], [0.0, 0.0, 1.0]);
    let j1 = h([0.5, 0.0, 0.0], [0.0; 3]);
    let f1 = h([1.0, 0.0, 0.0], [0.0, 0.5, 0.0]);
    let f2 = h([0.0, 0.0, 1.0], [0.2, 0.0, 0.0]);
    let j2 = h([0.0, 0.3, 0.0], [0.0; 3]);
    let f3 = h([0.0, 0.0, 0.25], [0.0; 3]);
    let close = |t: &Transform<f64>, want: Matrix4<f64>, what: &str| {
        let got = t.to_homogeneous();
        for r in 0..4 {
            for c in 0..4 {
                assert!((got[r][c] - want[(r, c)]).abs() < 1e-14, "{what}: {got:?} vs {want}");
            }
        }
    };
    close(&m.bodies[0].joint.placement, f0 * j1, "j1 placement in the base");
    close(&m.bodies[1].joint.placement, f1 * f2 * j2, "j2 placement in body a");
    let frame = |n: &str| m.frame(n).unwrap();
    assert_eq!(frame("base").body, None);
    assert_eq!(frame("mount").body, None);
    close(&frame("mount").placement, f0, "mount");
    close(&frame("base").placement, Matrix4::identity(), "base");
    assert_eq!(frame("a").body, Some(0));
    close(&frame("a").placement, Matrix4::identity(), "a");
    close(&frame("a_plate").placement, f1, "a_plate");
    close(&frame("a_tip").placement, f1 * f2, "a_tip");
    assert_eq!(frame("b_tip").body, Some(1));
    close(&frame("b_tip").placement, f3, "b_tip");
    // and forward kinematics puts b_tip where the product of all of them says
    let mut robot = Robot::new(m);
    let q = DVector::from_vec(vec![0.7, -0.4]);
    let rz = |a: f64| h([0.0; 3], [0.0, 0.0, a]);
    let rx = |a: f64| h([0.0; 3], [a, 0.0, 0.0]);
    let want = f0 * j1 * rz(0.7) * f1 * f2 * j2 * rx(-0.4) * f3;
    let got = robot.frame_pose("b_tip", &q).unwrap();
    assert!((got - want).abs().max() < 1e-13, "{got} vs {want}");
}

#[test]
fn non_unit_axes_are_normalised_with_a_warning() {
    let xml = robot(&format!(
        r#"<link name="base"/><link name="a">{INERTIAL}</link><link name="b">{INERTIAL}</link>
        <joint name="turn" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 2"/></joint>
        <joint name="slide" type="prismatic"><parent link="a"/><child link="b"/><axis xyz="3 4 0"/>
            <limit lower="0" upper="1" effort="1" velocity="1"/></joint>"#
    ));
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(
        m.warnings,
        [
            ModelWarning::AxisNormalised { joint: "turn".into(), norm: 2.0 },
            ModelWarning::AxisNormalised { joint: "slide".into(), norm: 5.0 }
        ]
    );
    assert!(m.warnings[1].to_string().contains("\"slide\""));
    let turn = &m.bodies[0].joint;
    assert_eq!((turn.axis, turn.unit_axis, turn.axis_norm), (Vec3([0.0, 0.0, 1.0]), Vec3([0.0, 0.0, 1.0]), 1.0));
    let slide = &m.bodies[1].joint;
    assert!((slide.axis.0[0] - 0.6).abs() < 1e-15 && (slide.axis.0[1] - 0.8).abs() < 1e-15);
    assert!((slide.axis_norm - 1.0).abs() < 1e-15);
    // a unit axis, even as printed with few digits, is left alone
    let m = Model::from_urdf_str(&one_joint(r#"<axis xyz="0 0.7071067811865476 0.7071067811865476"/>"#)).unwrap();
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
}

#[test]
fn joint_order_is_depth_first_children_in_file_order_whatever_the_order_of_the_file() {
    // the tree:  base ─ jb ─ B
    //                └ ja ─ A ─ ja2 ─ A2
    //                           └ ja1 ─ A1 ─ ja1x ─ A1x
    // listed in the file with links and joints scrambled; siblings in the
    // order of their joints in the file: jb before ja, ja2 before ja1
    let xml = robot(&format!(
        r#"<link name="A1x">{INERTIAL}</link><link name="A">{INERTIAL}</link><link name="B">{INERTIAL}</link>
        <joint name="ja2" type="continuous"><parent link="A"/><child link="A2"/><axis xyz="0 1 0"/></joint>
        <link name="A2">{INERTIAL}</link>
        <joint name="jb" type="continuous"><parent link="base"/><child link="B"/></joint>
        <joint name="ja1x" type="continuous"><parent link="A1"/><child link="A1x"/><axis xyz="0 1 0"/></joint>
        <link name="base"/>
        <joint name="ja" type="continuous"><parent link="base"/><child link="A"/></joint>
        <link name="A1">{INERTIAL}</link>
        <joint name="ja1" type="continuous"><parent link="A"/><child link="A1"/><axis xyz="0 1 0"/></joint>"#
    ));
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(m.root, "base");
    assert_eq!(m.joint_names(), ["jb", "ja", "ja2", "ja1", "ja1x"]);
    let parents: Vec<Option<usize>> = m.bodies.iter().map(|b| b.parent).collect();
    assert_eq!(parents, [None, None, Some(1), Some(1), Some(3)]);
    let bodies: Vec<&str> = m.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(bodies, ["B", "A", "A2", "A1", "A1x"]);
    for (i, name) in ["jb", "ja", "ja2", "ja1", "ja1x"].iter().enumerate() {
        assert_eq!(m.joint_index(name), Some(i));
    }
    assert!(m.is_in_subtree(1, 4) && m.is_in_subtree(3, 4) && !m.is_in_subtree(2, 4) && !m.is_in_subtree(0, 4));
    assert_eq!(m.frames.len(), 6);
}

#[test]
fn bundled_robots_load_in_strict_mode() {
    let mut seen = 0;
    for entry in std::fs::read_dir(support::ROBOTS).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "urdf") {
            let m = Model::from_urdf_file_with(&path, &BuildOptions { strict: true, ..Default::default() })
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert!(m.dof() > 0);
            seen += 1;
        }
    }
    assert!(seen > 0);
}

#[test]
fn a_ten_thousand_link_chain_loads_and_runs() {
    // no recursion anywhere in import, validation or the algorithms: this
    // runs on a test thread's 2 MiB stack
    let n = 10_000;
    let mut xml = String::from(r#"<robot name="chain"><link name="l0"/>"#);
    for i in 1..=n {
        xml += &format!(
            r#"<link name="l{i}"><inertial><origin xyz="0.01 0 0"/><mass value="1"/>
            <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
            <joint name="j{i}" type="continuous"><parent link="l{}"/><child link="l{i}"/>
            <origin xyz="0 0 0.01"/><axis xyz="0 1 0"/></joint>"#,
            i - 1
        );
    }
    xml += "</robot>";
    let m = Model::from_urdf_str(&xml).unwrap();
    assert_eq!(m.dof(), n);
    assert!(m.bodies.iter().enumerate().all(|(i, b)| b.parent == i.checked_sub(1)));
    // gravity torques at q = 0: joint k (axis y) holds the n - k + 1 unit
    // masses below it, each 0.01 m out along x: |τ_k| = (n - k + 1)·9.81·0.01
    let mut robot = Robot::new(m);
    let tau = robot.gravity_torques(&DVector::zeros(n)).unwrap();
    for k in [0, 1, n / 2, n - 1] {
        let want = (n - k) as f64 * 9.81 * 0.01;
        assert!((tau[k].abs() - want).abs() < 1e-9 * want, "τ[{k}] = {} want ±{want}", tau[k]);
    }
}
