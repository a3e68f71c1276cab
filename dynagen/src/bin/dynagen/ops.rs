//! `dynagen ops`: the operation count of each generated function beside
//! that of the generic recursion ([`dynagen::codegen::generic_op_count`]:
//! the same algorithm run on the [`dynagen::Counting`] scalar, every model
//! constant used as a number at run time). With `--scene`, the scene
//! module's functions beside the same functions of the full module: what
//! the scene saves (or what its run-time inputs cost).

use crate::error::{CliError, Output};
use crate::generate::cli_error;
use dynagen::codegen::{generic_op_count, Builder, ForwardDynamicsMethod, GeneratedFunction, GeneratedModule};
use dynagen::symbolic::OpCount;
use std::fmt::Write;
use std::path::PathBuf;

/// Arguments of `dynagen ops`.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub robot: crate::robot_source::RobotArgs,
    /// Count the functions of this scene's module (TOML; see `dynagen
    /// generate --scene`) beside those of the full module.
    #[arg(long, value_name = "SCENE.toml")]
    pub scene: Option<PathBuf>,
    /// Count these functions (comma-separated, as `dynagen generate
    /// --functions`) instead of the default five, e.g. the derivatives.
    #[arg(long, value_name = "a,b,...", value_delimiter = ',')]
    pub functions: Option<Vec<String>>,
}

/// Runs `dynagen ops`.
pub fn run(args: &Args) -> Result<Output, CliError> {
    let (source, model) = args.robot.load()?;
    let with_functions = |b: Builder| match &args.functions {
        Some(f) => b.functions(f),
        None => b,
    };
    let module =
        with_functions(Builder::new().model(model.clone())).generate_module().map_err(|e| cli_error(e, &source))?;
    let mut o = String::new();
    let _ = writeln!(o, "robot \"{}\" from {source}: {} joints", model.name, model.dof());
    match &args.scene {
        None => full_table(&mut o, &model, &module),
        Some(path) => {
            let scene = with_functions(Builder::new().model(model.clone()))
                .scene_file(path)
                .generate_module()
                .map_err(|e| cli_error(e, &source))?;
            scene_table(&mut o, path, &module, &scene);
        }
    }
    Ok(Output { stdout: o, warnings: source.warnings(&model), notes: Vec::new() })
}

/// The generic recursion's count of the function `f` was traced from.
fn generic_count(model: &dynagen::Model, f: &GeneratedFunction) -> OpCount {
    let method = f.method.unwrap_or(ForwardDynamicsMethod::Aba);
    generic_op_count(model, &f.function, method).unwrap_or_default()
}

/// The generated functions beside the generic recursion.
fn full_table(o: &mut String, model: &dynagen::Model, module: &GeneratedModule) {
    let _ = writeln!(
        o,
        "operations per call (+ - * / sqrt sin_cos; negations apart, in columns 4 and 5): generated vs the generic recursion;\n\
         fused: the generated sums emitted as fused multiply-adds, FP ops: the generated operations with each fused one = 1,\n\
         multiplies: the multiplications executed, fused ones included (two a cycle at most on current x86-64 cores)"
    );
    let _ = writeln!(
        o,
        "{:<32} {:>10} {:>10} {:>7}   {:>13} {:>11}   {:>6} {:>7} {:>10}",
        "function", "generated", "generic", "ratio", "generated neg", "generic neg", "fused", "FP ops", "multiplies"
    );
    for f in &module.functions {
        let generic = generic_count(model, f);
        let (g, r) = (f.op_count.arithmetic(), generic.arithmetic());
        let _ = writeln!(
            o,
            "{:<32} {:>10} {:>10} {:>6.2}x   {:>13} {:>11}   {:>6} {:>7} {:>10}",
            f.label(),
            g,
            r,
            r as f64 / g.max(1) as f64,
            f.op_count.neg,
            generic.neg,
            f.op_count.fused,
            f.op_count.fp_ops(),
            f.op_count.multiplies()
        );
    }
    let _ = writeln!(o, "\nbreakdown (generated | generic):");
    for f in &module.functions {
        let body = &f.sin_cos_inputs.function;
        let fusion = body.fusion();
        let _ = writeln!(
            o,
            "  {}:\n    {}\n    {}\n    body with sines and cosines given: {}, {} ({} unfused)",
            f.label(),
            f.op_count,
            generic_count(model, f),
            fusion.op_count(body),
            fusion.critical_path(),
            body.critical_path().cycles
        );
    }
}

/// The scene module's functions beside the full module's (`-` where the
/// full module has no such function: coriolis, the frame functions). A
/// scene's constant gravity, locks or sub-tree make its functions cheaper;
/// armature, friction, payloads and run-time inputs make them dearer.
fn scene_table(o: &mut String, path: &std::path::Path, full: &GeneratedModule, scene: &GeneratedModule) {
    let _ = writeln!(
        o,
        "operations per call (+ - * / sqrt sin_cos, negations apart) of the scene {}: its module vs the full module",
        path.display()
    );
    let _ = writeln!(o, "{:<32} {:>10} {:>10} {:>12}", "function", "scene", "full", "scene - full");
    for f in scene.functions.iter().filter(|f| f.emitted) {
        let s = f.op_count.arithmetic();
        match full.function(&f.name) {
            Some(g) => {
                let r = g.op_count.arithmetic();
                let diff = s as i64 - r as i64;
                let _ = writeln!(o, "{:<32} {s:>10} {r:>10} {diff:>+12}", f.label());
            }
            None => {
                let _ = writeln!(o, "{:<32} {s:>10} {:>10} {:>12}", f.label(), "-", "-");
            }
        }
    }
    let _ = writeln!(o, "\nbreakdown (scene):");
    for f in &scene.functions {
        let note = if f.emitted { "" } else { " [not emitted]" };
        let _ = writeln!(o, "  {}{note}: {}", f.label(), f.op_count);
    }
}
