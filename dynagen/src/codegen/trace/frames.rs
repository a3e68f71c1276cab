//! The frame functions of a module (a frame's pose, its body and world
//! Jacobians, its acceleration bias J̇q̇), on a fixed or a floating base,
//! written once over any scalar: traced on [`Expr`] for the module, counted
//! on [`Counting`](crate::scalar::Counting) for `dynagen ops`, run on `f64`
//! by the tests.

use super::CodegenError;
use crate::algorithms::{floating, frame_acceleration, kinematics, Workspace};
use crate::codegen::emit::Sizes;
use crate::codegen::Function;
use crate::model::Model;
use crate::scene::SceneModel;
use crate::symbolic::{Expr, Rewrites, Traced, Tracer};
use crate::Scalar;

/// Writes the outputs of the frame function `f` of `frame` (an index into
/// the model's frames) into `out`: `args` are its state vectors (q, and q̇
/// for the acceleration bias; NQ/NV long on a floating base), `out` has
/// [`Function::output_len`] entries. On a floating base the pose and the
/// world Jacobian are in the world frame.
pub(crate) fn frame_outputs<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    f: &Function,
    frame: usize,
    args: &[Vec<S>],
    out: &mut [S],
) {
    let q = &args[0];
    if let Function::FrameAccelerationBias(_) = f {
        let a = frame_acceleration::frame_acceleration_bias(model, ws, q, &args[1], frame);
        out.copy_from_slice(&a.to_array());
        return;
    }
    let floating = model.is_floating();
    match floating {
        true => floating::kinematics::forward_kinematics(model, ws, q),
        false => kinematics::forward_kinematics(model, ws, q),
    }
    match f {
        Function::FramePose(_) => {
            let t = match floating {
                true => floating::kinematics::frame_pose_world(model, ws, q, frame),
                false => kinematics::frame_pose(model, ws, frame),
            };
            for (o, x) in out.iter_mut().zip(t.to_homogeneous().iter().flatten()) {
                *o = *x;
            }
        }
        Function::FrameJacobian(_) if floating => floating::kinematics::body_jacobian(model, ws, frame, out),
        Function::FrameJacobian(_) => kinematics::body_jacobian(model, ws, frame, out),
        Function::FrameWorldJacobian(_) if floating => {
            floating::kinematics::space_jacobian_world(model, ws, q, frame, out)
        }
        Function::FrameWorldJacobian(_) => kinematics::space_jacobian(model, ws, frame, out),
        _ => unreachable!("frame_outputs: {f:?} is not a frame function"),
    }
}

/// Traces the frame function `f` of `scene` (its frame named `name`)
/// without factoring.
pub(super) fn trace_unfactored(
    scene: &SceneModel,
    f: &Function,
    name: &str,
    rewrites: Rewrites,
) -> Result<Traced, CodegenError> {
    let model = &scene.model;
    let frame = scene.frame(f.name(), name).map_err(|e| CodegenError::Scene(Box::new(e)))?;
    let tracer = Tracer::start_with(rewrites)?;
    let args: Vec<Vec<Expr>> =
        f.vectors().iter().map(|v| tracer.inputs(v, if *v == "q" { model.nq() } else { model.nv() })).collect();
    let mut ws = Workspace::<Expr>::new(model);
    let mut out = vec![tracer.constant(0.0); f.output_len(Sizes::of(model))];
    frame_outputs(model, &mut ws, f, frame, &args, &mut out);
    drop(ws);
    Ok(Traced::new(&f.rust_name(), &tracer.finish(), &out))
}
