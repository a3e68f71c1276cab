//! Generates, into OUT_DIR, the generated-code variants the report measures,
//! for each bundled robot (`dynagen/robots/NAME.urdf`):
//!
//! - `NAME_f64.rs`: f64, std's `sin_cos` (`Trig::Std`), forward dynamics by the
//!   articulated-body algorithm (every module also has the `NAME_sc`
//!   functions, which take the sines and cosines as inputs, and
//!   `sin_cos_all`);
//! - `NAME_f64_batched.rs`: the same with `NAME` calling the batched
//!   `sin_cos_all` (`Trig::Batched`, the default options');
//! - `NAME_f64_ldlt.rs`, `NAME_f64_ldlt_batched.rs`: forward dynamics only,
//!   by CRBA + LTDL;
//! - `NAME_f32.rs` and `NAME_f32_ldlt.rs`: the same in f32 (std's `sin_cos`).
//!
//! and `generated.rs`, which `include!`s them in one module per robot, with
//! adapters `sc::*` that give every robot's `NAME_sc` the same arguments
//! (`s, c, q, …`: the Panda's take `q` for its prismatic fingers, the
//! others do not); and `derivatives.rs`, the derivatives of the dynamics
//! (`inverse_dynamics_derivatives`, `forward_dynamics_derivatives`,
//! `mass_matrix_inverse`, default options) of the robots of
//! [`DERIVATIVE_ROBOTS`] in f64 and f32. It also records the rustc version
//! for the report.

use dynagen::codegen::{generate, CodegenOptions, ForwardDynamicsMethod, Function, ScalarType, Trig};
use dynagen::model::JointKind;
use dynagen::Model;
use std::fmt::Write as _;
use std::path::Path;

const ROBOTS: [&str; 4] = ["ur5", "panda", "torso_two_arms", "planar_2link"];

/// The robots of the derivatives' section: the benchmark's (a 6- and two
/// 7-joint arms, a 12-joint leg set with its trunk fixed).
const DERIVATIVE_ROBOTS: [&str; 4] = ["ur5", "panda", "iiwa14", "quadruped12"];

fn main() {
    let robots = Path::new(env!("CARGO_MANIFEST_DIR")).join("../dynagen/robots");
    println!("cargo:rerun-if-changed=build.rs");
    let out = std::env::var("OUT_DIR").expect("OUT_DIR");
    let out = Path::new(&out);
    let fd_only = [Function::ForwardDynamics];
    let mut glue = String::from("// The generated variants of every bundled robot (written by build.rs).\n\n");
    for robot in ROBOTS {
        let rel = format!("dynagen/robots/{robot}.urdf");
        let urdf = robots.join(format!("{robot}.urdf"));
        println!("cargo:rerun-if-changed={}", urdf.display());
        let model = Model::from_urdf_file(&urdf).unwrap_or_else(|e| panic!("{}: {e}", urdf.display()));
        // Forward dynamics by the ABA here, so that its row is that algorithm's (the default picks per robot);
        // std's sin_cos unless a variant says batched (the default).
        let base =
            CodegenOptions::default().source(rel.clone()).forward_dynamics(ForwardDynamicsMethod::Aba).trig(Trig::Std);
        let variants = [
            ("f64", base.clone()),
            ("f64_batched", base.clone().trig(Trig::Batched)),
            ("f64_ldlt", base.clone().functions(fd_only.clone()).forward_dynamics(ForwardDynamicsMethod::Ldlt)),
            (
                "f64_ldlt_batched",
                base.clone()
                    .functions(fd_only.clone())
                    .forward_dynamics(ForwardDynamicsMethod::Ldlt)
                    .trig(Trig::Batched),
            ),
            ("f32", base.clone().scalar(ScalarType::F32)),
            (
                "f32_ldlt",
                base.clone()
                    .scalar(ScalarType::F32)
                    .functions(fd_only.clone())
                    .forward_dynamics(ForwardDynamicsMethod::Ldlt),
            ),
        ];
        let _ = writeln!(glue, "/// `{rel}`.\n#[allow(dead_code)]\npub mod {robot} {{");
        let _ = writeln!(
            glue,
            "    /// The robot file, relative to the workspace root.\n    pub const URDF: &str = {rel:?};"
        );
        for (suffix, opts) in variants {
            let module = generate(&model, &opts).unwrap_or_else(|e| panic!("generating {robot} {suffix}: {e}"));
            let file = format!("{robot}_{suffix}.rs");
            write_if_changed(&out.join(&file), &module.source);
            let _ = writeln!(
                glue,
                "    pub mod {suffix} {{\n        include!(concat!(env!(\"OUT_DIR\"), \"/{file}\"));\n    }}"
            );
        }
        // Uniform `NAME_sc(s, c, q, …)` adapters over the f64 modules.
        let prismatic = model.bodies.iter().any(|b| b.joint.kind == JointKind::Prismatic);
        let unused = if prismatic { "" } else { "let _ = q; " };
        let a = "[f64; DOF]";
        let _ = writeln!(
            glue,
            "    /// Every `NAME_sc` of the f64 modules with the arguments `s, c, q, …`.\n    pub mod sc {{"
        );
        let _ = writeln!(glue, "        use super::f64::DOF;");
        for (name, module, inputs, ret) in [
            ("inverse_dynamics", "f64", &["qd", "qdd"][..], "A"),
            ("mass_matrix", "f64", &[][..], "[A; DOF]"),
            ("bias_forces", "f64", &["qd"][..], "A"),
            ("gravity_torques", "f64", &[][..], "A"),
            ("forward_dynamics", "f64", &["qd", "tau"][..], "A"),
            ("forward_dynamics", "f64_ldlt", &["qd", "tau"][..], "A"),
        ] {
            let ret = ret.replace('A', a);
            let params: String = inputs.iter().map(|x| format!(", {x}: &{a}")).collect();
            let mut call = vec!["s", "c"];
            if prismatic {
                call.push("q");
            }
            call.extend(inputs);
            let adapter = if module == "f64_ldlt" { "forward_dynamics_ldlt" } else { name };
            let _ = writeln!(
                glue,
                "        #[inline(always)]\n        pub fn {adapter}(s: &{a}, c: &{a}, q: &{a}{params}) -> {ret} {{\n            {unused}super::{module}::{name}_sc({})\n        }}",
                call.join(", ")
            );
        }
        let _ = writeln!(glue, "    }}\n}}");
    }
    write_if_changed(&out.join("generated.rs"), &glue);

    // The derivatives, default options, f64 and f32.
    let derivatives =
        [Function::InverseDynamicsDerivatives, Function::ForwardDynamicsDerivatives, Function::MassMatrixInverse];
    let mut glue = String::from("// The derivatives of the dynamics (written by build.rs).\n\n");
    for robot in DERIVATIVE_ROBOTS {
        let rel = format!("dynagen/robots/{robot}.urdf");
        let urdf = robots.join(format!("{robot}.urdf"));
        println!("cargo:rerun-if-changed={}", urdf.display());
        let model = Model::from_urdf_file(&urdf).unwrap_or_else(|e| panic!("{}: {e}", urdf.display()));
        let _ = writeln!(glue, "/// `{rel}`.\n#[allow(dead_code)]\npub mod {robot} {{");
        for (suffix, scalar) in [("f64", ScalarType::F64), ("f32", ScalarType::F32)] {
            let opts = CodegenOptions::default().source(rel.clone()).functions(derivatives.clone()).scalar(scalar);
            let module = generate(&model, &opts).unwrap_or_else(|e| panic!("generating {robot} {suffix}: {e}"));
            let file = format!("{robot}_derivatives_{suffix}.rs");
            write_if_changed(&out.join(&file), &module.source);
            let _ = writeln!(
                glue,
                "    pub mod {suffix} {{\n        include!(concat!(env!(\"OUT_DIR\"), \"/{file}\"));\n    }}"
            );
        }
        let _ = writeln!(glue, "}}");
    }
    write_if_changed(&out.join("derivatives.rs"), &glue);

    // The compiler that built the report, for its "machine" paragraph.
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = std::process::Command::new(&rustc)
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=DYNAGEN_REPORT_RUSTC={version}");
    println!("cargo:rustc-env=DYNAGEN_REPORT_PROFILE={}", std::env::var("PROFILE").unwrap_or_default());
}

/// Writes `text` unless the file already holds it (so that an unchanged
/// module does not make cargo recompile the report).
fn write_if_changed(path: &Path, text: &str) {
    if std::fs::read_to_string(path).ok().as_deref() != Some(text) {
        std::fs::write(path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}
