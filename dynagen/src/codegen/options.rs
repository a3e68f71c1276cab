//! What code generation is asked for: [`CodegenOptions`] and its enums.
//! Each enum parses from the one spelling the command line, the macros and
//! scene files share ([`FromStr`]).

use super::Function;
use crate::symbolic::Rewrites;
use std::str::FromStr;

/// The float type of the generated code.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ScalarType {
    /// `f64`.
    #[default]
    F64,
    /// `f32` (constants rounded to `f32`).
    F32,
}

/// How the generated `forward_dynamics` computes q̈.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ForwardDynamicsMethod {
    /// Whichever of the two is faster without being less accurate, measured
    /// on the model when the module is generated (see
    /// [`fd_choice`](super::fd_choice)); with a run-time payload, LᵀDL (the
    /// articulated-body algorithm has no payload input).
    #[default]
    Auto,
    /// The articulated-body algorithm: the accurate one on long chains.
    Aba,
    /// M by CRBA, h by RNEA, then a sparse LᵀDL solve.
    Ldlt,
}

/// Where the generated code gets the sines and cosines of the joint
/// angles from.
///
/// Every function has one body, `NAME_sc(s, c, [q,] …)`, which reads the
/// sine `s[i]` and cosine `c[i]` of each joint's angle θᵢ = `q[i]` (times
/// `|axis|` when a revolute joint's axis is not a unit vector; the entries
/// of prismatic joints are not read) and takes `q` only when the model has
/// a prismatic joint. Except with [`Trig::Inputs`], the module also has the
/// contract's `NAME(q, …)`, which computes the sines and cosines and calls
/// `NAME_sc`. Every module has `sin_cos_all(q)`, the batched sine and
/// cosine of [`sin_cos_array`](super::sin_cos_array) (no std, no dependency, within 1 ulp).
///
/// Why `Batched` is the default:
///
/// - **Speed.** Whole generated functions, sines and cosines included, run
///   faster than with std's `sin_cos` on every machine measured
///   (`docs/performance.md`).
/// - **Accuracy.** Within 1 ulp for every finite angle, close to std's
///   (`tests` of the kernel measure both); the bodies' own rounding is far
///   larger.
/// - **No std, no dependency.** The default module is then `#![no_std]`
///   and depends on nothing (a scene's square roots too: the module's own,
///   correctly rounded `sqrt`), which is what a module vendored into a
///   real-time controller needs.
///
/// [`Trig::Std`] remains an option (`--trig std`, the macros' `trig =
/// std`), for code that wants the platform's `sin_cos`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Trig {
    /// `NAME(q, …)` calls `f64::sin_cos` (or `f32::sin_cos`) per joint, and
    /// a scene's square roots are `f64::sqrt`: needs std.
    Std,
    /// `NAME(q, …)` calls the module's `sin_cos_array` on the angles its
    /// body reads, and a scene's square roots are the module's `sqrt`
    /// (`sqrtf`): `#![no_std]`, no dependency, faster than `Std` in the
    /// benchmarks. The default.
    #[default]
    Batched,
    /// `NAME(q, …)` calls `libm::sincos` (`libm::sincosf` for `f32`), and a
    /// scene's square roots are `libm::sqrt` (`sqrtf`): `#![no_std]`, needs
    /// the `libm` crate.
    Libm,
    /// Only the `NAME_sc` functions (and `sin_cos_all`), a scene's square
    /// roots the module's `sqrt`: `#![no_std]`, no dependency; the caller
    /// brings the sines and cosines.
    Inputs,
}

impl Trig {
    /// Whether the module needs std (only [`Trig::Std`] does).
    pub fn needs_std(self) -> bool {
        self == Trig::Std
    }
}

/// What to generate and how. Every field has a chained setter, so a
/// build-script builder or a macro can fill it in one expression.
#[derive(Clone, Debug, PartialEq)]
pub struct CodegenOptions {
    /// The module's name, for the header and the [`Builder`](super::Builder)'s
    /// output file (default: the robot's).
    pub name: Option<String>,
    /// The float type of the output (`f64`).
    pub scalar: ScalarType,
    /// Which functions, in the order the module lists them
    /// ([`Function::DEFAULT`]: the five of the generated-code contract).
    pub functions: Vec<Function>,
    /// The forward-dynamics algorithm emitted (the faster one that is as
    /// accurate, [`ForwardDynamicsMethod::Auto`]); both are traced and
    /// counted in the header.
    pub forward_dynamics: ForwardDynamicsMethod,
    /// Replace constants that are 0 or ±1 up to rounding (on); see
    /// [`snap_rounding`](super::snap_rounding) for the rule and why.
    pub snap_rounding: bool,
    /// Move the inertia a joint cannot move to its parent (on); see
    /// [`regroup_inertia`](super::regroup_inertia) (with the body frames
    /// moved first: [`center_prismatic_leaves`](super::center_prismatic_leaves),
    /// [`slide_origins_along_axes`](super::slide_origins_along_axes)).
    pub regroup_inertia: bool,
    /// The value-changing graph rewrites (on); see [`Rewrites`].
    pub rewrites: Rewrites,
    /// Where the model came from (a file name), for the header.
    pub source: Option<String>,
    /// Where the sines and cosines come from ([`Trig::Batched`]: the
    /// module's own, no std).
    pub trig: Trig,
    /// A function body of more than this many `let`s is emitted as private
    /// parts of at most this many, called in order by the public function
    /// ([`DEFAULT_SPLIT_LETS`]; `None`: never split). Splitting keeps rustc
    /// from overflowing its stack on long bodies in debug builds and bounds
    /// LLVM's super-linear passes in release builds; the results are bit
    /// for bit those of the unsplit body.
    pub split_lets: Option<usize>,
    /// Write `a·b ± c` as `fma(a, b, ±c)` (on): one fused multiply-add
    /// with a single rounding where the target has one (x86-64 built with
    /// the `fma` target feature, aarch64), else `a * b + c`, bit for bit
    /// the unfused code; see [`crate::symbolic::Fusion`] for which sums.
    /// On by default: it costs nothing where the target has no fused
    /// multiply-add (the same bits, the same instructions), and where it
    /// has, the bodies, bound by the floating-point ports, run fewer
    /// operations (`docs/performance.md`); with
    /// [`runtime_dispatch`](Self::runtime_dispatch) a default x86-64 build
    /// has a copy with FMA too. Off, the bodies give the
    /// same bits on every target. (The module's `sin_cos_array` fuses its
    /// polynomials wherever the target has FMA, either way: within 1 ulp
    /// both ways.)
    pub fma: bool,
    /// On x86-64 builds without the `avx2` and `fma` target features (a
    /// default `cargo build`), compile every public function twice, once
    /// for the build's target and once for AVX2 and FMA, and pick the copy
    /// at run time by what the processor has (on): see
    /// `docs/architecture.md`. Builds that have both features, and other
    /// targets, get one copy, as without it. On by default, because most
    /// x86-64 processors in use have both and the bodies are bound by the
    /// floating-point ports: a default build then runs as fast as a native
    /// one. x86-64 builds without AVX-512 (F, VL and DQ) get a third copy
    /// for processors that have it: the AVX2 copy's operations and bits,
    /// with 32 vector registers (long bodies spill less); it needs Rust
    /// 1.89. The
    /// price: a default build's results differ in the last bits between
    /// machines with and without FMA (on both they are within the accuracy
    /// the tests check, 1e-12 of the generic solver), and the bodies are
    /// compiled three times. Off, a build gives the same bits on every
    /// x86-64 machine.
    pub runtime_dispatch: bool,
    /// Emit sibling subtrees of one shape (a humanoid's legs and arms, a
    /// quadruped's legs) as one body, reading its constants from a table,
    /// in τ, h, M and the forward dynamics by the articulated-body
    /// algorithm (on). In `f64` the body runs on two or four branches at
    /// once, one to each lane of a vector register (four where the
    /// processor has AVX2), with the scalar code's bits in every lane; in
    /// `f32` it runs in a loop. It writes a third to a half of the unrolled
    /// code, and runs each instruction on several branches (see
    /// `codegen/trace/branches.rs`). Off, or for a function whose body with
    /// branches would be longer than [`split_lets`](Self::split_lets), every
    /// branch is unrolled.
    pub branch_loops: bool,
}

/// The default [`CodegenOptions::split_lets`]: 2,500 `let`s. rustc with
/// debug information overflows its stack at somewhat more `let`s in one
/// function (`docs/performance.md`); the bodies of the bundled robots stay
/// whole.
pub const DEFAULT_SPLIT_LETS: usize = 2500;

impl Default for CodegenOptions {
    fn default() -> Self {
        CodegenOptions {
            name: None,
            scalar: ScalarType::F64,
            functions: Function::DEFAULT.to_vec(),
            forward_dynamics: ForwardDynamicsMethod::Auto,
            snap_rounding: true,
            regroup_inertia: true,
            rewrites: Rewrites::default(),
            source: None,
            trig: Trig::default(),
            split_lets: Some(DEFAULT_SPLIT_LETS),
            fma: true,
            runtime_dispatch: true,
            branch_loops: true,
        }
    }
}

impl CodegenOptions {
    /// Sets the float type.
    pub fn scalar(mut self, scalar: ScalarType) -> Self {
        self.scalar = scalar;
        self
    }
    /// Sets which functions to generate (repeats are dropped).
    pub fn functions(mut self, functions: impl IntoIterator<Item = Function>) -> Self {
        self.functions.clear();
        for f in functions {
            if !self.functions.contains(&f) {
                self.functions.push(f);
            }
        }
        self
    }
    /// Adds a function to generate.
    pub fn function(mut self, function: Function) -> Self {
        if !self.functions.contains(&function) {
            self.functions.push(function);
        }
        self
    }
    /// Sets the module's name.
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }
    /// Sets the forward-dynamics algorithm.
    pub fn forward_dynamics(mut self, method: ForwardDynamicsMethod) -> Self {
        self.forward_dynamics = method;
        self
    }
    /// Turns the rounding snap on or off.
    pub fn snap_rounding(mut self, on: bool) -> Self {
        self.snap_rounding = on;
        self
    }
    /// Turns the regrouping of inertial parameters on or off.
    pub fn regroup_inertia(mut self, on: bool) -> Self {
        self.regroup_inertia = on;
        self
    }
    /// Sets the value-changing rewrites.
    pub fn rewrites(mut self, rewrites: Rewrites) -> Self {
        self.rewrites = rewrites;
        self
    }
    /// Sets where the sines and cosines come from.
    pub fn trig(mut self, trig: Trig) -> Self {
        self.trig = trig;
        self
    }
    /// Sets the longest body emitted as one function (`None`: no limit).
    pub fn split_lets(mut self, lets: Option<usize>) -> Self {
        self.split_lets = lets;
        self
    }
    /// Turns fused multiply-adds on or off.
    pub fn fma(mut self, on: bool) -> Self {
        self.fma = on;
        self
    }
    /// Turns the loops over branches of one shape on or off ([`CodegenOptions::branch_loops`]).
    pub fn branch_loops(mut self, on: bool) -> Self {
        self.branch_loops = on;
        self
    }
    /// Turns the run-time choice of AVX-512 and AVX2 + FMA copies on or off.
    pub fn runtime_dispatch(mut self, on: bool) -> Self {
        self.runtime_dispatch = on;
        self
    }
    /// Names the model's source for the header.
    pub fn source(mut self, source: impl Into<String>) -> Self {
        self.source = Some(source.into());
        self
    }
}

/// An option enum's spellings, one table per enum: what [`FromStr`] reads
/// (the command line, the macros, scene files) and `name` writes back.
trait Spelled: Copy + PartialEq + 'static {
    /// What the option is, for an error.
    const WHAT: &'static str;
    /// Each spelling and its value.
    const SPELLINGS: &'static [(&'static str, Self)];
    /// The value spelled `s` (surrounding white space ignored); the error
    /// lists the spellings.
    fn parse(s: &str) -> Result<Self, String> {
        let s = s.trim();
        Self::SPELLINGS.iter().find(|(name, _)| *name == s).map(|&(_, v)| v).ok_or_else(|| {
            let names: Vec<&str> = Self::SPELLINGS.iter().map(|(name, _)| *name).collect();
            format!("unknown {} \"{s}\" (expected {})", Self::WHAT, names.join(", "))
        })
    }
    /// Its spelling.
    fn spelling(self) -> &'static str {
        Self::SPELLINGS.iter().find(|(_, v)| *v == self).map_or("", |(name, _)| name)
    }
}

impl Spelled for ScalarType {
    const WHAT: &'static str = "scalar";
    const SPELLINGS: &'static [(&'static str, Self)] = &[("f64", ScalarType::F64), ("f32", ScalarType::F32)];
}

impl Spelled for Trig {
    const WHAT: &'static str = "trigonometry";
    const SPELLINGS: &'static [(&'static str, Self)] =
        &[("batched", Trig::Batched), ("std", Trig::Std), ("libm", Trig::Libm), ("inputs", Trig::Inputs)];
}

impl Spelled for ForwardDynamicsMethod {
    const WHAT: &'static str = "forward-dynamics method";
    const SPELLINGS: &'static [(&'static str, Self)] = &[
        ("auto", ForwardDynamicsMethod::Auto),
        ("aba", ForwardDynamicsMethod::Aba),
        ("ldlt", ForwardDynamicsMethod::Ldlt),
    ];
}

impl FromStr for ScalarType {
    type Err = String;
    /// `f64` or `f32`.
    fn from_str(s: &str) -> Result<Self, String> {
        Self::parse(s)
    }
}

impl FromStr for Trig {
    type Err = String;
    /// `batched`, `std`, `libm` or `inputs`.
    fn from_str(s: &str) -> Result<Self, String> {
        Self::parse(s)
    }
}

impl FromStr for ForwardDynamicsMethod {
    type Err = String;
    /// `auto`, `aba` or `ldlt`.
    fn from_str(s: &str) -> Result<Self, String> {
        Self::parse(s)
    }
}

impl Trig {
    /// Its spelling ([`FromStr`] reads it back).
    pub fn name(self) -> &'static str {
        self.spelling()
    }
}

impl ScalarType {
    /// The Rust type's name (its spelling; [`FromStr`] reads it back).
    pub fn name(self) -> &'static str {
        self.spelling()
    }
}

impl ForwardDynamicsMethod {
    /// Its spelling ([`FromStr`] reads it back).
    pub fn name(self) -> &'static str {
        self.spelling()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every spelling parses to its value and is what `name` writes; an
    /// unknown one is an error that lists them all.
    fn round_trips<T: Spelled + FromStr<Err = String> + std::fmt::Debug>(name: impl Fn(T) -> &'static str) {
        for &(spelling, value) in T::SPELLINGS {
            assert_eq!(format!(" {spelling} ").parse::<T>(), Ok(value));
            assert_eq!(name(value), spelling);
        }
        let e = "nonsense".parse::<T>().unwrap_err();
        assert!(e.starts_with(&format!("unknown {} \"nonsense\" (expected ", T::WHAT)), "{e}");
        assert!(T::SPELLINGS.iter().all(|(s, _)| e.contains(s)), "{e}");
    }

    #[test]
    fn each_option_enum_reads_back_what_it_writes() {
        round_trips(ScalarType::name);
        round_trips(Trig::name);
        round_trips(ForwardDynamicsMethod::name);
    }
}
