//! An interpreter for traced functions: evaluates the kept nodes on numbers,
//! so that a trace and its simplifications can be checked against the
//! generic solver without compiling the generated code.

use super::fuse::Fusion;
use super::node::Node;
use super::traced::Traced;
use crate::Scalar;

/// An input vector that [`Traced::eval`] was not given, or given too short.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("function {function} reads {input}[{index}], which was not given")]
pub struct MissingInput {
    /// The function.
    pub function: String,
    /// The input vector.
    pub input: String,
    /// The entry read.
    pub index: usize,
}

/// A fused multiply-add `a·b + c` in the scalar `S`.
type MulAdd<S> = fn(S, S, S) -> S;

impl Traced {
    /// Evaluates the outputs on `f64` inputs given as `(name, values)`.
    pub fn eval(&self, inputs: &[(&str, &[f64])]) -> Result<Vec<f64>, MissingInput> {
        self.eval_as::<f64>(inputs)
    }
    /// Evaluates the outputs in the scalar `S` (e.g. `f32`), each constant
    /// converted with [`Scalar::from_f64`].
    pub fn eval_as<S: Scalar>(&self, inputs: &[(&str, &[f64])]) -> Result<Vec<S>, MissingInput> {
        self.eval_nodes(inputs, None)
    }
    /// Evaluates the outputs as the code emitted with `fusion` computes them
    /// on a target with fused multiply-adds: each fused sum by one
    /// [`f64::mul_add`] (a single rounding), everything else as
    /// [`Traced::eval`].
    pub fn eval_fused(&self, fusion: &Fusion, inputs: &[(&str, &[f64])]) -> Result<Vec<f64>, MissingInput> {
        self.eval_fused_as(fusion, inputs, f64::mul_add)
    }
    /// As [`Traced::eval_fused`], in the scalar `S` with its fused
    /// multiply-add `mul_add` (e.g. [`f32::mul_add`]).
    pub fn eval_fused_as<S: Scalar>(
        &self,
        fusion: &Fusion,
        inputs: &[(&str, &[f64])],
        mul_add: MulAdd<S>,
    ) -> Result<Vec<S>, MissingInput> {
        self.eval_nodes(inputs, Some((fusion, mul_add)))
    }
    fn eval_nodes<S: Scalar>(
        &self,
        inputs: &[(&str, &[f64])],
        fused: Option<(&Fusion, MulAdd<S>)>,
    ) -> Result<Vec<S>, MissingInput> {
        let nodes = self.nodes();
        let mut val: Vec<S> = Vec::with_capacity(nodes.len());
        for (id, node) in nodes.iter().enumerate() {
            if let Some((fu, mul_add)) = fused.and_then(|(fusion, m)| fusion.sum(id as u32).map(|fu| (fu, m))) {
                let sign = |x: S, negate: bool| if negate { -x } else { x };
                let a = sign(val[fu.a as usize], fu.negate_product);
                val.push(mul_add(a, val[fu.b as usize], sign(val[fu.c as usize], fu.negate_addend)));
                continue;
            }
            let v = match *node {
                Node::Const(_) => S::from_f64(node.constant().unwrap_or_default()),
                Node::Input { name, index } => {
                    let input = &self.input_names()[name as usize];
                    let x =
                        inputs.iter().find(|(n, _)| n == input).and_then(|(_, v)| v.get(index as usize)).ok_or_else(
                            || MissingInput {
                                function: self.name().to_string(),
                                input: input.clone(),
                                index: index as usize,
                            },
                        )?;
                    S::from_f64(*x)
                }
                Node::Add(a, b) => val[a as usize] + val[b as usize],
                Node::Sub(a, b) => val[a as usize] - val[b as usize],
                Node::Mul(a, b) => val[a as usize] * val[b as usize],
                Node::Div(a, b) => val[a as usize] / val[b as usize],
                Node::Neg(a) => -val[a as usize],
                Node::Sqrt(a) => val[a as usize].sqrt(),
                // The angle; its users take the sine or the cosine.
                Node::SinCos(a) => val[a as usize],
                Node::Sin(sc) => val[sc as usize].sin_cos().0,
                Node::Cos(sc) => val[sc as usize].sin_cos().1,
            };
            val.push(v);
        }
        Ok(self.outputs().iter().map(|&o| val[o as usize]).collect())
    }
}
