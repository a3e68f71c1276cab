
/// The sines and cosines of `x` (`f32`), entry by entry: `sin_cos_array` in
/// `f64`, rounded to `f32` (within 1 ulp of `f32` for every finite angle;
/// NaN and ±∞ give NaN).
#[inline]
pub fn sin_cos_array_f32<const N: usize>(x: &[f32; N]) -> ([f32; N], [f32; N]) {
    let (s, c) = sin_cos_array(&x.map(f64::from));
    (s.map(|v| v as f32), c.map(|v| v as f32))
}
