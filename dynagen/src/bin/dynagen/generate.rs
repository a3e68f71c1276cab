//! `dynagen generate`: the module of unrolled dynamics for a robot, as
//! [`dynagen::Builder`] writes it in a build script (byte for byte the same
//! as [`dynagen::codegen::generate`] with the same options).

use crate::error::{CliError, Output, STATUS_BAD_INPUT};
use crate::robot_source::RobotSource;
use dynagen::codegen::{BuildError, Builder, ForwardDynamicsMethod, GeneratedModule, ScalarType, Trig};
use std::path::PathBuf;

/// Arguments of `dynagen generate`.
#[derive(clap::Args, Debug)]
#[command(after_long_help = GENERATE_HELP)]
pub struct Args {
    #[command(flatten)]
    pub robot: crate::robot_source::RobotArgs,
    /// Write the module to this file instead of stdout.
    #[arg(long, short, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Only these functions (comma-separated): inverse_dynamics, mass_matrix,
    /// bias_forces, gravity_torques, coriolis, forward_dynamics,
    /// inverse_dynamics_derivatives, forward_dynamics_derivatives,
    /// mass_matrix_inverse, frame_pose:FRAME, frame_jacobian:FRAME,
    /// frame_world_jacobian:FRAME, frame_acceleration_bias:FRAME.
    #[arg(long, value_name = "a,b,...", value_delimiter = ',')]
    pub functions: Option<Vec<String>>,
    /// Generate f32 code (constants rounded to f32).
    #[arg(long)]
    pub f32: bool,
    /// Generate code for #![no_std] with no dependency: the sines and cosines
    /// come from the module's own sin_cos_all (the same as --trig batched,
    /// the default).
    #[arg(long, conflicts_with = "trig")]
    pub no_std: bool,
    /// Where the sines and cosines come from: batched (the default: the
    /// module's own sin_cos_all, within 1 ulp and faster than std's; no_std,
    /// no dependency), std (f64::sin_cos; needs std), libm (no_std, needs the
    /// libm crate), inputs (only the NAME_sc functions, which take them;
    /// no_std).
    #[arg(long, value_name = "batched|std|libm|inputs")]
    pub trig: Option<String>,
    /// Forward dynamics by CRBA + RNEA + a sparse LTDL solve (default: the
    /// faster of the two that is as accurate, measured when generating).
    #[arg(long, conflicts_with = "aba")]
    pub ldlt: bool,
    /// Forward dynamics by the articulated-body algorithm (default: the
    /// faster of the two that is as accurate, measured when generating).
    #[arg(long)]
    pub aba: bool,
    /// Keep constants that are 0 or ±1 up to rounding as they are.
    #[arg(long)]
    pub no_snap: bool,
    /// Write every a*b + c as a*b + c rounded twice, also where the target
    /// has fused multiply-adds (default: fma(a, b, c), one rounding on
    /// x86_64 built with the fma target feature and on aarch64, the same
    /// bits as a*b + c elsewhere).
    #[arg(long)]
    pub no_fma: bool,
    /// Compile each function for the build's target only (default: x86_64
    /// builds without the avx2 and fma target features also get copies for
    /// AVX-512 and for AVX2 and FMA, run where the processor has them; their
    /// results differ in the last bits from the baseline's).
    #[arg(long)]
    pub no_dispatch: bool,
    /// Unroll every branch: without it, sibling subtrees of one shape
    /// (legs, arms) in τ, h, M and the ABA forward dynamics are one body
    /// run on all of them, in vector lanes, over a table of their constants.
    #[arg(long, conflicts_with = "branch_loops")]
    pub no_branch_loops: bool,
    /// Sibling subtrees of one shape as one body (the default).
    #[arg(long, hide = true)]
    pub branch_loops: bool,
    /// Cut a function body of more than N `let`s into private parts of at
    /// most N (default 2500; 0: never cut). Long bodies overflow rustc's
    /// stack in debug builds and compile slowly in release builds.
    #[arg(long, value_name = "N")]
    pub split_lets: Option<usize>,
    /// A scene (TOML; see the documentation of `dynagen::scene`): its
    /// constants folded in, its run-time inputs (gravity, tip wrench,
    /// payloads) as extra arguments, its code keys (functions, scalar, …)
    /// as defaults that the options given here override (--functions keeps
    /// its frame functions).
    #[arg(long, value_name = "SCENE.toml")]
    pub scene: Option<PathBuf>,
}

const GENERATE_HELP: &str = "\
The module holds DOF, JOINT_NAMES and the functions (f64 shown):
  inverse_dynamics(q, qd, qdd) -> [f64; DOF]
  mass_matrix(q) -> [[f64; DOF]; DOF]
  bias_forces(q, qd) -> [f64; DOF]
  gravity_torques(q) -> [f64; DOF]
  forward_dynamics(q, qd, tau) -> [f64; DOF]
It has no inner attributes: include it in a module with
  mod ur5 { include!(\"ur5.rs\"); }
By default it needs neither std nor any crate (#![no_std]): the sines and
cosines, and the square roots of a scene's Coulomb friction, are the module's
own (--trig std: std's f64::sin_cos and f64::sqrt).
Each function's operation count is printed on stderr.

With --scene SCENE.toml the module has the scene's functions only (coriolis and
the frame functions too if it asks), and the scene's
run-time inputs as arguments after the usual ones: gravity: &[f64; 3],
f_tip: &[f64; 6], payload_LINK: &[f64; 10]. Its header lists what the scene
left out and each function's operation count.

Examples:
  dynagen generate robots/panda.urdf --functions inverse_dynamics,mass_matrix -o src/panda.rs
  dynagen generate robots/ur5.urdf --scene scenes/ur5_controller.toml -o src/ur5_controller.rs";

/// The builder for `args`, and the model it was given.
fn builder(args: &Args, source: &RobotSource) -> Result<(Builder, dynagen::Model), CliError> {
    // Only what the command line says is set: a scene file's code keys
    // stand where it says nothing (and give way where it does).
    let trig = match (args.no_std, args.trig.as_deref()) {
        (true, _) => Some(Trig::Batched),
        (false, None) => None,
        (false, Some(t)) => Some(
            t.parse::<Trig>().map_err(|e| CliError { message: format!("--trig: {e}"), status: STATUS_BAD_INPUT })?,
        ),
    };
    let model = source.load(&args.robot.load)?;
    let mut b = Builder::new().model(model.clone()).source(&source.to_string());
    if args.f32 {
        b = b.scalar(ScalarType::F32);
    }
    match (args.ldlt, args.aba) {
        (true, _) => b = b.forward_dynamics(ForwardDynamicsMethod::Ldlt),
        (_, true) => b = b.forward_dynamics(ForwardDynamicsMethod::Aba),
        _ => {}
    }
    if args.no_snap {
        b = b.snap_rounding(false);
    }
    if args.no_fma {
        b = b.fma(false);
    }
    if args.no_dispatch {
        b = b.runtime_dispatch(false);
    }
    if args.no_branch_loops {
        b = b.branch_loops(false);
    }
    if let Some(t) = trig {
        b = b.trig(t);
    }
    if let Some(n) = args.split_lets {
        b = b.split_lets((n > 0).then_some(n));
    }
    if let Some(f) = &args.functions {
        b = b.functions(f);
    }
    if let Some(s) = &args.scene {
        b = b.scene_file(s);
    }
    Ok((b, model))
}

/// A builder error as a command-line error.
pub fn cli_error(e: BuildError, source: &RobotSource) -> CliError {
    let status = STATUS_BAD_INPUT;
    let text = e.to_string();
    let text = text.strip_prefix("dynagen: ").unwrap_or(&text);
    let message = match e {
        BuildError::UnknownFunction { .. } => format!("--functions: {text}"),
        BuildError::Codegen { .. } => format!("{source}: {text}"),
        _ => text.to_string(),
    };
    CliError { message, status }
}

/// Generates the module `args` ask for; also gives the robot's source and
/// its model.
fn module(args: &Args) -> Result<(RobotSource, dynagen::Model, GeneratedModule), CliError> {
    let source = args.robot.source();
    let (builder, model) = builder(args, &source)?;
    let module = builder.generate_module().map_err(|e| cli_error(e, &source))?;
    Ok((source, model, module))
}

/// Runs `dynagen generate`.
pub fn run(args: &Args) -> Result<Output, CliError> {
    let (source, model, module) = module(args)?;
    let mut notes: Vec<String> =
        module.op_counts().into_iter().map(|(name, count)| format!("{name}: {count}")).collect();
    let stdout = match &args.output {
        None => module.source,
        Some(path) => {
            std::fs::write(path, &module.source)
                .map_err(|e| CliError::input(path.display(), format!("cannot write the file: {e}")))?;
            notes.push(format!("wrote {}", path.display()));
            String::new()
        }
    };
    Ok(Output { stdout, warnings: source.warnings(&model), notes })
}
