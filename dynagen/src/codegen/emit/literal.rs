//! Float literals that read back as exactly the same number.

use crate::codegen::ScalarType;

/// The text of a float literal for `x` in `scalar`: Rust's shortest
/// representation that reads back as the same value (`{:?}`), which always
/// has a `.` or an exponent (`1.0`, `0.1`, `1e300`, `5e-324`), so it is a
/// float literal; a negative number (and `-0.0`) gets a leading `-`, which
/// Rust reads as a negation of the literal. `None` for NaN and infinities,
/// which have no literal. For `f32`, `x` is first rounded to `f32`.
pub fn float_literal_text(x: f64, scalar: ScalarType) -> Option<String> {
    let text = match scalar {
        ScalarType::F64 => format!("{x:?}"),
        ScalarType::F32 => format!("{:?}", x as f32),
    };
    let finite = match scalar {
        ScalarType::F64 => x.is_finite(),
        ScalarType::F32 => (x as f32).is_finite(),
    };
    finite.then_some(text)
}
