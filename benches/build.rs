//! Generates the benchmarked modules into OUT_DIR: the UR5 and the Panda,
//! each with std's sin_cos (`*_std`) and with the same bodies without fused
//! multiply-adds and run-time dispatch (`*_base`); the UR5, the Panda, the
//! KUKA iiwa 14 and the quadruped12 with its trunk fixed, each with the
//! batched `sin_cos_all` (`*_batched`, every module has the `NAME_sc`
//! bodies, which take the sines and cosines as inputs) and with the
//! derivatives of the dynamics (`*_derivatives`); and the quadruped12 and
//! the humanoid32 with a floating base, default options
//! (`quadruped12_floating`, `humanoid32_floating`, as `dynagen generate
//! dynagen/robots/ROBOT.urdf --floating-base`), and the floating
//! quadruped12's derivatives (`quadruped12_floating_derivatives`); the
//! Panda with its mimic finger, default options (`panda_mimic`).

use dynagen::codegen::{generate, CodegenOptions, Function, Trig};
use dynagen::{Builder, Model};
use std::path::Path;

/// The derivative functions of the `*_derivatives` modules.
const DERIVATIVES: [Function; 3] =
    [Function::InverseDynamicsDerivatives, Function::ForwardDynamicsDerivatives, Function::MassMatrixInverse];

fn main() {
    let robots = Path::new(env!("CARGO_MANIFEST_DIR")).join("../dynagen/robots");
    println!("cargo:rerun-if-changed=build.rs");
    let out = std::env::var("OUT_DIR").expect("OUT_DIR");
    // A function ahead of the modules, its size set by DYNAGEN_BENCH_LAYOUT
    // (0 by default): another value moves the modules' code, so that a
    // timing can be repeated over several code layouts
    // (scripts/reference/layouts.sh; docs/performance.md, "The same body,
    // different binaries").
    println!("cargo:rerun-if-env-changed=DYNAGEN_BENCH_LAYOUT");
    let layout: usize = std::env::var("DYNAGEN_BENCH_LAYOUT").ok().and_then(|v| v.parse().ok()).unwrap_or(0);
    let terms: Vec<String> = (0..=97 * layout).map(|i| format!("x * {i}.5")).collect();
    let pad = format!(
        "/// The code layout this library was built with (`DYNAGEN_BENCH_LAYOUT`).\n\
         pub const LAYOUT: usize = {layout};\n\
         #[inline(never)]\n\
         fn layout_pad(x: f64) -> f64 {{\n    {}\n}}\n",
        terms.join(" + ")
    );
    std::fs::write(Path::new(&out).join("layout_pad.rs"), pad).expect("writing");
    for robot in ["ur5", "panda", "iiwa14", "quadruped12"] {
        let urdf = robots.join(format!("{robot}.urdf"));
        println!("cargo:rerun-if-changed={}", urdf.display());
        let model = Model::from_urdf_file(&urdf).unwrap_or_else(|e| panic!("{}: {e}", urdf.display()));
        let write = |suffix: &str, opts: CodegenOptions| {
            let module = generate(&model, &opts.source(format!("dynagen/robots/{robot}.urdf")))
                .unwrap_or_else(|e| panic!("generating {robot}: {e}"));
            std::fs::write(Path::new(&out).join(format!("{robot}_{suffix}.rs")), module.source).expect("writing");
        };
        write("batched", CodegenOptions::default().trig(Trig::Batched));
        // The derivatives (examples/derivatives.rs), default options.
        write("derivatives", CodegenOptions::default().functions(DERIVATIVES));
        if robot == "ur5" || robot == "panda" {
            write("std", CodegenOptions::default().trig(Trig::Std));
            // The same bodies without fused multiply-adds and without run-time
            // dispatch, for with/without in one run: on a default build, what
            // the bodies ran before either (SSE2, unfused); on a build with the
            // `fma` and `avx2` target features (RUSTFLAGS="-C target-cpu=native"),
            // where dispatch compiles out, the unfused body alone.
            write("base", CodegenOptions::default().trig(Trig::Inputs).fma(false).runtime_dispatch(false));
        }
    }
    // The Panda with its mimic finger (examples/mimic.rs), default options.
    let urdf = Path::new(env!("CARGO_MANIFEST_DIR")).join("../dynagen/tests/data/panda_mimic.urdf");
    println!("cargo:rerun-if-changed={}", urdf.display());
    let module = Builder::new()
        .urdf(&urdf)
        .source("dynagen/tests/data/panda_mimic.urdf")
        .generate_module()
        .unwrap_or_else(|e| panic!("generating panda_mimic: {e}"));
    std::fs::write(Path::new(&out).join("panda_mimic.rs"), module.source).expect("writing");
    // The floating-base quadruped and humanoid (examples/floating.rs).
    for robot in ["quadruped12", "humanoid32"] {
        let urdf = robots.join(format!("{robot}.urdf"));
        println!("cargo:rerun-if-changed={}", urdf.display());
        let model = Model::from_urdf_file(&urdf).unwrap_or_else(|e| panic!("{}: {e}", urdf.display()));
        let module = Builder::new()
            .model(model)
            .floating_base(true)
            .source(&format!("dynagen/robots/{robot}.urdf"))
            .generate_module()
            .unwrap_or_else(|e| panic!("generating {robot} (floating): {e}"));
        std::fs::write(Path::new(&out).join(format!("{robot}_floating.rs")), module.source).expect("writing");
        // τ, M and h with every branch unrolled (`--no-branch-loops`).
        let module = Builder::new()
            .urdf(&urdf)
            .floating_base(true)
            .functions(&["inverse_dynamics", "mass_matrix", "bias_forces"])
            .branch_loops(false)
            .source(&format!("dynagen/robots/{robot}.urdf"))
            .generate_module()
            .unwrap_or_else(|e| panic!("generating {robot} (floating, unrolled): {e}"));
        std::fs::write(Path::new(&out).join(format!("{robot}_floating_unrolled.rs")), module.source).expect("writing");
    }
    // The floating quadruped's derivatives (examples/derivatives.rs).
    let model = Model::from_urdf_file(robots.join("quadruped12.urdf")).expect("quadruped12.urdf");
    let opts = CodegenOptions::default().functions(DERIVATIVES).source("dynagen/robots/quadruped12.urdf");
    let module = generate(&model.with_floating_base(), &opts)
        .unwrap_or_else(|e| panic!("generating quadruped12's floating derivatives: {e}"));
    std::fs::write(Path::new(&out).join("quadruped12_floating_derivatives.rs"), module.source).expect("writing");
}
