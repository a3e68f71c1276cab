//! `dynagen inspect`: the robot as dynagen sees it, readable at a glance.
//!
//! The tree of moving bodies (each with its joint, the link it is made of and
//! the links fixed to it, merged in), the joint order with types, axes and
//! limits (and, for a joint that follows another, the coupling), each body's
//! mass and centre of mass, the frames, and the validation warnings.

use crate::error::{CliError, Output};
use crate::robot_source::RobotSource;
use dynagen::model::{JointKind, Model};
use dynagen::spatial::{Mat3, Vec3};
use std::fmt::Write;
use std::path::PathBuf;

/// Arguments of `dynagen inspect`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The robot's URDF file (default: the bundled UR5).
    #[arg(value_name = "ROBOT.urdf")]
    pub robot: Option<PathBuf>,
    #[command(flatten)]
    pub load: crate::robot_source::LoadArgs,
}

/// Runs `dynagen inspect`.
pub fn run(args: &Args) -> Result<Output, CliError> {
    let source = RobotSource::from_arg(args.robot.as_deref());
    let model = source.load(&args.load)?;
    Ok(Output::text(report(&model, &source.to_string())))
}

/// The whole report. `writeln!` into a String cannot fail.
fn report(model: &Model, source: &str) -> String {
    let mut o = String::new();
    let (n, nb) = (model.dof(), model.bodies.len());
    let links = model.frames.len();
    let _ = writeln!(o, "robot \"{}\" from {source}", model.name);
    let mimics = match nb - n {
        0 => String::new(),
        1 => " and 1 mimic joint that follows one of them".to_string(),
        k => format!(" and {k} mimic joints that follow them"),
    };
    let _ = writeln!(
        o,
        "  {n} joint{} (degrees of freedom){mimics}, {nb} moving bod{}, {links} link{} (every link is a frame)",
        plural(n),
        if nb == 1 { "y" } else { "ies" },
        plural(links)
    );
    if model.is_floating() {
        let _ = writeln!(
            o,
            "  a floating base (the root link moves freely): q has NQ = {} entries (base position, quaternion x y z \
             w, joints), qd, qdd and tau NV = {} (the base's body twist or wrench, angular first, then the joints)",
            model.nq(),
            model.nv()
        );
    }
    let frame = if model.is_floating() { "world" } else { "base" };
    let _ = writeln!(o, "  gravity {} m/s² in the {frame} frame", vec3(&model.gravity));

    // Tree.
    let _ = writeln!(o, "\ntree (joint index, joint, type -> the link the body is made of; + links fixed to it):");
    let base_fixed = fixed_links(model, None);
    let base = if model.is_floating() { "floating base" } else { "fixed base" };
    let _ = writeln!(o, "  {} ({base}){}", model.root, plus_fixed(&base_fixed));
    let roots: Vec<usize> = (0..nb).filter(|&i| model.bodies[i].parent.is_none()).collect();
    tree(model, &roots, "  ", &mut o);

    // Joints.
    let _ = writeln!(o, "\njoints (the order of every vector and matrix index; limits: position, velocity, effort):");
    let mut rows = vec![row(["#", "name", "type", "axis", "lower", "upper", "velocity", "effort"])];
    if model.has_mimic() {
        rows[0].push("follows (mimic: q = multiplier·q_master + offset)".into());
    }
    for (i, b) in model.bodies.iter().enumerate() {
        let j = &b.joint;
        let (pos_unit, vel_unit, eff_unit) = if j.is_revolute() { ("rad", "rad/s", "N·m") } else { ("m", "m/s", "N") };
        let lim = |x: f64, unit: &str| format!("{} {unit}", num(x));
        let (lower, upper, velocity, effort) = match &j.limits {
            Some(l) => {
                (lim(l.lower, pos_unit), lim(l.upper, pos_unit), lim(l.velocity, vel_unit), lim(l.effort, eff_unit))
            }
            None => ("-".into(), "-".into(), "-".into(), "-".into()),
        };
        let index = if model.mimic(i).is_some() { "-".to_string() } else { model.column(i).to_string() };
        let mut cells = vec![index, j.name.clone(), kind(j.kind).into(), vec3(&j.axis), lower, upper, velocity, effort];
        if model.has_mimic() {
            cells.push(model.mimic(i).map_or("-".into(), |m| {
                let offset = match m.offset {
                    0.0 => String::new(),
                    o if o < 0.0 => format!(" − {}", num(-o)),
                    o => format!(" + {}", num(o)),
                };
                format!("{} × {}{offset}", num(m.multiplier), model.bodies[m.master].joint.name)
            }));
        }
        rows.push(cells);
    }
    table(&rows, &mut o);

    // Bodies.
    let _ = writeln!(o, "\nbodies (mass and centre of mass in the body's frame, fixed links included):");
    let mut rows = vec![row(["#", "body (link)", "mass", "centre of mass", "links merged in"])];
    for (i, b) in model.bodies.iter().enumerate() {
        let com = match b.inertia.com() {
            Some(c) => format!("{} m", vec3(&c)),
            None => "- (no mass)".into(),
        };
        let merged = fixed_links(model, Some(i));
        rows.push(vec![
            i.to_string(),
            b.name.clone(),
            format!("{} kg", num(b.inertia.mass)),
            com,
            if merged.is_empty() { "-".into() } else { merged.join(", ") },
        ]);
    }
    table(&rows, &mut o);
    let moving = model.total_mass();
    let (moving_what, base_what) = match model.is_floating() {
        true => ("in the joints' bodies", "in the floating base"),
        false => ("moving", "fixed to the base (it does not enter the dynamics)"),
    };
    let _ = writeln!(
        o,
        "  total mass {} kg: {} kg {moving_what}, {} kg {base_what}",
        num(moving + model.base_mass),
        num(moving),
        num(model.base_mass)
    );

    // Frames.
    let _ = writeln!(o, "\nframes (every link; its pose in the frame of the body it belongs to):");
    let mut rows = vec![row(["frame", "on body", "xyz (m)", "rpy (rad)"])];
    for f in &model.frames {
        let body = match f.body {
            Some(b) => format!("{b} {}", model.bodies[b].name),
            None => "base".into(),
        };
        rows.push(vec![f.name.clone(), body, vec3(&f.placement.trans), vec3(&Vec3(rpy(&f.placement.rot)))]);
    }
    table(&rows, &mut o);

    // Warnings.
    if model.warnings.is_empty() {
        let _ = writeln!(o, "\nwarnings: none");
    } else {
        let _ = writeln!(o, "\nwarnings ({}):", model.warnings.len());
        for w in &model.warnings {
            let _ = writeln!(o, "  warning: {w}");
        }
    }
    o
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// Draws the bodies below one parent, depth first, children in joint order.
fn tree(model: &Model, children: &[usize], prefix: &str, o: &mut String) {
    for (k, &i) in children.iter().enumerate() {
        let last = k + 1 == children.len();
        let b = &model.bodies[i];
        let merged = fixed_links(model, Some(i));
        // a mimic joint has no index: it follows its master's
        let index = match model.mimic(i) {
            Some(m) => format!("follows {}", model.bodies[m.master].joint.name),
            None => model.column(i).to_string(),
        };
        let _ = writeln!(
            o,
            "{prefix}{} [{index}] {} ({}) -> {}{}",
            if last { "└─" } else { "├─" },
            b.joint.name,
            kind(b.joint.kind),
            b.name,
            plus_fixed(&merged)
        );
        let below: Vec<usize> = (i + 1..model.bodies.len()).filter(|&c| model.bodies[c].parent == Some(i)).collect();
        let deeper = format!("{prefix}{}", if last { "   " } else { "│  " });
        tree(model, &below, &deeper, o);
    }
}

/// The links fixed to a body (or to the base), other than the body's own.
fn fixed_links(model: &Model, body: Option<usize>) -> Vec<&str> {
    let own = match body {
        Some(b) => model.bodies[b].name.as_str(),
        None => model.root.as_str(),
    };
    model.frames.iter().filter(|f| f.body == body && f.name != own).map(|f| f.name.as_str()).collect()
}

fn plus_fixed(links: &[&str]) -> String {
    if links.is_empty() {
        String::new()
    } else {
        format!(" + {}", links.join(", "))
    }
}

fn kind(k: JointKind) -> &'static str {
    match k {
        JointKind::Revolute => "revolute",
        JointKind::Continuous => "continuous",
        JointKind::Prismatic => "prismatic",
    }
}

/// Roll, pitch, yaw of R = Rz(yaw)·Ry(pitch)·Rx(roll) (URDF's convention).
fn rpy(r: &Mat3<f64>) -> [f64; 3] {
    let m = &r.0;
    let pitch = (-m[2][0]).clamp(-1.0, 1.0).asin();
    if m[2][0].abs() < 1.0 - 1e-12 {
        [m[2][1].atan2(m[2][2]), pitch, m[1][0].atan2(m[0][0])]
    } else {
        // Gimbal lock: only roll ∓ yaw is defined; put it all in roll.
        [(-m[1][2]).atan2(m[1][1]), pitch, 0.0]
    }
}

/// A number for reading: at most 6 significant digits, no trailing zeros,
/// no "-0".
fn num(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return x.to_string();
    }
    let e = x.abs().log10().floor() as i32;
    if (-4..6).contains(&e) {
        let decimals = (5 - e).max(0) as usize;
        let s = format!("{x:.decimals$}");
        let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s };
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    } else {
        let s = format!("{x:.5e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa =
            if mantissa.contains('.') { mantissa.trim_end_matches('0').trim_end_matches('.') } else { mantissa };
        format!("{mantissa}e{exp}")
    }
}

fn vec3(v: &Vec3<f64>) -> String {
    format!("({}, {}, {})", num(v.0[0]), num(v.0[1]), num(v.0[2]))
}

fn row<const N: usize>(cells: [&str; N]) -> Vec<String> {
    cells.iter().map(|s| s.to_string()).collect()
}

/// Left-aligned columns, two spaces apart, indented by two.
fn table(rows: &[Vec<String>], o: &mut String) {
    let cols = rows.iter().map(Vec::len).max().unwrap_or(0);
    let width: Vec<usize> =
        (0..cols).map(|c| rows.iter().filter_map(|r| r.get(c)).map(|s| s.chars().count()).max().unwrap_or(0)).collect();
    for r in rows {
        let mut line = String::from(" ");
        for (c, cell) in r.iter().enumerate() {
            let pad = width[c] - cell.chars().count();
            let _ = write!(line, " {cell}{}", " ".repeat(pad));
            line.push(' ');
        }
        let _ = writeln!(o, "{}", line.trim_end());
    }
}
