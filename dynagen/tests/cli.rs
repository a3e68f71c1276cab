//! The `dynagen` command, run as a user would: every subcommand, its output
//! checked against the library called here on the same input, and every
//! kind of bad input giving one error line that names the file and the item.

mod support;

use assert_cmd::Command;
use dynagen::Robot;
use nalgebra::{DVector, Vector3};
use serde_json::Value;
use std::path::{Path, PathBuf};

use support::ROBOTS;

fn dynagen() -> Command {
    Command::cargo_bin("dynagen").expect("the dynagen binary is built for integration tests")
}

/// A fresh directory for one test's files.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Runs and expects failure with `status`: stderr is one line `error: …`,
/// which is returned. No panic, no backtrace, no usage text.
fn fails(cmd: &mut Command, status: i32) -> String {
    let out = cmd.output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(status), "stderr: {stderr}");
    assert!(out.stdout.is_empty(), "nothing on stdout on failure");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one line on stderr, got: {stderr}");
    assert!(lines[0].starts_with("error: "), "{stderr}");
    assert!(!stderr.contains("panicked") && !stderr.contains("internal error"), "{stderr}");
    lines[0].to_string()
}

fn succeeds(cmd: &mut Command) -> String {
    let out = cmd.output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "stderr: {stderr}");
    String::from_utf8(out.stdout).unwrap()
}

// ---------------------------------------------------------------- inspect

#[test]
fn inspect_the_bundled_ur5_from_any_directory() {
    let dir = scratch("inspect_bundled");
    let out = succeeds(dynagen().arg("inspect").current_dir(&dir));
    assert!(out.starts_with("robot \"ur5\" from ur5.urdf (bundled)\n"), "{out}");

    // The joint table lists every joint in the library's order, with its
    // index, type, axis and limits (UR5: ±2π rad, π rad/s; 150 and 28 N·m).
    let robot = support::robot("ur5");
    let names = robot.joint_names();
    assert_eq!(names.len(), 6);
    let axes = ["(0, 0, 1)", "(0, 1, 0)", "(0, 1, 0)", "(0, 1, 0)", "(0, 0, 1)", "(0, 1, 0)"];
    for (i, name) in names.iter().enumerate() {
        let line = out
            .lines()
            .find(|l| l.split_whitespace().take(2).eq([i.to_string().as_str(), name]))
            .unwrap_or_else(|| panic!("no joint row \"{i} {name}\" in\n{out}"));
        let effort = if i < 3 { "150 N·m" } else { "28 N·m" };
        for part in ["revolute", axes[i], "-6.28319 rad", "6.28319 rad", "3.14159 rad/s", effort] {
            assert!(line.contains(part), "{line:?} lacks {part:?}");
        }
    }
    // The tree is a chain: each joint one level deeper than the last, and
    // ee_link (fixed to wrist_3_link) merged into the last body.
    let tree: Vec<&str> = out.lines().filter(|l| l.contains("└─") || l.contains("├─")).collect();
    assert_eq!(tree.len(), 6, "{out}");
    for (i, line) in tree.iter().enumerate() {
        assert_eq!(line.find("└─"), Some(2 + 3 * i), "{line:?}");
        assert!(line.contains(&format!("[{i}] {}", names[i])), "{line:?}");
    }
    assert!(tree[5].ends_with("-> wrist_3_link + ee_link"), "{}", tree[5]);
    // Masses as in the file, and their sum (3.7 + 8.393 + 2.275 + 2·1.219 + 0.1879).
    for (body, mass) in [("shoulder_link", "3.7 kg"), ("upper_arm_link", "8.393 kg"), ("wrist_3_link", "0.1879 kg")] {
        let line = out.lines().find(|l| l.split_whitespace().nth(1) == Some(body) && l.contains(" kg ")).unwrap();
        assert!(line.contains(mass), "{line:?}");
    }
    assert!(out.contains("total mass 16.9939 kg"), "{out}");
    // The centre of mass of upper_arm_link is 0.28 m up its z axis.
    assert!(out.lines().any(|l| l.contains("upper_arm_link") && l.contains("(0, 0, 0.28) m")), "{out}");
    // Every link is a frame; ee_link sits 0.0823 m along y of wrist_3_link.
    let ee = out.lines().find(|l| l.trim_start().starts_with("ee_link")).unwrap();
    assert!(ee.contains("5 wrist_3_link") && ee.contains("(0, 0.0823, 0)"), "{ee:?}");
    assert!(out.contains("\nwarnings: none\n"), "{out}");
}

#[test]
fn inspect_a_file_shows_branches_fixed_links_and_base_mass() {
    let out = succeeds(dynagen().arg("inspect").arg(format!("{ROBOTS}/torso_two_arms.urdf")));
    assert!(out.contains("torso_two_arms.urdf"), "{out}");
    let robot = Robot::from_urdf_file(format!("{ROBOTS}/torso_two_arms.urdf")).unwrap();
    let model = robot.model();
    // One tree line per body, in joint order; a body with two children has
    // one ├─ child and one └─ child at the same depth.
    let tree: Vec<&str> = out.lines().filter(|l| l.contains("└─") || l.contains("├─")).collect();
    assert_eq!(tree.len(), model.dof());
    for (i, line) in tree.iter().enumerate() {
        let b = &model.bodies[i];
        assert!(line.contains(&format!("[{i}] {} (revolute) -> {}", b.joint.name, b.name)), "{line:?}");
        let depth = |mut j: usize| {
            let mut d = 0;
            while let Some(p) = model.bodies[j].parent {
                j = p;
                d += 1;
            }
            d
        };
        let col = line.find("─").unwrap() - 3; // the byte before "├" or "└" (3 bytes each)
        assert_eq!(line[..col].chars().count(), 2 + 3 * depth(i), "{line:?}");
    }
    // Links fixed to a body are listed with it, and the base's mass is shown apart.
    assert!(out.contains("-> left_forearm + left_wrist_mount"), "{out}");
    assert!(out.contains("-> right_hand + right_ee"), "{out}");
    // Frames: a fixed link's pose in its body's frame, as the file gives it
    // (joint origins xyz="0 0 -0.09" rpy="0.1 -0.2 0.3" and xyz="0 0 -0.25" rpy="0 0 0.5").
    let frame = |name: &str| out.lines().find(|l| l.split_whitespace().next() == Some(name)).unwrap();
    assert!(frame("right_ee").ends_with("6 right_hand       (0, 0, -0.09)  (0.1, -0.2, 0.3)"), "{out}");
    assert!(frame("left_wrist_mount").ends_with("2 left_forearm     (0, 0, -0.25)  (0, 0, 0.5)"), "{out}");
    // Masses from the file: left_forearm 1.2 kg + left_wrist_mount 0.6 kg
    // fixed to it; 11.8 kg moving in all, and the base link's 5 kg.
    assert!(out.lines().any(|l| l.contains(" left_forearm ") && l.contains(" 1.8 kg ")), "{out}");
    assert!(out.contains("total mass 16.8 kg: 11.8 kg moving, 5 kg fixed to the base"), "{out}");
}

const TWO_LINKS: &str = r#"<robot name="two">
  <link name="base"/>
  <link name="arm">
    <inertial><origin xyz="0.5 0 0"/><mass value="2"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.05" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="shoulder" type="continuous">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 AXIS"/>
  </joint>
</robot>"#;

#[test]
fn inspect_lists_every_warning() {
    let dir = scratch("inspect_warnings");
    // Axis of length 2: normalised, with a warning. Inertia 0.01, 0.01, 0.05:
    // 0.01 + 0.01 < 0.05 breaks the triangle inequality, another warning.
    let file = write(&dir, "warn.urdf", &TWO_LINKS.replace("AXIS", "2"));
    let out = succeeds(dynagen().arg("inspect").arg(&file));
    assert!(out.contains("warnings (2):"), "{out}");
    assert!(out.contains("warning: joint \"shoulder\": axis of length 2 normalised"), "{out}");
    assert!(out.contains("warning: link \"arm\": principal moments"), "{out}");
    assert!(out.lines().any(|l| l.contains("shoulder") && l.contains("continuous") && l.contains("(0, 0, 1)")));
    // eval on the same robot passes the warnings to stderr and still works.
    let states = write(&dir, "s.json", r#"{"states": [{"q": [0.5]}]}"#);
    let run = dynagen().args(["eval"]).arg(&file).arg("--input").arg(&states).output().unwrap();
    assert!(run.status.success());
    let stderr = String::from_utf8(run.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 2, "{stderr}");
    assert!(stderr.lines().all(|l| l.starts_with("warning: ") && l.contains("warn.urdf: ")), "{stderr}");
}

// ---------------------------------------------------------------- eval

/// Deterministic numbers in [-scale, scale) with all 53 bits used.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self, scale: f64) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * scale
    }
    fn vec(&mut self, n: usize, scale: f64) -> Vec<f64> {
        (0..n).map(|_| self.next(scale)).collect()
    }
}

/// A state with the fields given; each number written in a different text
/// form (shortest, exponent, 17 significant digits), all exact.
fn state_json(fields: &[(&str, &[f64])]) -> String {
    let num = |k: usize, x: f64| match k % 3 {
        0 => format!("{x:?}"),
        1 => format!("{x:e}"),
        _ => format!("{x:.16e}"),
    };
    let body: Vec<String> = fields
        .iter()
        .map(|(name, xs)| {
            let items: Vec<String> = xs.iter().enumerate().map(|(k, &x)| num(k, x)).collect();
            format!("\"{name}\": [{}]", items.join(", "))
        })
        .collect();
    format!("{{{}}}", body.join(", "))
}

fn bits_eq(what: &str, got: &Value, want: &[f64]) {
    let got: Vec<f64> = got
        .as_array()
        .unwrap_or_else(|| panic!("{what} is not an array"))
        .iter()
        .map(|v| v.as_f64().unwrap_or_else(|| panic!("{what}: {v} is not a number")))
        .collect();
    assert_eq!(got.len(), want.len(), "{what}");
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(g.to_bits(), w.to_bits(), "{what}[{k}]: {g:e} from the command, {w:e} from the library");
    }
}

type Fields = (Vec<f64>, Option<Vec<f64>>, Option<Vec<f64>>, Option<Vec<f64>>);

/// Checks one result object against the library on the same state: exactly
/// the outputs the state has inputs for, equal bit for bit.
fn check_result(robot: &mut Robot, r: &Value, (q, qd, qdd, tau): &Fields, i: usize) {
    let v = |x: &Vec<f64>| DVector::from_column_slice(x);
    let obj = r.as_object().unwrap();
    let mut expected_keys = vec!["M", "g"];
    let m = robot.mass_matrix(&v(q)).unwrap();
    let rows = obj["M"].as_array().unwrap();
    assert_eq!(rows.len(), robot.dof());
    for (row, json_row) in rows.iter().enumerate() {
        let want: Vec<f64> = m.row(row).iter().copied().collect();
        bits_eq(&format!("state {i} M[{row}]"), json_row, &want);
    }
    bits_eq(&format!("state {i} g"), &obj["g"], robot.gravity_torques(&v(q)).unwrap().as_slice());
    if let (Some(qd), Some(qdd)) = (qd, qdd) {
        expected_keys.push("tau");
        let want = robot.inverse_dynamics(&v(q), &v(qd), &v(qdd)).unwrap();
        bits_eq(&format!("state {i} tau"), &obj["tau"], want.as_slice());
    }
    if let Some(qd) = qd {
        expected_keys.push("h");
        let want = robot.bias_forces(&v(q), &v(qd)).unwrap();
        bits_eq(&format!("state {i} h"), &obj["h"], want.as_slice());
    }
    if let (Some(qd), Some(tau)) = (qd, tau) {
        expected_keys.push("qdd");
        let want = robot.forward_dynamics(&v(q), &v(qd), &v(tau)).unwrap();
        bits_eq(&format!("state {i} qdd"), &obj["qdd"], want.as_slice());
    }
    let mut keys: Vec<&str> = obj.keys().map(String::as_str).collect();
    keys.sort_unstable();
    expected_keys.sort_unstable();
    assert_eq!(keys, expected_keys, "state {i}: the outputs present");
}

/// States covering every combination of optional fields.
fn some_states(n: usize, seed: u64) -> Vec<Fields> {
    let mut rng = Lcg(seed);
    let mut states = Vec::new();
    for mask in 0..8u32 {
        for scale in [1.0, 50.0] {
            let q = rng.vec(n, 3.0 * scale);
            let qd = (mask & 1 != 0).then(|| rng.vec(n, 4.0 * scale));
            let qdd = (mask & 2 != 0).then(|| rng.vec(n, 10.0 * scale));
            let tau = (mask & 4 != 0).then(|| rng.vec(n, 100.0 * scale));
            states.push((q, qd, qdd, tau));
        }
    }
    states
}

fn states_file(states: &[Fields]) -> String {
    let items: Vec<String> = states
        .iter()
        .map(|(q, qd, qdd, tau)| {
            let mut f: Vec<(&str, &[f64])> = vec![("q", q)];
            // Field order varies: it must not matter.
            if let Some(x) = tau {
                f.push(("tau", x));
            }
            if let Some(x) = qdd {
                f.push(("qdd", x));
            }
            if let Some(x) = qd {
                f.push(("qd", x));
            }
            state_json(&f)
        })
        .collect();
    format!("{{\"states\": [\n  {}\n]}}\n", items.join(",\n  "))
}

#[test]
fn eval_on_the_bundled_ur5_agrees_bit_for_bit_with_the_library() {
    let dir = scratch("eval_bundled");
    let states = some_states(6, 1);
    let file = write(&dir, "states.json", &states_file(&states));
    let out = succeeds(dynagen().arg("eval").arg("--input").arg(&file));
    let doc: Value = serde_json::from_str(&out).unwrap();
    let mut robot = support::robot("ur5");
    let names: Vec<&str> = doc["joint_names"].as_array().unwrap().iter().map(|v| v.as_str().unwrap()).collect();
    assert_eq!(names, robot.joint_names());
    let results = doc["results"].as_array().unwrap();
    assert_eq!(results.len(), states.len());
    for (i, (r, s)) in results.iter().zip(&states).enumerate() {
        check_result(&mut robot, r, s, i);
    }
    // The same through stdin, and a mass matrix printed one row per line.
    let piped = succeeds(dynagen().args(["eval", "--input", "-"]).write_stdin(std::fs::read(&file).unwrap()));
    assert_eq!(piped, out);
    assert!(out.contains("      \"M\": [\n        ["), "{out}");
}

#[test]
fn eval_on_every_other_bundled_robot_agrees_bit_for_bit_with_the_library() {
    // The UR5 (default) and the Panda (with gravity) have their own tests.
    for name in ["torso_two_arms", "planar_2link"] {
        let dir = scratch(&format!("eval_{name}"));
        let path = format!("{ROBOTS}/{name}.urdf");
        let mut robot = Robot::from_urdf_file(&path).unwrap();
        let states = some_states(robot.dof(), 3);
        let file = write(&dir, "states.json", &states_file(&states));
        let doc: Value =
            serde_json::from_str(&succeeds(dynagen().args(["eval", &path, "--input"]).arg(&file))).unwrap();
        let names: Vec<&str> = doc["joint_names"].as_array().unwrap().iter().map(|v| v.as_str().unwrap()).collect();
        assert_eq!(names, robot.joint_names(), "{name}");
        let results = doc["results"].as_array().unwrap();
        assert_eq!(results.len(), states.len(), "{name}");
        for (i, (r, s)) in results.iter().zip(&states).enumerate() {
            check_result(&mut robot, r, s, i);
        }
    }
}

#[test]
fn eval_on_a_file_with_gravity_agrees_bit_for_bit_with_the_library() {
    let dir = scratch("eval_gravity");
    let path = format!("{ROBOTS}/panda.urdf");
    let mut robot = Robot::from_urdf_file(&path).unwrap();
    let states = some_states(robot.dof(), 2);
    let file = write(&dir, "states.json", &states_file(&states));
    // Negative first component: must not be taken for an option.
    let out = succeeds(dynagen().args(["eval", &path, "--gravity", "-1.5, 0.25,-9.80665", "--input"]).arg(&file));
    robot.set_gravity(Vector3::new(-1.5, 0.25, -9.80665)).unwrap();
    let doc: Value = serde_json::from_str(&out).unwrap();
    let names: Vec<&str> = doc["joint_names"].as_array().unwrap().iter().map(|v| v.as_str().unwrap()).collect();
    assert_eq!(names, robot.joint_names());
    for (i, (r, s)) in doc["results"].as_array().unwrap().iter().zip(&states).enumerate() {
        check_result(&mut robot, r, s, i);
    }
    // Gravity really changed the answer (g differs from the default's).
    let mut default = Robot::from_urdf_file(&path).unwrap();
    let q = DVector::from_column_slice(&states[0].0);
    let g_default = default.gravity_torques(&q).unwrap();
    let g_out: Vec<f64> = doc["results"][0]["g"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert!(g_out.iter().zip(g_default.iter()).any(|(a, b)| a != b));
}

#[test]
fn eval_accepts_integers_and_checks_joint_names() {
    let dir = scratch("eval_joint_names");
    let robot = support::robot("ur5");
    let names: Vec<String> = robot.joint_names().iter().map(|n| format!("\"{n}\"")).collect();
    let good = format!("{{\"joint_names\": [{}], \"states\": [{{\"q\": [0, 1, 0, 0, 0, 0]}}]}}", names.join(", "));
    let out = succeeds(dynagen().args(["eval", "--input", "-"]).write_stdin(good));
    let doc: Value = serde_json::from_str(&out).unwrap();
    let mut robot = support::robot("ur5");
    let g = robot.gravity_torques(&DVector::from_column_slice(&[0.0, 1.0, 0.0, 0.0, 0.0, 0.0])).unwrap();
    bits_eq("g", &doc["results"][0]["g"], g.as_slice());

    let mut swapped = names.clone();
    swapped.swap(1, 2);
    let bad = write(&dir, "order.json", &format!("{{\"joint_names\": [{}], \"states\": []}}", swapped.join(", ")));
    let e = fails(dynagen().args(["eval", "--input"]).arg(&bad), 1);
    assert!(e.contains("order.json: \"joint_names\"[1] is \"elbow_joint\""), "{e}");
}

// ---------------------------------------------------------------- errors

#[test]
fn a_missing_robot_file_is_one_line_naming_it() {
    for sub in [&["inspect"][..], &["eval", "--input", "-"]] {
        let e = fails(dynagen().args(sub).arg("no/such/robot.urdf").write_stdin("{\"states\": []}"), 1);
        assert!(e.starts_with("error: no/such/robot.urdf: cannot read the file"), "{e}");
    }
}

#[test]
fn a_malformed_urdf_is_one_line_naming_the_file() {
    let dir = scratch("bad_urdf");
    let file = write(&dir, "broken.urdf", "<robot name=\"x\">\n  <link name=\"a\">\n</robot>\n");
    let e = fails(dynagen().arg("inspect").arg(&file), 1);
    assert!(e.contains("broken.urdf: malformed URDF"), "{e}");
}

#[test]
fn a_bad_urdf_names_the_file_and_the_joint_or_link() {
    let dir = scratch("bad_joint");
    let zero = write(&dir, "zero.urdf", &TWO_LINKS.replace("0 0 AXIS", "0 0 0"));
    let e = fails(dynagen().arg("inspect").arg(&zero), 1);
    assert_eq!(e, format!("error: {}: joint \"shoulder\": the axis is zero", zero.display()));
    let heavy = write(&dir, "neg.urdf", &TWO_LINKS.replace("AXIS", "1").replace("value=\"2\"", "value=\"-2\""));
    let states = write(&dir, "s.json", r#"{"states": [{"q": [0]}]}"#);
    let e = fails(dynagen().arg("eval").arg(&heavy).arg("--input").arg(&states), 1);
    assert!(e.starts_with(&format!("error: {}: link \"arm\": negative mass", heavy.display())), "{e}");
}

/// Runs eval on the bundled UR5 with this input file and returns the error.
fn eval_error(test: &str, json: &str) -> String {
    let dir = scratch(test);
    write(&dir, "states.json", json);
    fails(dynagen().args(["eval", "--input", "states.json"]).current_dir(&dir), 1)
}

#[test]
fn a_state_of_the_wrong_length_names_the_file_state_and_field() {
    let ok = "\"q\": [0, 0, 0, 0, 0, 0]";
    let json = format!("{{\"states\": [{{{ok}}}, {{{ok}}}, {{{ok}}}, {{{ok}, \"qd\": [1, 2, 3, 4, 5]}}]}}");
    let e = eval_error("wrong_length", &json);
    assert!(e.ends_with("states.json: state 3: \"qd\" has 5 entries, the robot has 6 joints"), "{e}");
}

#[test]
fn non_numbers_in_a_state_name_the_entry_and_its_joint() {
    let cases = [
        (r#"{"states": [{"q": [0, 0, "x", 0, 0, 0]}]}"#, "state 0: \"q\"[2] (joint \"elbow_joint\") is a string"),
        (r#"{"states": [{"q": [0, 0, 0, 0, null, 0]}]}"#, "state 0: \"q\"[4] (joint \"wrist_2_joint\") is null"),
        (
            r#"{"states": [{"q": [0, 0, 0, 0, 0, 0], "qd": [true, 0, 0, 0, 0, 0]}]}"#,
            "\"qd\"[0] (joint \"shoulder_pan_joint\") is a boolean",
        ),
        (r#"{"states": [{"q": [0, 0, 0, 0, 0, 0], "qd": null}]}"#, "state 0: \"qd\" is null"),
        (r#"{"states": [{"q": [0, 0, 0, 0, 0, 0], "tau": "fast"}]}"#, "state 0: \"tau\" must be an array"),
        // JSON has no NaN or infinity; a number beyond f64 is refused and located.
        (
            r#"{"states": [{"q": [0, 0, 0, 0, 0, 0]}, {"q": [0, 0, 0, 1e999, 0, 0]}]}"#,
            "state 1: \"q\"[3] (joint \"wrist_1_joint\"): a number too large for f64",
        ),
        (
            r#"{"states": [{"q": [0, 0, 0, 0, 0, 0], "qdd": [NaN, 0, 0, 0, 0, 0]}]}"#,
            "state 0: \"qdd\"[0] (joint \"shoulder_pan_joint\"): malformed JSON",
        ),
        (r#"{"states": [{"q": [0, 0, 0, 0, 0, 0], "qdot": [0, 0, 0, 0, 0, 0]}]}"#, "state 0: unknown field \"qdot\""),
        (r#"{"states": [{"qd": [0, 0, 0, 0, 0, 0]}]}"#, "state 0: \"q\" is missing"),
        (r#"{"states": [{"q": [0, 0, 0, 0, 0, 0]}, 7]}"#, "state 1: expected an object"),
        (r#"{"state": []}"#, "unknown top-level field \"state\""),
        (r#"{"states": [{"q": [0, 0, 0,"#, "state 0: \"q\"[3] (joint \"wrist_1_joint\"): malformed JSON: EOF"),
        // Finite inputs whose outputs overflow f64: refused, not printed as null.
        (
            r#"{"states": [{"q": [0, 0, 0, 0, 0, 0], "qd": [1e200, 1e200, 1e200, 1e200, 1e200, 1e200]}]}"#,
            "state 0: output \"h\"",
        ),
    ];
    for (k, (json, item)) in cases.iter().enumerate() {
        let e = eval_error(&format!("non_numbers_{k}"), json);
        assert!(e.starts_with("error: states.json: "), "{e}");
        assert!(e.contains(item), "case {k}: {e:?} lacks {item:?}");
    }
}

#[test]
fn a_missing_or_malformed_states_file_is_named() {
    let e = fails(dynagen().args(["eval", "--input", "no_such_states.json"]), 1);
    assert!(e.starts_with("error: no_such_states.json: cannot read the file"), "{e}");
    let e = fails(dynagen().args(["eval", "--input", "-"]).write_stdin("{\"states\": [}"), 1);
    assert!(e.starts_with("error: <stdin>: state 0: malformed JSON: expected value at line 1 column 13"), "{e}");
}

#[test]
fn a_bad_gravity_is_one_line_naming_the_option() {
    for (g, why) in [
        ("0,-9.81", "expected three numbers X,Y,Z"),
        ("0;0;-9.81", "expected three numbers X,Y,Z"),
        ("0,0,down", "Z = \"down\" is not a number"),
        ("nan,0,0", "X = \"nan\" is not a finite number"),
    ] {
        let e = fails(dynagen().args(["eval", "--input", "-", "--gravity", g]).write_stdin("{\"states\": []}"), 1);
        assert!(e.starts_with(&format!("error: --gravity \"{g}\": {why}")), "{e}");
    }
}

// A full report takes minutes: these tests run `dynagen report` only as far
// as its argument parsing and its errors.

#[test]
fn report_help_names_its_options_and_the_program_it_runs() {
    let help = succeeds(dynagen().args(["report", "--help"]));
    for what in ["--quick", "--out", "dynagen-report", "DYNAGEN_WORKSPACE"] {
        assert!(help.contains(what), "`dynagen report --help` does not mention {what}:\n{help}");
    }
    let out = dynagen().args(["report", "--slow"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "an unknown option is a command-line error");
}

#[test]
fn report_without_a_workspace_says_what_to_run() {
    let dir = scratch("report_no_workspace");
    let e = fails(dynagen().args(["report", "--quick"]).env("DYNAGEN_WORKSPACE", &dir), 1);
    assert!(e.starts_with(&format!("error: {}: no dynagen workspace here", dir.display())), "{e}");
    assert!(e.contains("`cargo run --release -p dynagen-report -- --quick`"), "{e}");
}

#[test]
fn report_without_cargo_says_what_to_run() {
    let dir = scratch("report_no_cargo");
    let missing = dir.join("no-such-cargo");
    let e = fails(dynagen().args(["report", "--out", "somewhere"]).env("CARGO", &missing), 1);
    assert!(e.starts_with(&format!("error: {}: cannot run cargo", missing.display())), "{e}");
    assert!(e.contains("`cargo run --release -p dynagen-report -- --out somewhere`"), "{e}");
    assert!(!dir.join("somewhere").exists());
}

/// A stand-in for cargo: records its working directory and arguments in
/// `record`, then exits with `status`.
#[cfg(unix)]
fn fake_cargo(dir: &Path, record: &Path, status: i32) -> PathBuf {
    use std::os::unix::fs::PermissionsExt;
    let script = format!("#!/bin/sh\necho \"$PWD $*\" > '{}'\nexit {status}\n", record.display());
    let path = write(dir, "fake-cargo", &script);
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    path
}

#[cfg(unix)]
#[test]
fn report_runs_the_report_program_in_the_workspace_with_the_callers_directory() {
    let dir = scratch("report_fake_cargo");
    let record = dir.join("args.txt");
    let cargo = fake_cargo(&dir, &record, 0);
    let out =
        dynagen().current_dir(&dir).args(["report", "--quick", "--out", "mine"]).env("CARGO", &cargo).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let want = format!(
        "{} run --release -p dynagen-report -- --out {} --quick",
        workspace.canonicalize().unwrap().display(),
        dir.join("mine").display()
    );
    assert_eq!(std::fs::read_to_string(&record).unwrap().trim(), want);

    // The report's failure is dynagen's, with the command to run by hand.
    let cargo = fake_cargo(&dir, &record, 4);
    let e = fails(dynagen().args(["report"]).env("CARGO", &cargo), 1);
    assert!(e.starts_with("error: the report failed (exit status: 4)"), "{e}");
    assert!(e.ends_with("`cargo run --release -p dynagen-report`"), "{e}");
}

// ---------------------------------------------------------------- generate

/// Runs and returns (stdout, stderr) of a success.
fn succeeds_with_stderr(cmd: &mut Command) -> (String, String) {
    let out = cmd.output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "stderr: {stderr}");
    (String::from_utf8(out.stdout).unwrap(), stderr)
}

#[test]
fn generate_to_stdout_and_to_a_file_equal_the_library_output() {
    use dynagen::codegen::{generate, CodegenOptions, Function, ScalarType};
    let dir = scratch("generate");
    let urdf = format!("{ROBOTS}/planar_2link.urdf");
    let model = dynagen::Model::from_urdf_file(&urdf).unwrap();

    // stdout: the whole module; stderr: one op-count line per traced function.
    let (stdout, stderr) = succeeds_with_stderr(dynagen().arg("generate").arg(&urdf));
    let want = generate(&model, &CodegenOptions::default().source(urdf.clone())).unwrap();
    assert_eq!(stdout, want.source);
    // Without --trig: the library's default, the module's own batched sines and cosines (no std).
    assert!(stdout.contains("= sin_cos_array(&[") && !stdout.contains(".sin_cos()"), "{stdout}");
    // --trig std: std's sin_cos, as the library gives it.
    let with_std = succeeds(dynagen().arg("generate").arg(&urdf).args(["--trig", "std"]));
    let opts = CodegenOptions::default().source(urdf.clone()).trig(dynagen::codegen::Trig::Std);
    assert_eq!(with_std, generate(&model, &opts).unwrap().source);
    assert!(with_std.contains(".sin_cos();") && !with_std.contains("= sin_cos_array(&["), "{with_std}");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), want.functions.len(), "{stderr}");
    for (line, f) in lines.iter().zip(&want.functions) {
        assert!(line.starts_with(&f.label()) && line.ends_with(&f.op_count.to_string()), "{line}");
    }

    // -o FILE with options: nothing on stdout, the file is the library's
    // source for the same options.
    let out = dir.join("planar.rs");
    let (stdout, stderr) = succeeds_with_stderr(
        dynagen()
            .arg("generate")
            .arg(&urdf)
            .args(["--functions", "mass_matrix,gravity_torques", "--f32", "-o"])
            .arg(&out),
    );
    assert!(stdout.is_empty());
    assert!(stderr.contains("wrote ") && stderr.contains("mass_matrix: "), "{stderr}");
    let opts = CodegenOptions::default()
        .source(urdf.clone())
        .scalar(ScalarType::F32)
        .functions(["mass_matrix", "gravity_torques"].map(|n| Function::from_name(n).unwrap()));
    let written = std::fs::read_to_string(&out).unwrap();
    assert_eq!(written, generate(&model, &opts).unwrap().source);
    assert!(written.contains("pub fn mass_matrix(q: &[f32; DOF]) -> [[f32; DOF]; DOF]"));
    assert!(!written.contains("pub fn inverse_dynamics"));

    // --no-dispatch and --no-fma: the library's source with those options off.
    let stdout = succeeds(dynagen().arg("generate").arg(&urdf).args(["--no-dispatch", "--no-fma"]));
    let opts = CodegenOptions::default().source(urdf.clone()).runtime_dispatch(false).fma(false);
    assert_eq!(stdout, generate(&model, &opts).unwrap().source);
    let (bodies, kernel) = stdout.split_once("const RUNTIME_DISPATCH: bool = false;").expect("the kernel's switch off");
    assert!(bodies.contains("// Run-time dispatch: off") && !bodies.contains("_avx2_fma("), "{bodies}");
    assert!(kernel.contains("if RUNTIME_DISPATCH && has_avx2_and_fma()"));

    // Without a file: the bundled UR5, named as such in the header.
    let stdout = succeeds(dynagen().arg("generate").current_dir(&dir));
    assert!(stdout.contains("// Model source: ur5.urdf (bundled)") && stdout.contains("pub const DOF: usize = 6;"));
}

#[test]
fn generate_errors_are_one_line_naming_the_option_or_file() {
    let dir = scratch("generate_errors");
    let e = fails(dynagen().args(["generate", "--functions", "mass_matrix,jacobian"]), 1);
    assert!(e.contains("--functions") && e.contains("unknown function \"jacobian\""), "{e}");
    let e = fails(dynagen().args(["generate", "nowhere.urdf"]), 1);
    assert!(e.starts_with("error: nowhere.urdf: cannot read"), "{e}");
    let out = succeeds(dynagen().args(["generate", "--no-std"]));
    assert!(out.contains("pub fn sin_cos_all") && !out.contains(".sin_cos()"), "--no-std must not call std's sin_cos");
    let out = succeeds(dynagen().args(["generate", "--trig", "inputs"]));
    assert!(out.contains("pub fn inverse_dynamics_sc") && !out.contains("pub fn inverse_dynamics("), "{out}");
    let e = fails(dynagen().args(["generate", "--trig", "fast"]), 1);
    // The option, then the value and the spellings accepted, as Trig's FromStr says them.
    assert!(e.contains("--trig: ") && e.contains("unknown trigonometry \"fast\"") && e.contains("batched"), "{e}");
    // A scene that does not fit the robot: exit 1, one line naming the
    // scene file and the joint.
    let scene = write(&dir, "scene.toml", "[joints.elbow_jiont]\nlock = 0.5\n");
    let e = fails(dynagen().arg("generate").arg("--scene").arg(&scene), 1);
    assert!(e.starts_with("error: scene ") && e.contains("scene.toml") && e.contains("\"elbow_jiont\""), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    // A malformed scene: the key.
    let scene = write(&dir, "typo.toml", "[gravity]\nmode = \"none\"\nvectr = [0, 0, 1]\n");
    let e = fails(dynagen().arg("generate").arg("--scene").arg(&scene), 1);
    assert!(e.contains("typo.toml") && e.contains("vectr"), "{e}");
    let e = fails(dynagen().args(["generate", "--scene", "no/such/scene.toml"]), 1);
    assert!(e.contains("no/such/scene.toml"), "{e}");
    // Gravity none and only τ: fewer operations than the default, no M.
    let scene = write(&dir, "tau.toml", "functions = [\"inverse_dynamics\"]\n[gravity]\nmode = \"none\"\n");
    let (out, err) = succeeds_with_stderr(dynagen().arg("generate").arg("--scene").arg(&scene));
    assert!(out.contains("pub fn inverse_dynamics(") && !out.contains("fn mass_matrix"), "{out}");
    assert!(out.contains("//   gravity: none"), "{out}");
    let ops = |stderr: &str| -> usize {
        let line = stderr.lines().find(|l| l.starts_with("inverse_dynamics: ")).unwrap_or_else(|| panic!("{stderr}"));
        line["inverse_dynamics: ".len()..].split(' ').next().unwrap().parse().unwrap()
    };
    let (_, full) = succeeds_with_stderr(dynagen().arg("generate"));
    assert!(ops(&err) < ops(&full), "{err}\n{full}");
    // coriolis without a scene: the default scene's module.
    let out = succeeds(dynagen().args(["generate", "--functions", "coriolis,inverse_dynamics"]));
    assert!(out.contains("pub fn coriolis(q: &[f64; DOF], qd: &[f64; DOF])") && !out.contains("fn mass_matrix"));
    // The bundled controller scene.
    let out = succeeds(dynagen().args(["generate", "--scene"]).arg(support::scene_path("ur5_controller")));
    assert!(out.contains("in the scene \"ur5_controller\""), "{out}");
    assert!(out.contains("f_tip: &[f64; 6]") && out.contains("pub fn frame_jacobian_ee_link("), "{out}");
    assert!(out.contains("//   functions not generated: coriolis"), "{out}");
    // A scene that only picks functions and the scalar is honoured.
    let scene = write(&dir, "plain.toml", "functions = [\"mass_matrix\"]\nscalar = \"f32\"\n");
    let out = succeeds(dynagen().arg("generate").arg("--scene").arg(&scene));
    assert!(out.contains("pub fn mass_matrix(q: &[f32; DOF])") && !out.contains("pub fn bias_forces"), "{out}");
    let e = fails(dynagen().arg("generate").arg("-o").arg(dir.join("no/such/dir/x.rs")), 1);
    assert!(e.contains("cannot write the file"), "{e}");
}

// ---------------------------------------------------------------- ops

#[test]
fn ops_lists_generated_and_generic_counts() {
    use dynagen::codegen::{generate, generic_op_count, CodegenOptions, ForwardDynamicsMethod};
    let urdf = format!("{ROBOTS}/ur5.urdf");
    let model = dynagen::Model::from_urdf_file(&urdf).unwrap();
    let module = generate(&model, &CodegenOptions::default()).unwrap();
    let out = succeeds(dynagen().arg("ops").arg(&urdf));
    assert!(out.starts_with(&format!("robot \"ur5\" from {urdf}: 6 joints\n")), "{out}");
    for f in &module.functions {
        let generic = generic_op_count(&model, &f.function, f.method.unwrap_or(ForwardDynamicsMethod::Auto)).unwrap();
        let label = f.label();
        let row = out.lines().find(|l| l.starts_with(&label)).unwrap_or_else(|| panic!("{out}"));
        let cols: Vec<&str> = row[label.len()..].split_whitespace().collect();
        assert_eq!(cols[0], f.op_count.arithmetic().to_string(), "{row}");
        assert_eq!(cols[1], generic.arithmetic().to_string(), "{row}");
        // Fused multiply-adds are on by default: how many, and the
        // operations with each fused one counted once.
        assert_eq!(cols[5], f.op_count.fused.to_string(), "{row}");
        assert_eq!(cols[6], f.op_count.fp_ops().to_string(), "{row}");
        assert!(f.op_count.fused > 0 && f.op_count.fp_ops() < f.op_count.arithmetic(), "{row}");
        // The multiplications executed: more than the products computed on
        // their own (the fused ones count), fewer than the traced ones.
        assert_eq!(cols[7], f.op_count.multiplies().to_string(), "{row}");
        assert!(f.op_count.multiplies() > f.op_count.mul - f.op_count.mul_folded, "{row}");
        assert!(f.op_count.multiplies() < f.op_count.mul + f.op_count.fused, "{row}");
        // The generic recursion does every multiplication by a model
        // constant at run time: the generated code must do fewer.
        assert!(f.op_count.arithmetic() < generic.arithmetic(), "{row}");
    }
    let e = fails(dynagen().args(["ops", "nowhere.urdf"]), 1);
    assert!(e.starts_with("error: nowhere.urdf: cannot read"), "{e}");
}

#[test]
fn ops_with_a_scene_lists_the_scene_module_beside_the_full_one() {
    use dynagen::codegen::{generate, generate_scene, CodegenOptions};
    use dynagen::scene::SceneFile;
    let dir = scratch("ops_scene");
    let urdf = format!("{ROBOTS}/ur5.urdf");
    let model = dynagen::Model::from_urdf_file(&urdf).unwrap();
    let text = "functions = [\"inverse_dynamics\", \"gravity_torques\"]\nframe_pose = [\"ee_link\"]\n[gravity]\nmode = \"none\"\n[joints.wrist_3_joint]\nlock = 0.0\n";
    let scene = write(&dir, "light.toml", text);
    let out = succeeds(dynagen().arg("ops").arg(&urdf).arg("--scene").arg(&scene));
    let full = generate(&model, &CodegenOptions::default()).unwrap();
    let file = SceneFile::from_toml_str(text).unwrap();
    let applied = file.scene.apply(&model).unwrap();
    let reduced = generate_scene(&applied, &file.code.apply(CodegenOptions::default())).unwrap();
    let row = |name: &str| -> Vec<String> {
        let line = out.lines().find(|l| l.split_whitespace().next() == Some(name)).unwrap_or_else(|| panic!("{out}"));
        line.split_whitespace().skip(1).map(str::to_string).collect()
    };
    let tau = row("inverse_dynamics");
    let scene_tau = reduced.function("inverse_dynamics").unwrap().op_count.arithmetic();
    let full_tau = full.function("inverse_dynamics").unwrap().op_count.arithmetic();
    assert_eq!(tau[0], scene_tau.to_string(), "{out}");
    assert_eq!(tau[1], full_tau.to_string(), "{out}");
    // No gravity and a locked joint: τ is cheaper than the full module's.
    assert!(scene_tau < full_tau, "{out}");
    assert_eq!(tau[2], format!("{:+}", scene_tau as i64 - full_tau as i64), "{out}");
    // g without gravity is zero: no operation at all.
    assert_eq!(row("gravity_torques")[0], "0", "{out}");
    // A frame function has no counterpart in the full module.
    assert_eq!(row("frame_pose_ee_link")[1..], ["-", "-"], "{out}");
    assert!(!out.contains("mass_matrix"), "{out}");
    let e = fails(dynagen().args(["ops", "--scene", "no/such/scene.toml"]), 1);
    assert!(e.contains("no/such/scene.toml"), "{e}");
}

/// `eval --derivatives`: the derivatives each state has the inputs for,
/// `[output][input]` one row per line, bit for bit the library's; M·M⁻¹ = 1
/// from the printed matrices; without the flag, none of them.
/// Random states of the Panda for `test` (seeded): the states, their file,
/// and the Panda's URDF path.
fn panda_states(test: &str, seed: u64) -> (Vec<Fields>, PathBuf, String) {
    let dir = scratch(test);
    let states = some_states(9, seed);
    let file = write(&dir, "states.json", &states_file(&states));
    (states, file, support::robot_path("panda").display().to_string())
}

#[test]
fn eval_derivatives_agree_bit_for_bit_with_the_library() {
    let (states, file, path) = panda_states("eval_derivatives", 16);
    let plain = succeeds(dynagen().args(["eval", &path, "--input"]).arg(&file));
    assert!(!plain.contains("dtau_dq") && !plain.contains("minv"));
    let out = succeeds(dynagen().args(["eval", &path, "--derivatives", "--input"]).arg(&file));
    let doc: Value = serde_json::from_str(&out).unwrap();
    let mut robot = support::robot("panda");
    let n = robot.dof();
    let v = |x: &Vec<f64>| DVector::from_column_slice(x);
    let rows_eq = |what: &str, got: &Value, want: &nalgebra::DMatrix<f64>| {
        let rows = got.as_array().unwrap_or_else(|| panic!("{what} missing"));
        assert_eq!(rows.len(), n, "{what}");
        for (r, row) in rows.iter().enumerate() {
            bits_eq(&format!("{what}[{r}]"), row, &want.row(r).iter().copied().collect::<Vec<_>>());
        }
    };
    let matrix = |x: &Value| {
        let rows: Vec<Vec<f64>> = x
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect())
            .collect();
        nalgebra::DMatrix::from_fn(n, n, |i, j| rows[i][j])
    };
    let mut counted = [0; 2];
    for (i, (r, (q, qd, qdd, tau))) in doc["results"].as_array().unwrap().iter().zip(&states).enumerate() {
        let obj = r.as_object().unwrap();
        assert_eq!(obj.contains_key("dtau_dq"), qd.is_some() && qdd.is_some(), "state {i}");
        assert_eq!(obj.contains_key("minv"), qd.is_some() && tau.is_some(), "state {i}");
        if let (Some(qd), Some(qdd)) = (qd, qdd) {
            let (a, b) = robot.inverse_dynamics_derivatives(&v(q), &v(qd), &v(qdd)).unwrap();
            rows_eq(&format!("state {i} dtau_dq"), &obj["dtau_dq"], &a);
            rows_eq(&format!("state {i} dtau_dqd"), &obj["dtau_dqd"], &b);
            counted[0] += 1;
        }
        if let (Some(qd), Some(tau)) = (qd, tau) {
            let (a, b, c) = robot.forward_dynamics_derivatives(&v(q), &v(qd), &v(tau)).unwrap();
            rows_eq(&format!("state {i} dqdd_dq"), &obj["dqdd_dq"], &a);
            rows_eq(&format!("state {i} dqdd_dqd"), &obj["dqdd_dqd"], &b);
            rows_eq(&format!("state {i} minv"), &obj["minv"], &c);
            let eye = matrix(&obj["M"]) * matrix(&obj["minv"]);
            let e = (eye - nalgebra::DMatrix::identity(n, n)).norm();
            assert!(e < 1e-9, "state {i}: M·M⁻¹ − 1 = {e:e}");
            counted[1] += 1;
        }
    }
    assert!(counted[0] > 0 && counted[1] > 0, "{counted:?}");
    assert!(out.contains("      \"dtau_dq\": [\n        ["), "{out}");
}

/// `--floating-base` on the commands that load a robot: `generate` writes
/// the NQ/NV module (and a floating scene's, with contact frames), `ops`
/// counts it against the floating-base recursion, `inspect` says it
/// floats, `eval` takes NQ/NV-long states (checked below).
#[test]
fn floating_base_on_the_command_line() {
    let quad = support::robot_path("quadruped12");
    let out = succeeds(dynagen().args(["generate", quad.to_str().unwrap(), "--floating-base"]));
    assert!(out.contains("pub const NQ: usize = 19;") && out.contains("pub const NV: usize = 18;"));
    assert!(out.contains("pub fn inverse_dynamics(q: &[f64; NQ], qd: &[f64; NV], qdd: &[f64; NV]) -> [f64; NV]"));
    let fixed = succeeds(dynagen().args(["generate", quad.to_str().unwrap()]));
    assert!(fixed.contains("pub const NQ: usize = DOF;"));
    let ops = succeeds(dynagen().args(["ops", quad.to_str().unwrap(), "--floating-base"]));
    let row = ops.lines().find(|l| l.starts_with("mass_matrix")).expect("a mass_matrix row");
    let counts: Vec<usize> = row.split_whitespace().skip(1).take(2).map(|x| x.parse().unwrap()).collect();
    assert!(counts[0] > 0 && counts[1] > counts[0], "generated and generic counts: {row}");
    let inspect = succeeds(dynagen().args(["inspect", quad.to_str().unwrap(), "--floating-base"]));
    assert!(inspect.contains("a floating base (the root link moves freely): q has NQ = 19 entries"), "{inspect}");
    assert!(inspect.contains("  trunk (floating base)") && inspect.contains("m/s² in the world frame"), "{inspect}");
    let lm = support::robot_path("legged_manipulator");
    let scene = support::scene_path("legged_manipulator");
    let (lm, scene) = (lm.to_str().unwrap(), scene.to_str().unwrap());
    let out = succeeds(dynagen().args(["generate", lm, "--floating-base", "--scene", scene]));
    assert!(out.contains("pub fn frame_acceleration_bias_fl_foot(q: &[f64; NQ], qd: &[f64; NV]) -> [f64; 6]"));
    assert!(out.contains("// Run-time inputs: f_tip: &[T; 6] (m; f) at frame \"arm_ee\""), "{out}");
    let ops = succeeds(dynagen().args(["ops", lm, "--floating-base", "--scene", scene]));
    assert!(ops.contains("frame_acceleration_bias_rr_foot"), "{ops}");
}

/// The legged manipulator's Pinocchio data (free-flyer root) as `dynagen
/// eval` input: with `--floating-base`, or a URDF whose root joint is
/// `floating`, τ, M, h, g and q̈ agree with Pinocchio's within 1e-12; the
/// errors name NQ/NV, the base's entries and the quaternion.
#[test]
fn eval_takes_floating_base_states() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(dir.join("tests/data/pinocchio_floating_legged_manipulator.json")).unwrap();
    let data: Value = serde_json::from_str(&text).unwrap();
    let states: Vec<Value> = data["states"].as_array().unwrap()[..4]
        .iter()
        .map(|s| serde_json::json!({"q": s["q"], "qd": s["qd"], "qdd": s["qdd"], "tau": s["tau"]}))
        .collect();
    let input = serde_json::json!({ "states": states }).to_string();
    let lm = support::robot_path("legged_manipulator");
    let with_flag = succeeds(
        dynagen().args(["eval", lm.to_str().unwrap(), "--floating-base", "--input", "-"]).write_stdin(input.clone()),
    );
    // the same robot floated by its file: a world link and a floating joint
    let dir = scratch("eval_takes_floating_base_states");
    let floated = dir.join("floated.urdf");
    let urdf = std::fs::read_to_string(&lm).unwrap().replace(
        "<robot name=\"legged_manipulator\">",
        "<robot name=\"legged_manipulator\"><link name=\"world\"/><joint name=\"root\" type=\"floating\">\
         <parent link=\"world\"/><child link=\"trunk\"/></joint>",
    );
    std::fs::write(&floated, urdf).unwrap();
    let by_file =
        succeeds(dynagen().args(["eval", floated.to_str().unwrap(), "--input", "-"]).write_stdin(input.clone()));
    assert_eq!(by_file, with_flag);
    let out: Value = serde_json::from_str(&with_flag).unwrap();
    assert_eq!(out["joint_names"].as_array().unwrap().len(), 18);
    // every number of a value, rows flattened
    fn flat(v: &Value) -> Vec<f64> {
        match v {
            Value::Array(a) => a.iter().flat_map(flat).collect(),
            x => vec![x.as_f64().unwrap()],
        }
    }
    for (k, (got, want)) in
        out["results"].as_array().unwrap().iter().zip(data["states"].as_array().unwrap()).enumerate()
    {
        for (field, key) in [("tau", "tau_id"), ("M", "M"), ("h", "h"), ("g", "g"), ("qdd", "qdd_fd")] {
            let (g, w) = (flat(&got[field]), flat(&want[key]));
            assert_eq!(g.len(), w.len(), "{field}");
            let scale = w.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            let e = g.iter().zip(&w).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
            assert!(e < 1e-12, "state {k}: {field} differs from Pinocchio by {e:e}");
        }
    }
    // errors: NQ and NV named, the base's entries named, the quaternion checked
    let lm = lm.to_str().unwrap();
    let eval = |states: &str| {
        fails(dynagen().args(["eval", lm, "--floating-base", "--input", "-"]).write_stdin(states.to_string()), 1)
    };
    let zeros = |n: usize| format!("[{}]", vec!["0"; n].join(", "));
    let e = eval(&format!("{{\"states\": [{{\"q\": {}}}]}}", zeros(18)));
    assert!(e.contains("\"q\" has 18 entries, a floating-base q has NQ = 25"), "{e}");
    let e = eval(&format!("{{\"states\": [{{\"q\": {}, \"qd\": {}}}]}}", zeros(25), zeros(18)));
    assert!(e.contains("\"qd\" has 18 entries, a floating-base \"qd\" has NV = 24"), "{e}");
    let mut q: Vec<String> = vec!["0".into(); 25];
    q[4] = "\"y\"".into();
    let e = eval(&format!("{{\"states\": [{{\"q\": [{}]}}]}}", q.join(", ")));
    assert!(e.contains("state 0: \"q\"[4] (base quaternion y) is a string"), "{e}");
    let e = eval(&format!("{{\"states\": [{{\"q\": {}}}]}}", zeros(25)));
    assert!(e.contains("state 0: q[3..7], the base's quaternion (x, y, z, w), has norm 0"), "{e}");
    q[4] = "0".into();
    q[6] = "1.01".into();
    let e = eval(&format!("{{\"states\": [{{\"q\": [{}]}}]}}", q.join(", ")));
    assert!(e.contains("has norm 1.01, but it must be 1"), "{e}");
}

/// `eval --fd`: the forward dynamics behind "qdd" is the library's method
/// of that name, bit for bit (the default the articulated-body algorithm);
/// on a cancelling state of a test robot with its 50-digit reference
/// (`tests/data/file_precision.json`) the compensated method is the
/// accurate one; an unknown method is a usage error listing the four.
#[test]
fn eval_fd_picks_the_forward_dynamics() {
    let (states, file, path) = panda_states("eval_fd", 21);
    let run = |method: Option<&str>| -> Value {
        let mut cmd = dynagen();
        cmd.args(["eval", &path, "--input"]).arg(&file);
        if let Some(m) = method {
            cmd.args(["--fd", m]);
        }
        serde_json::from_str(&succeeds(&mut cmd)).unwrap()
    };
    assert_eq!(run(None), run(Some("aba")), "the default is aba");
    let v = |x: &Vec<f64>| DVector::from_column_slice(x);
    let mut counted = 0;
    for method in ["aba", "ldlt", "compensated", "refined"] {
        let doc = run(Some(method));
        let mut robot = support::robot("panda");
        if method == "refined" {
            robot.set_compensated_refinement(1);
        }
        for (i, (r, (q, qd, _, tau))) in doc["results"].as_array().unwrap().iter().zip(&states).enumerate() {
            let (Some(qd), Some(tau)) = (qd, tau) else { continue };
            let want = match method {
                "aba" => robot.forward_dynamics(&v(q), &v(qd), &v(tau)),
                "ldlt" => robot.forward_dynamics_ldlt(&v(q), &v(qd), &v(tau)),
                _ => robot.forward_dynamics_compensated(&v(q), &v(qd), &v(tau)),
            }
            .unwrap();
            bits_eq(&format!("--fd {method} state {i} qdd"), &r["qdd"], want.as_slice());
            counted += 1;
        }
    }
    assert!(counted >= 16, "{counted}");

    // A cancelling state of the 8-joint test chain: ABA loses digits, compensated does not.
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(data.join("file_precision.json")).unwrap()).unwrap();
    let robot = &json["robots"][0];
    let chain = data.join(robot["urdf"].as_str().unwrap());
    let state = robot["states"].as_array().unwrap().iter().find(|s| s["kind"] == "cancelling").unwrap();
    let input =
        format!("{{\"states\": [{{\"q\": {}, \"qd\": {}, \"tau\": {}}}]}}", state["q"], state["qd"], state["tau"]);
    let reference: Vec<f64> =
        state["qdd"].as_array().unwrap().iter().map(|x| x.as_str().unwrap().parse().unwrap()).collect();
    let error = |method: &str| {
        let mut cmd = dynagen();
        let out =
            succeeds(cmd.arg("eval").arg(&chain).args(["--fd", method, "--input", "-"]).write_stdin(input.clone()));
        let doc: Value = serde_json::from_str(&out).unwrap();
        let qdd: Vec<f64> = doc["results"][0]["qdd"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        support::norm_rel_err(&qdd, &reference, 0.0)
    };
    let (aba, compensated) = (error("aba"), error("compensated"));
    assert!(100.0 * compensated < aba, "compensated {compensated:e} against ABA {aba:e}");

    let out = dynagen().args(["eval", "--fd", "rk4", "--input", "-"]).write_stdin("{\"states\": []}").output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("rk4") && stderr.contains("aba, ldlt, compensated, refined"), "{stderr}");
}
