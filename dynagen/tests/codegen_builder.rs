//! `dynagen::Builder` as a build script uses it: the file it writes is
//! `codegen::generate`'s source, written only when it changes, and every
//! error's message names the file and the item.

mod support;

use dynagen::codegen::{generate, BuildError, CodegenOptions, Function, ScalarType};
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
fn writes_the_generators_source_named_after_the_robot() {
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
