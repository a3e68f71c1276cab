//! The `dynagen` command on files other tools write: a non-physical inertia
//! refused with the option named, and accepted with it; dependent joints
//! named by `eval`; JSON states with a duplicate key refused, with a
//! byte-order mark accepted.

use assert_cmd::Command;
use std::path::{Path, PathBuf};

fn dynagen() -> Command {
    Command::cargo_bin("dynagen").expect("the dynagen binary is built for integration tests")
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_files").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// (exit status, stdout, stderr)
fn run(cmd: &mut Command) -> (i32, String, String) {
    let out = cmd.output().unwrap();
    let text = |b: Vec<u8>| String::from_utf8(b).unwrap();
    (out.status.code().unwrap_or(-1), text(out.stdout), text(out.stderr))
}

#[test]
fn a_nonphysical_inertia_needs_the_option_and_is_then_loaded_with_a_warning() {
    let urdf = data("nonphysical_inertia.urdf");
    for command in ["inspect", "ops"] {
        let (status, stdout, stderr) = run(dynagen().arg(command).arg(&urdf));
        assert_eq!(status, 1, "{command}: {stderr}");
        assert!(stdout.is_empty());
        assert!(
            stderr.starts_with("error: ")
                && stderr.contains("link \"utorso\"")
                && stderr.contains("--allow-nonphysical-inertia"),
            "{command}: {stderr}"
        );
    }
    let (status, stdout, stderr) = run(dynagen().arg("inspect").arg(&urdf).arg("--allow-nonphysical-inertia"));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("link \"utorso\"") && stdout.contains("indefinite"), "{stdout}");
    let (status, stdout, stderr) = run(dynagen()
        .args(["generate", "--functions", "inverse_dynamics,mass_matrix", "--allow-nonphysical-inertia"])
        .arg(&urdf));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("pub fn mass_matrix"));
}

const TWIN: &str = r#"<robot name="twin">
  <link name="base"/><link name="mid"/>
  <link name="arm"><inertial><origin xyz="0.3 0 0"/><mass value="2"/><inertia ixx="0.01" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j1" type="continuous"><parent link="base"/><child link="mid"/><axis xyz="0 0 1"/></joint>
  <joint name="j2" type="continuous"><parent link="mid"/><child link="arm"/><axis xyz="0 0 1"/></joint>
</robot>"#;

#[test]
fn eval_names_dependent_joints_instead_of_blaming_the_inputs() {
    let dir = scratch("dependent");
    let urdf = dir.join("twin.urdf");
    std::fs::write(&urdf, TWIN).unwrap();
    let states = dir.join("s.json");
    // inverse dynamics alone works
    std::fs::write(&states, r#"{"states": [{"q": [0.1, 0.2], "qd": [0, 1], "qdd": [1, 0]}]}"#).unwrap();
    let (status, stdout, stderr) = run(dynagen().arg("eval").arg(&urdf).arg("--input").arg(&states));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("\"tau\""));
    assert!(stderr.contains("joints \"j1\" and \"j2\" are dependent"), "the load-time warning: {stderr}");
    // forward dynamics: the joints, not "the inputs are too large for f64"
    std::fs::write(&states, r#"{"states": [{"q": [0.1, 0.2], "qd": [0, 1], "tau": [1, 0]}]}"#).unwrap();
    let (status, _, stderr) = run(dynagen().arg("eval").arg(&urdf).arg("--input").arg(&states));
    assert_eq!(status, 1, "{stderr}");
    let error = stderr.lines().find(|l| l.starts_with("error: ")).unwrap();
    assert!(error.contains("forward dynamics is undefined") && error.contains("joints \"j1\" and \"j2\""), "{error}");
    assert!(!error.contains("too large"), "{error}");
    // generate: forward dynamics refused with the way out
    let (status, _, stderr) = run(dynagen().arg("generate").arg(&urdf));
    assert_eq!(status, 1, "{stderr}");
    assert!(stderr.contains("joints \"j1\" and \"j2\"") && stderr.contains("leave forward_dynamics out"), "{stderr}");
    let (status, _, stderr) = run(dynagen().arg("generate").arg(&urdf).args(["--functions", "inverse_dynamics"]));
    assert_eq!(status, 0, "{stderr}");
}

#[test]
fn json_states_duplicate_keys_refused_and_a_byte_order_mark_accepted() {
    let dir = scratch("json");
    let states = dir.join("s.json");
    let q = "[0, 0, 0, 0, 0, 0]";
    std::fs::write(&states, format!("{{\"states\": [{{\"q\": {q}}}], \"states\": []}}")).unwrap();
    let (status, stdout, stderr) = run(dynagen().arg("eval").arg("--input").arg(&states));
    assert_eq!(status, 1, "{stderr}");
    assert!(stdout.is_empty());
    assert!(stderr.contains("the key \"states\" appears twice"), "{stderr}");
    std::fs::write(&states, format!("\u{feff}{{\"states\": [{{\"q\": {q}}}]}}")).unwrap();
    let (status, stdout, stderr) = run(dynagen().arg("eval").arg("--input").arg(&states));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("\"g\""), "{stdout}");
}

/// A massless upper arm and a point mass on the forearm: M is singular only
/// with the elbow straight (det M = l1²·l2²·sin²(q_elbow)).
const PLANAR: &str = r#"<robot name="p"><link name="base"/><link name="upper"/>
<link name="fore"><inertial><origin xyz="1 0 0"/><mass value="1"/><inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial></link>
<joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/><axis xyz="0 0 1"/></joint>
<joint name="elbow" type="continuous"><parent link="upper"/><child link="fore"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/></joint></robot>"#;

#[test]
fn eval_names_the_joints_of_a_mass_matrix_singular_at_this_q() {
    let dir = scratch("singular_here");
    let urdf = dir.join("planar.urdf");
    std::fs::write(&urdf, PLANAR).unwrap();
    let states = dir.join("s.json");
    std::fs::write(&states, r#"{"states": [{"q": [0.3, 0.5], "qd": [0, 0], "tau": [1, 0]}]}"#).unwrap();
    let (status, _, stderr) = run(dynagen().arg("eval").arg(&urdf).arg("--input").arg(&states));
    assert_eq!(status, 0, "{stderr}");
    std::fs::write(&states, r#"{"states": [{"q": [0.3, 0], "qd": [0, 0], "tau": [1, 0]}]}"#).unwrap();
    let (status, _, stderr) = run(dynagen().arg("eval").arg(&urdf).arg("--input").arg(&states));
    assert_eq!(status, 1, "{stderr}");
    let error = stderr.lines().find(|l| l.starts_with("error: ")).unwrap();
    assert!(
        error.contains(
            "the mass matrix is singular at this q (joints \"shoulder\", \"elbow\" move without moving any mass"
        ) && !error.contains("too large"),
        "{error}"
    );
}

/// A robot with mimic joints, as users have it, through every command: the
/// Panda of franka_description has 8 joints (the second finger follows the
/// first), `inspect` shows the couplings, `eval` matches Pinocchio with its
/// mimic option, `generate` writes 8 joint names; `--mimic independent`
/// gives the 9 joints of old.
#[test]
fn mimic_joints_through_every_command() {
    let urdf = data("gripper_mimic.urdf");
    let (status, stdout, stderr) = run(dynagen().arg("inspect").arg(&urdf));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("4 joints (degrees of freedom) and 4 mimic joints that follow them"), "{stdout}");
    assert!(stdout.contains("[follows c_finger] d_tip_l (revolute) -> tip_l"), "{stdout}");
    assert!(stdout.contains("-0.75 × c_finger + 0.2") && stdout.contains("1 × c_finger − 0.1"), "{stdout}");
    let (status, stdout, stderr) = run(dynagen().arg("inspect").arg(&urdf).args(["--mimic", "independent"]));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("8 joints (degrees of freedom), 8 moving bodies") && !stdout.contains("follows"));
    let (status, _, stderr) = run(dynagen().arg("inspect").arg(&urdf).args(["--mimic", "sideways"]));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("unknown mimic mode \"sideways\""), "{stderr}");

    let urdf = data("panda_mimic.urdf");
    let text = std::fs::read_to_string(data("pinocchio_mimic_panda.json")).unwrap();
    let reference: serde_json::Value = serde_json::from_str(&text).unwrap();
    let state = &reference["states"][3];
    let input = serde_json::json!({"states": [{"q": state["q"], "qd": state["qd"], "qdd": state["qdd"], "tau": state["tau_in"]}]});
    let (status, stdout, stderr) =
        run(dynagen().arg("eval").arg(&urdf).args(["--input", "-"]).write_stdin(input.to_string()));
    assert_eq!(status, 0, "{stderr}");
    let out: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(out["joint_names"], reference["joint_names"]);
    for (ours, theirs) in [("tau", "tau"), ("h", "h"), ("g", "g"), ("qdd", "qdd_fd")] {
        let v =
            |x: &serde_json::Value| -> Vec<f64> { x.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect() };
        let (got, want) = (v(&out["results"][0][ours]), v(&state[theirs]));
        let scale = want.iter().fold(1e-9f64, |m, x| m.max(x.abs()));
        let e = got.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / scale;
        assert!(e <= 1e-12, "eval {ours}: relative error {e:e} against Pinocchio");
    }
    let dir = scratch("mimic");
    let out = dir.join("panda_mimic.rs");
    let (status, _, stderr) = run(dynagen().arg("generate").arg(&urdf).arg("-o").arg(&out));
    assert_eq!(status, 0, "{stderr}");
    let source = std::fs::read_to_string(&out).unwrap();
    assert!(source.contains("pub const DOF: usize = 8;"));
    assert!(source.contains("//   \"panda_finger_joint2\" = 1.0 * \"panda_finger_joint1\" + 0.0"), "the header");
    let (status, _, stderr) =
        run(dynagen().arg("generate").arg(&urdf).args(["--mimic", "independent", "-o"]).arg(&out));
    assert_eq!(status, 0, "{stderr}");
    let source = std::fs::read_to_string(&out).unwrap();
    assert!(source.contains("pub const DOF: usize = 9;") && !source.contains("Mimic joints"));
    let (status, stdout, stderr) = run(dynagen().arg("ops").arg(&urdf));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("8 joints"), "{stdout}");
}
