//! What generation gives: the module's source and its traced functions.

use super::trace::branches::Branched;
use super::{ForwardDynamicsMethod, Function, SinCosTrace, SnappedConstant};
use crate::algorithms::derivatives::Formulation;
use crate::symbolic::{OpCount, Traced};

/// One traced function of a module.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratedFunction {
    /// Which function.
    pub function: Function,
    /// For forward dynamics, the algorithm it was traced from (ABA or
    /// LᵀDL); `None` for the others.
    pub method: Option<ForwardDynamicsMethod>,
    /// For the derivatives of the dynamics, the formulation of ∂τ/∂(q, q̇)
    /// it was traced in (both are traced, the one with fewer operations is
    /// emitted); `None` for the others.
    pub formulation: Option<Formulation>,
    /// Its Rust name (`frame_pose_ee_link` for a frame function).
    pub name: String,
    /// Whether it is in the source (the forward dynamics not chosen is
    /// traced and counted only).
    pub emitted: bool,
    /// Its arguments in order, with their lengths (`NAME_sc` takes `s` and
    /// `c` instead of `q`, and `q` too if a joint is prismatic).
    pub inputs: Vec<(String, usize)>,
    /// The traced, dead-code-eliminated function of `q` (evaluate it with
    /// [`Traced::eval`], inputs by the names of [`inputs`](Self::inputs)).
    pub traced: Traced,
    /// The same with the sines and cosines as inputs: the body of `NAME_sc`.
    pub sin_cos_inputs: SinCosTrace,
    /// Its operation count.
    pub op_count: OpCount,
    /// For the forward dynamics' derivatives emitted as their factors and a
    /// loop (`codegen/emit/products.rs`): the factors' body (∂τ/∂q, ∂τ/∂q̇
    /// at q̈ = FD(q, q̇, τ), and M⁻¹; `NAME_factors_sc`) and its count;
    /// `None` where the whole trace is emitted.
    pub factors: Option<(SinCosTrace, OpCount)>,
    /// With [`CodegenOptions::branch_loops`](super::CodegenOptions::branch_loops):
    /// the body emitted instead of `sin_cos_inputs`, its branches in a loop.
    pub branched: Option<Branched>,
}

impl GeneratedFunction {
    /// The name, with the forward dynamics' algorithm: `forward_dynamics
    /// (ABA)`, `forward_dynamics (CRBA + LTDL)`.
    pub fn label(&self) -> String {
        match (self.method, self.formulation) {
            (Some(ForwardDynamicsMethod::Ldlt), _) => format!("{} (CRBA + LTDL)", self.name),
            (Some(_), _) => format!("{} (ABA)", self.name),
            (None, Some(f)) => format!("{} ({})", self.name, f.name()),
            (None, None) => self.name.clone(),
        }
    }
}

/// A generated module.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratedModule {
    /// The formatted Rust source, header included.
    pub source: String,
    /// Every traced function, in the module's order (both forward dynamics
    /// where both were traced, the one not emitted marked so).
    pub functions: Vec<GeneratedFunction>,
    /// The model constants replaced by 0 or ±1.
    pub snapped: Vec<SnappedConstant>,
    /// FNV-1a of the (reduced) model's [`canonical_text`](super::canonical_text).
    pub model_hash: u64,
}

impl GeneratedModule {
    /// The emitted function named `name` (`inverse_dynamics`,
    /// `frame_pose_ee_link`, …).
    pub fn function(&self, name: &str) -> Option<&GeneratedFunction> {
        self.functions.iter().find(|f| f.emitted && f.name == name)
    }
    /// Every traced function's [`label`](GeneratedFunction::label) and
    /// operation count (the forward dynamics not emitted marked so).
    pub fn op_counts(&self) -> Vec<(String, OpCount)> {
        let note = |f: &GeneratedFunction| if f.emitted { "" } else { " [not emitted]" };
        self.functions.iter().map(|f| (format!("{}{}", f.label(), note(f)), f.op_count)).collect()
    }
}
