//! `dynagen::Builder` as a build script uses it: the file it writes is
//! `codegen::generate`'s source, written only when it changes, and every
//! error's message names the file and the item.

mod support;

use dynagen::codegen::{generate, BuildError, CodegenOptions, Function, ScalarType, Trig};
use dynagen::scene::{Gravity, Scene};
use dynagen::Builder;
use std::path::{Path, PathBuf};

use support::ROBOTS;

fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("builder").join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn writes_the_generators_source_named_after_the_file() {
    let dir = scratch("writes");
    let urdf = format!("{ROBOTS}/planar_2link.urdf");
    let written = Builder::new()
        .urdf(&urdf)
        .functions(&["gravity_torques"])
        .scalar(ScalarType::F32)
        .out_dir(&dir)
        .generate()
        .unwrap();
    assert_eq!(written.path, dir.join("planar_2link.rs"));
    assert_eq!(written.inputs, vec![PathBuf::from(&urdf)]);
    let model = dynagen::Model::from_urdf_file(&urdf).unwrap();
    let opts =
        CodegenOptions::default().source(urdf.clone()).scalar(ScalarType::F32).functions([Function::GravityTorques]);
    let want = generate(&model, &opts).unwrap().source;
    assert_eq!(std::fs::read_to_string(&written.path).unwrap(), want);
    // Includable in a `mod`: no inner attribute anywhere.
    assert!(!want.contains("#!["));

    // Unchanged content: the file is left alone (its mtime kept), so cargo
    // does not rebuild what includes it.
    let before = std::fs::metadata(&written.path).unwrap().modified().unwrap();
    std::thread::sleep(std::time::Duration::from_millis(20));
    let again = Builder::new()
        .urdf(&urdf)
        .functions(&["gravity_torques"])
        .scalar(ScalarType::F32)
        .out_dir(&dir)
        .generate()
        .unwrap();
    assert_eq!(std::fs::metadata(&again.path).unwrap().modified().unwrap(), before);

    // A model given in Rust, a module name, and the default scene.
    let written = Builder::new().model(model).module_name("arm").scene(Scene::new()).out_dir(&dir).generate().unwrap();
    assert_eq!(written.path, dir.join("arm.rs"));
    assert!(written.module.source.contains("pub fn forward_dynamics("));
}

#[test]
fn errors_name_the_file_and_the_item() {
    let dir = scratch("errors");
    let msg = |b: Builder| b.out_dir(&dir).generate().unwrap_err().to_string();

    assert!(matches!(Builder::new().out_dir(&dir).generate(), Err(BuildError::NoRobot)));

    let e = msg(Builder::new().urdf("no/such/robot.urdf"));
    assert!(e.starts_with("dynagen: robot no/such/robot.urdf: cannot read"), "{e}");

    let bad = dir.join("bad.urdf");
    std::fs::write(
        &bad,
        r#"<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1"/>
           <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
           <joint name="j" type="revolute"><parent link="a"/><child link="c"/><axis xyz="0 0 1"/>
           <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"#,
    )
    .unwrap();
    let e = msg(Builder::new().urdf(&bad));
    assert!(e.contains("bad.urdf") && e.contains("joint \"j\""), "{e}");

    let ur5 = format!("{ROBOTS}/ur5.urdf");
    let e = msg(Builder::new().urdf(&ur5).functions(&["mass_matrix", "jacobian"]));
    assert!(e.starts_with("dynagen: unknown function \"jacobian\" (the functions are inverse_dynamics, "), "{e}");

    let e = msg(Builder::new().urdf(&ur5).file_name("sub/ur5.rs"));
    assert!(e.contains("bad output file name \"sub/ur5.rs\""), "{e}");
    let e = msg(Builder::new().urdf(&ur5).file_name("ur5\n.rs"));
    assert!(e.contains("bad output file name \"ur5\\n.rs\""), "{e}");

    // Scenes: a scene that does not fit the robot names the scene, the
    // robot and the item.
    let e = msg(Builder::new().urdf(&ur5).scene(Scene::new().lock("wrist_9_joint", 0.0)));
    assert!(
        e.starts_with("dynagen: scene (given in Rust) for ")
            && e.contains("ur5.urdf")
            && e.contains("\"wrist_9_joint\""),
        "{e}"
    );
    let scene = dir.join("s.toml");
    std::fs::write(&scene, "tip_wrench = \"tool9\"\n").unwrap();
    let e = msg(Builder::new().urdf(&ur5).scene_file(&scene));
    assert!(e.contains("s.toml") && e.contains("tip wrench") && e.contains("\"tool9\""), "{e}");
    let e = msg(Builder::new().urdf(&ur5).scene(Scene::new()).functions(&["coriolis", "jacobian"]));
    assert!(e.contains("unknown function \"jacobian\""), "{e}");
    std::fs::write(&scene, "functoins = []\n").unwrap();
    let e = msg(Builder::new().urdf(&ur5).scene_file(&scene));
    assert!(e.starts_with("dynagen: scene ") && e.contains("s.toml") && e.contains("functoins"), "{e}");

    // A scene that only picks functions, the scalar and the name is honoured.
    std::fs::write(&scene, "name = \"ur5_gravity\"\nfunctions = [\"gravity_torques\"]\nscalar = \"f32\"\n").unwrap();
    let written = Builder::new().urdf(&ur5).scene_file(&scene).out_dir(&dir).generate().unwrap();
    assert_eq!(written.path, dir.join("ur5_gravity.rs"));
    assert!(written.module.source.contains("pub fn gravity_torques(q: &[f32; DOF]) -> [f32; DOF]"));
    assert!(!written.module.source.contains("pub fn mass_matrix"));

    // A scene with a run-time gravity and coriolis: generated, with the input.
    let written = Builder::new()
        .urdf(&ur5)
        .scene(Scene::new().gravity(Gravity::Input))
        .name("ur5 gravity input")
        .functions(&["gravity_torques", "coriolis"])
        .out_dir(&dir)
        .generate()
        .unwrap();
    assert_eq!(written.path, dir.join("ur5_gravity_input.rs"));
    let src = &written.module.source;
    assert!(src.contains("pub fn gravity_torques(q: &[f64; DOF], gravity: &[f64; 3]) -> [f64; DOF]"), "{src}");
    assert!(src.contains("pub fn coriolis(q: &[f64; DOF], qd: &[f64; DOF]) -> [f64; DOF]"), "{src}");
    assert!(!src.contains("pub fn inverse_dynamics"));
    assert_eq!(written.inputs.len(), 1);
}

/// One run of a build script: run by `run_build_script` as a child process
/// (the test binary again, with `OUT_DIR` set, as cargo runs a build
/// script), one Builder per URDF of `DYNAGEN_TEST_URDFS` (`;`-separated).
#[test]
#[ignore = "a child process of the stale-module tests, not a test on its own"]
fn build_script_run() {
    let Ok(urdfs) = std::env::var("DYNAGEN_TEST_URDFS") else { return };
    for urdf in urdfs.split(';') {
        Builder::new().urdf(urdf).functions(&["gravity_torques"]).generate().unwrap();
    }
}

/// Runs the build script `build_script_run` in `out_dir` on `urdfs`.
fn run_build_script(out_dir: &Path, urdfs: &[&Path]) {
    let list: Vec<String> = urdfs.iter().map(|p| p.display().to_string()).collect();
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "build_script_run", "--ignored", "--test-threads=1", "--nocapture"])
        .env("OUT_DIR", out_dir)
        .env("DYNAGEN_TEST_URDFS", list.join(";"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && stdout.contains("1 passed"), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
}

/// The `.rs` files in `dir`.
fn rust_files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".rs"))
        .collect();
    v.sort();
    v
}

/// The issue as a user met it: the robot renamed (`ur5` → `UR5e-arm`) and a
/// mass changed in the same file, then the file renamed too. The output is
/// named after the file, so the first build's `include!` sees the new
/// dynamics; after the file's rename, the old output is gone from `OUT_DIR`
/// (an `include!` of it fails to compile instead of compiling the old
/// dynamics), and a rerun that writes the same content keeps the files'
/// modification times.
#[test]
fn renaming_the_robot_or_its_file_leaves_no_stale_module() {
    let dir = scratch("stale");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let ur5 = std::fs::read_to_string(format!("{ROBOTS}/ur5.urdf")).unwrap();
    let urdf = dir.join("ur5.urdf");
    std::fs::write(&urdf, &ur5).unwrap();
    run_build_script(&out, &[&urdf]);
    assert_eq!(rust_files(&out), ["ur5.rs"]);
    let first = std::fs::read_to_string(out.join("ur5.rs")).unwrap();

    // The robot renamed inside the file, and its upper arm's mass changed.
    assert!(ur5.contains("<robot name=\"ur5\">") && ur5.contains("<mass value=\"8.393\"/>"));
    let renamed = ur5
        .replace("<robot name=\"ur5\">", "<robot name=\"UR5e-arm\">")
        .replace("<mass value=\"8.393\"/>", "<mass value=\"9.0\"/>");
    std::fs::write(&urdf, &renamed).unwrap();
    run_build_script(&out, &[&urdf]);
    assert_eq!(rust_files(&out), ["ur5.rs"]);
    let second = std::fs::read_to_string(out.join("ur5.rs")).unwrap();
    let want = Builder::new().urdf(&urdf).functions(&["gravity_torques"]).generate_module().unwrap().source;
    assert!(second == want && second != first, "the module is the changed robot's");
    assert!(second.contains("\"UR5e-arm\""));

    // The file renamed (and the build script changed to name it), beside a
    // second robot: the old output leaves OUT_DIR.
    let arm = dir.join("UR5e-arm.urdf");
    std::fs::rename(&urdf, &arm).unwrap();
    let planar = PathBuf::from(format!("{ROBOTS}/planar_2link.urdf"));
    run_build_script(&out, &[&arm, &planar]);
    assert_eq!(rust_files(&out), ["planar_2link.rs", "ur5e_arm.rs"]);
    let times = |files: &[&str]| -> Vec<std::time::SystemTime> {
        files.iter().map(|f| std::fs::metadata(out.join(f)).unwrap().modified().unwrap()).collect()
    };
    let before = times(&["planar_2link.rs", "ur5e_arm.rs"]);
    std::thread::sleep(std::time::Duration::from_millis(20));
    run_build_script(&out, &[&arm, &planar]);
    assert_eq!(rust_files(&out), ["planar_2link.rs", "ur5e_arm.rs"]);
    assert_eq!(times(&["planar_2link.rs", "ur5e_arm.rs"]), before, "unchanged files keep their modification time");

    // Outside OUT_DIR nothing but the file written is touched.
    let elsewhere = dir.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::fs::write(elsewhere.join("mine.rs"), "// not dynagen's").unwrap();
    Builder::new().urdf(&planar).functions(&["gravity_torques"]).out_dir(&elsewhere).generate().unwrap();
    assert_eq!(rust_files(&elsewhere), ["mine.rs", "planar_2link.rs"]);
}

/// What a build script's `.expect(..)` prints is the error's Debug form: the
/// message, as Display writes it, not the enum's fields.
#[test]
fn errors_debug_as_their_message() {
    let e = Builder::new().urdf("no/such/robot.urdf").generate_module().unwrap_err();
    assert_eq!(format!("{e:?}"), e.to_string());
    assert!(!format!("{e:?}").contains("Io {") && format!("{e:?}").contains("no/such/robot.urdf"), "{e:?}");
    let BuildError::Robot { source, .. } = &e else { panic!("{e:?}") };
    assert_eq!(format!("{source:?}"), source.to_string());
    let e = Scene::new().tip_wrench("no_such_link").apply(&support::model("ur5")).unwrap_err();
    assert_eq!(format!("{e:?}"), e.to_string());
    let e = generate(&support::model("ur5"), &CodegenOptions::default().functions([])).unwrap_err();
    assert_eq!(format!("{e:?}"), e.to_string());
    // The panic message of `.expect(..)` in a build script.
    let panic = std::panic::catch_unwind(|| {
        Builder::new().urdf("no/such/robot.urdf").generate_module().expect("generating the dynamics");
    })
    .unwrap_err();
    let text = panic.downcast_ref::<String>().unwrap();
    assert!(text.starts_with("generating the dynamics: dynagen: robot no/such/robot.urdf: cannot read"), "{text}");
}

/// `.options(..)` is the base the other setters change, whichever is
/// called first: it does not reset what was set before it.
#[test]
fn options_are_a_base_the_setters_change_in_either_order() {
    let urdf = format!("{ROBOTS}/planar_2link.urdf");
    let base = CodegenOptions::default().functions([Function::MassMatrix, Function::GravityTorques]);
    let module = |b: Builder| b.generate_module().unwrap();
    let setters_first =
        module(Builder::new().urdf(&urdf).scalar(ScalarType::F32).trig(Trig::Std).options(base.clone()));
    let options_first = module(Builder::new().urdf(&urdf).options(base).scalar(ScalarType::F32).trig(Trig::Std));
    assert_eq!(setters_first.source, options_first.source);
    let names: Vec<&str> = setters_first.functions.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["mass_matrix", "gravity_torques"], "the options' functions");
    let source = &setters_first.source;
    assert!(source.contains("pub fn mass_matrix(q: &[f32; DOF]) -> [[f32; DOF]; DOF]"), "the setter's scalar");
    assert!(source.contains("by std's sin_cos"), "the setter's trigonometry");
}
