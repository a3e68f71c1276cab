//! `dynagen eval`: the generic solver ([`dynagen::Robot`]) on states read
//! from JSON.
//!
//! Input: `{"states": [{"q": […], "qd": […], "qdd": […], "tau": […]}, …]}`
//! (an optional `"joint_names": […]` is checked against the robot's order).
//! Output: `{"joint_names": […], "results": [{"tau", "M", "h", "g", "qdd"}, …]}`,
//! each output present when the state has the inputs it needs:
//!
//! | output | needs | computed by |
//! | --- | --- | --- |
//! | `tau` | q, qd, qdd | [`Robot::inverse_dynamics`] (RNEA) |
//! | `M` | q | [`Robot::mass_matrix`] (CRBA) |
//! | `h` | q, qd | [`Robot::bias_forces`] |
//! | `g` | q | [`Robot::gravity_torques`] |
//! | `qdd` | q, qd, tau | [`Robot::forward_dynamics`] (ABA; with mimic joints, M by LᵀDL), or the method `--fd` names |
//!
//! `--fd aba|ldlt|compensated|refined` picks the forward dynamics:
//! [`Robot::forward_dynamics`] (the default), [`Robot::forward_dynamics_ldlt`],
//! [`Robot::forward_dynamics_compensated`], or the compensated one with a step
//! of refinement ([`Robot::set_compensated_refinement`]).
//!
//! A floating-base robot (`--floating-base`, or a URDF `floating` root
//! joint) takes NQ-long q (base position, quaternion x, y, z, w, joints)
//! and NV-long qd, qdd, tau (the base's body twist or wrench, angular
//! first, then the joints), and every output is NV long (M NV × NV);
//! gravity is in the world frame. A quaternion whose norm is not 1 within
//! 1e-6 is an error naming it.
//!
//! With `--derivatives`, also (matrices `[output][input]`, one row per line):
//!
//! | output | needs | computed by |
//! | --- | --- | --- |
//! | `dtau_dq`, `dtau_dqd` | q, qd, qdd | [`Robot::inverse_dynamics_derivatives`] |
//! | `dqdd_dq`, `dqdd_dqd`, `minv` | q, qd, tau | [`Robot::forward_dynamics_derivatives`] |

use crate::error::{CliError, Output};
use crate::json::Json;
use crate::states::{parse_states, Entry, Layout, State};
use dynagen::Robot;
use nalgebra::Vector3;
use std::fmt;
use std::io::Read;
use std::path::PathBuf;

/// Arguments of `dynagen eval`.
#[derive(clap::Args, Debug)]
#[command(after_long_help = EVAL_HELP)]
pub struct Args {
    #[command(flatten)]
    pub robot: crate::robot_source::RobotArgs,
    /// The states, as JSON (`-` reads stdin).
    #[arg(long, short, value_name = "STATES.json")]
    pub input: PathBuf,
    /// Gravity in the base frame (a floating base: the world frame), m/s²
    /// (default: 0,0,-9.81).
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub gravity: Option<String>,
    /// Add the derivatives of the dynamics: dtau_dq, dtau_dqd (when the
    /// state has q, qd, qdd), dqdd_dq, dqdd_dqd and minv (when it has q, qd,
    /// tau), `[output][input]`.
    #[arg(long)]
    pub derivatives: bool,
    /// The forward dynamics behind "qdd".
    #[arg(long = "fd", value_enum, value_name = "METHOD", default_value_t = FdMethod::Aba)]
    pub fd: FdMethod,
}

/// The forward dynamics `--fd` picks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FdMethod {
    /// The articulated-body algorithm (Robot::forward_dynamics).
    Aba,
    /// M by the composite-rigid-body algorithm, h by RNEA, a sparse LᵀDL
    /// solve (Robot::forward_dynamics_ldlt).
    Ldlt,
    /// h and τ − h in compensated (double-f64) arithmetic, then the
    /// articulated-body algorithm (Robot::forward_dynamics_compensated): as
    /// many digits more as τ − h cancels.
    Compensated,
    /// Compensated, then one step of iterative refinement (the residual in
    /// compensated arithmetic): for an ill-conditioned mass matrix.
    Refined,
}

const EVAL_HELP: &str = "\
Input (STATES.json):
  {\"states\": [{\"q\": [...], \"qd\": [...], \"qdd\": [...], \"tau\": [...]}, ...]}
  One number per joint, in the order `dynagen inspect` lists (a mimic joint has
  none: it follows its master, unless --mimic independent). \"q\" is required;
  leave out a field to skip the outputs that need it. States count from 0 in
  messages. An optional \"joint_names\" list is checked against the robot's.
  With a floating base (--floating-base, or a URDF floating root joint):
  q = [base position x y z (world), quaternion x y z w (world <- base, unit
  norm), joints] (NQ = joints + 7); qd, qdd, tau and every output = [base
  body twist or wrench: angular x y z, linear x y z (base frame), joints]
  (NV = joints + 6); gravity in the world frame.

Output (stdout):
  {\"joint_names\": [...], \"results\": [{...}, ...]}, one result per state:
    tau  inverse dynamics (RNEA)          needs q, qd, qdd
    M    mass matrix, one row per line    needs q
    h    bias forces C(q,qd)qd + g(q)     needs q, qd
    g    gravity torques                  needs q
    qdd  forward dynamics                 needs q, qd, tau
         --fd aba (default): the articulated-body algorithm; ldlt: M, h and
         a sparse LTDL solve (what aba is with mimic joints); compensated: h and tau - h in double-f64, then
         ABA (accurate where tau nearly balances h at high speed); refined:
         compensated and one step of refinement (an ill-conditioned M)
  With --derivatives, also (matrices [output][input]: row i is output i):
    dtau_dq, dtau_dqd          d tau / d q, d tau / d qd   needs q, qd, qdd
    dqdd_dq, dqdd_dqd, minv    d qdd / d q, d qdd / d qd,
                               M^-1 = d qdd / d tau        needs q, qd, tau
  Numbers are printed with full round-trip precision.

Example:
  echo '{\"states\": [{\"q\": [0,0,0,0,0,0], \"qd\": [0,0,0,0,0,0]}]}' | dynagen eval --input -";

/// Where the states come from, for messages.
struct InputName<'a>(&'a std::path::Path);

impl fmt::Display for InputName<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.as_os_str() == "-" {
            f.write_str("<stdin>")
        } else {
            write!(f, "{}", self.0.display())
        }
    }
}

/// Runs `dynagen eval`.
pub fn run(args: &Args) -> Result<Output, CliError> {
    let (source, model) = args.robot.load()?;
    let layout = Layout::of(&model);
    let warnings = source.warnings(&model);
    let mut robot = Robot::new(model);
    if args.fd == FdMethod::Refined {
        robot.set_compensated_refinement(1);
    }
    if let Some(text) = &args.gravity {
        let g = parse_gravity(text)?;
        robot.set_gravity(Vector3::from(g)).map_err(|e| CliError::input("--gravity", e))?;
    }

    let name = InputName(&args.input);
    let text = read_input(&args.input).map_err(|e| CliError::input(&name, format!("cannot read the file: {e}")))?;
    let states = parse_states(&text, &layout).map_err(|e| CliError::input(&name, e))?;

    let mut results = Vec::with_capacity(states.len());
    for (i, state) in states.iter().enumerate() {
        let result = evaluate(&mut robot, state, &layout.v, (args.fd, args.derivatives))
            .map_err(|e| CliError::input(&name, format!("state {i}: {e}")))?;
        results.push(result);
    }
    let out = Json::Obj(vec![
        ("joint_names".into(), Json::Arr(layout.joints.iter().map(|n| Json::Str(n.clone())).collect())),
        ("results".into(), Json::Arr(results)),
    ]);
    Ok(Output { stdout: out.render(), warnings, notes: Vec::new() })
}

fn read_input(path: &std::path::Path) -> std::io::Result<String> {
    if path.as_os_str() == "-" {
        let mut s = String::new();
        std::io::stdin().read_to_string(&mut s)?;
        Ok(s)
    } else {
        std::fs::read_to_string(path)
    }
}

/// `X,Y,Z`: three finite numbers.
fn parse_gravity(text: &str) -> Result<[f64; 3], CliError> {
    let bad = |why: String| CliError::input(format!("--gravity \"{text}\""), why);
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(bad(format!(
            "expected three numbers X,Y,Z separated by commas (e.g. 0,0,-9.81), found {} part{}",
            parts.len(),
            if parts.len() == 1 { "" } else { "s" }
        )));
    }
    let mut g = [0.0; 3];
    for (k, (part, axis)) in parts.iter().zip(["X", "Y", "Z"]).enumerate() {
        g[k] = match part.parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            Ok(_) => return Err(bad(format!("{axis} = \"{part}\" is not a finite number"))),
            Err(_) => return Err(bad(format!("{axis} = \"{part}\" is not a number"))),
        };
    }
    Ok(g)
}

/// Every output the state has the inputs for, in the order tau, M, h, g, qdd
/// (by `fd`), and the derivatives when asked (`entries`: what each output
/// entry is, for messages).
fn evaluate(
    robot: &mut Robot,
    s: &State,
    entries: &[Entry],
    (fd, derivatives): (FdMethod, bool),
) -> Result<Json, String> {
    let err = |e: dynagen::InputError| e.to_string();
    let mut out = Vec::new();
    if let (Some(qd), Some(qdd)) = (&s.qd, &s.qdd) {
        let tau = robot.inverse_dynamics(&s.q, qd, qdd).map_err(err)?;
        out.push(("tau".to_string(), finite("tau", tau.as_slice(), entries)?));
    }
    out.push(("M".to_string(), matrix("M", &robot.mass_matrix(&s.q).map_err(err)?, entries)?));
    if let Some(qd) = &s.qd {
        let h = robot.bias_forces(&s.q, qd).map_err(err)?;
        out.push(("h".to_string(), finite("h", h.as_slice(), entries)?));
    }
    let g = robot.gravity_torques(&s.q).map_err(err)?;
    out.push(("g".to_string(), finite("g", g.as_slice(), entries)?));
    if let (Some(qd), Some(tau)) = (&s.qd, &s.tau) {
        let qdd = match fd {
            FdMethod::Aba => robot.forward_dynamics(&s.q, qd, tau),
            FdMethod::Ldlt => robot.forward_dynamics_ldlt(&s.q, qd, tau),
            FdMethod::Compensated | FdMethod::Refined => robot.forward_dynamics_compensated(&s.q, qd, tau),
        }
        .map_err(err)?;
        if let Some(k) = qdd.iter().position(|v| !v.is_finite()) {
            // singular here (not at every q: dependent joints are refused above)
            if let Some(set) = robot.model().singular_joints_at(s.q.as_slice()).first() {
                let names: Vec<String> = set.iter().map(|n| format!("\"{n}\"")).collect();
                return Err(format!(
                    "output \"qdd\"[{k}] ({}) is {}: the mass matrix is singular at this q (joints {} move without moving any mass in this configuration)",
                    entries[k],
                    qdd[k],
                    names.join(", ")
                ));
            }
        }
        out.push(("qdd".to_string(), finite("qdd", qdd.as_slice(), entries)?));
    }
    if derivatives {
        if let (Some(qd), Some(qdd)) = (&s.qd, &s.qdd) {
            let (dq, dqd) = robot.inverse_dynamics_derivatives(&s.q, qd, qdd).map_err(err)?;
            out.push(("dtau_dq".to_string(), matrix("dtau_dq", &dq, entries)?));
            out.push(("dtau_dqd".to_string(), matrix("dtau_dqd", &dqd, entries)?));
        }
        if let (Some(qd), Some(tau)) = (&s.qd, &s.tau) {
            let (dq, dqd, minv) = robot.forward_dynamics_derivatives(&s.q, qd, tau).map_err(err)?;
            out.push(("dqdd_dq".to_string(), matrix("dqdd_dq", &dq, entries)?));
            out.push(("dqdd_dqd".to_string(), matrix("dqdd_dqd", &dqd, entries)?));
            out.push(("minv".to_string(), matrix("minv", &minv, entries)?));
        }
    }
    Ok(Json::Obj(out))
}

/// A matrix as rows, each checked finite.
fn matrix(name: &str, m: &nalgebra::DMatrix<f64>, entries: &[Entry]) -> Result<Json, String> {
    let rows: Vec<Vec<f64>> = m.row_iter().map(|r| r.iter().copied().collect()).collect();
    for (r, row) in rows.iter().enumerate() {
        finite_row(name, row, r, entries)?;
    }
    Ok(Json::Arr(rows.iter().map(|r| Json::nums(r)).collect()))
}

/// JSON has no NaN or infinity: an output that overflowed is an error.
fn finite(name: &str, x: &[f64], entries: &[Entry]) -> Result<Json, String> {
    match x.iter().position(|v| !v.is_finite()) {
        None => Ok(Json::nums(x)),
        Some(k) => {
            Err(format!("output \"{name}\"[{k}] ({}) is {}: the inputs are too large for f64", entries[k], x[k]))
        }
    }
}

fn finite_row(name: &str, row: &[f64], r: usize, entries: &[Entry]) -> Result<(), String> {
    match row.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(c) => Err(format!(
            "output \"{name}\"[{r}][{c}] ({}, {}) is {}: the inputs are too large for f64",
            entries[r], entries[c], row[c]
        )),
    }
}
