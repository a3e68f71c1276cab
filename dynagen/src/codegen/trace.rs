//! The functions of a generated module, traced from the generic algorithms.

use crate::algorithms::{aba, bias, crba, forward_dynamics, rnea, Workspace};
use crate::model::Model;
use crate::spatial::Vec3;
use crate::symbolic::{factor, Expr, Function, Rewrites, TraceActive, Tracer};

/// The functions of the generated-code contract (DESIGN.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FunctionKind {
    /// `inverse_dynamics(q, qd, qdd) -> τ`, by the recursive Newton-Euler algorithm.
    InverseDynamics,
    /// `mass_matrix(q) -> M`, by the composite-rigid-body algorithm.
    MassMatrix,
    /// `bias_forces(q, qd) -> h = C(q, q̇)q̇ + g(q)`.
    BiasForces,
    /// `gravity_torques(q) -> g(q)`.
    GravityTorques,
    /// `forward_dynamics(q, qd, tau) -> q̈` by the articulated-body algorithm.
    ForwardDynamicsAba,
    /// `forward_dynamics(q, qd, tau) -> q̈` by CRBA, RNEA and a sparse LᵀDL solve.
    ForwardDynamicsLdlt,
}

impl FunctionKind {
    /// Every kind, in the order a module lists them.
    pub const ALL: [FunctionKind; 6] = [
        FunctionKind::InverseDynamics,
        FunctionKind::MassMatrix,
        FunctionKind::BiasForces,
        FunctionKind::GravityTorques,
        FunctionKind::ForwardDynamicsAba,
        FunctionKind::ForwardDynamicsLdlt,
    ];
    /// The name of the generated function.
    pub fn fn_name(self) -> &'static str {
        match self {
            FunctionKind::InverseDynamics => "inverse_dynamics",
            FunctionKind::MassMatrix => "mass_matrix",
            FunctionKind::BiasForces => "bias_forces",
            FunctionKind::GravityTorques => "gravity_torques",
            FunctionKind::ForwardDynamicsAba | FunctionKind::ForwardDynamicsLdlt => "forward_dynamics",
        }
    }
    /// A label that tells the two forward dynamics apart.
    pub fn label(self) -> &'static str {
        match self {
            FunctionKind::ForwardDynamicsAba => "forward_dynamics (ABA)",
            FunctionKind::ForwardDynamicsLdlt => "forward_dynamics (CRBA + LTDL)",
            k => k.fn_name(),
        }
    }
    /// The input vectors, in argument order.
    pub fn inputs(self) -> &'static [&'static str] {
        match self {
            FunctionKind::InverseDynamics => &["q", "qd", "qdd"],
            FunctionKind::MassMatrix | FunctionKind::GravityTorques => &["q"],
            FunctionKind::BiasForces => &["q", "qd"],
            FunctionKind::ForwardDynamicsAba | FunctionKind::ForwardDynamicsLdlt => &["q", "qd", "tau"],
        }
    }
    /// Whether the output is the n×n matrix (row-major) rather than an n-vector.
    pub fn is_matrix(self) -> bool {
        self == FunctionKind::MassMatrix
    }
}

/// Runs the generic algorithm behind `kind` on symbolic inputs and keeps
/// what its outputs reach. Gravity is the model's, folded in as constants.
pub fn trace(model: &Model, kind: FunctionKind, rewrites: Rewrites) -> Result<Function, TraceActive> {
    let n = model.dof();
    let tracer = Tracer::start_with(rewrites)?;
    let args: Vec<Vec<Expr>> = kind.inputs().iter().map(|name| tracer.inputs(name, n)).collect();
    let mut ws = Workspace::<Expr>::new(model);
    let g = Vec3::<Expr>::from_f64(&model.gravity);
    let zero = tracer.constant(0.0);
    let mut out = vec![zero; if kind.is_matrix() { n * n } else { n }];
    match kind {
        FunctionKind::InverseDynamics => {
            rnea::rnea(model, &mut ws, &args[0], Some(&args[1]), Some(&args[2]), Some(&g), &[], &mut out)
        }
        FunctionKind::MassMatrix => crba::crba(model, &mut ws, &args[0], &mut out),
        FunctionKind::BiasForces => bias::bias_forces(model, &mut ws, &args[0], &args[1], Some(&g), &mut out),
        FunctionKind::GravityTorques => bias::gravity_torques(model, &mut ws, &args[0], &g, &mut out),
        FunctionKind::ForwardDynamicsAba => {
            aba::aba(model, &mut ws, &args[0], &args[1], &args[2], Some(&g), &[], &mut out)
        }
        FunctionKind::ForwardDynamicsLdlt => forward_dynamics::forward_dynamics_ldlt(
            model,
            &mut ws,
            &args[0],
            &args[1],
            &args[2],
            Some(&g),
            &[],
            &mut out,
        ),
    }
    drop(ws);
    let graph = tracer.finish();
    Ok(factor(&Function::new(kind.fn_name(), &graph, &out), rewrites))
}
