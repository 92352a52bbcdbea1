//! Scaled fields: a raw integer on the wire, `raw * factor + offset` in Rust; the clamp range,
//! the rounding back to raw, and the raw value's fit in its integer type.

use crate::error::{DecodeError, EncodeError};
use crate::float::Float;

/// How a scaled field's physical value becomes its raw integer when encoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Rounding {
    /// To the nearest integer, halves away from zero.
    #[default]
    Nearest,
    /// Toward zero, as a C cast; but a quotient within float noise (a relative 1e-6) of an
    /// integer is that integer, so that a decoded value (`raw * factor`, rounded to `f32`)
    /// encodes back to the same raw value.
    Truncate,
}

/// The physical value of a scaled field's raw value: `raw * factor + offset`, in the field's
/// float type. A factor that is the reciprocal of an integer `n` (`0.1`, `0.001`: most scales)
/// divides by `n` instead, which rounds once, so that `-1500` at `0.001` is exactly `-1.5` in
/// `f32` too (`0.001f32` is not `0.001`, and the product would be off by one unit in the last
/// place). With constant arguments, as generated code passes them, the choice folds away.
///
/// ```
/// use protocol_runtime::field::to_physical;
/// assert_eq!(to_physical(250.0, 0.1, -5.0), 20.0);
/// assert_eq!(to_physical(-1500.0f32, 0.001, 0.0), -1.5);
/// assert_eq!(to_physical(100.0f32, 0.015, 0.0), 1.5);
/// ```
#[allow(
    clippy::arithmetic_side_effects,
    reason = "float arithmetic (F is f32 or f64): it neither wraps nor panics"
)]
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn to_physical<F: Float>(raw: F, factor: F, offset: F) -> F {
    match reciprocal_integer(factor) {
        Some(n) => raw / n + offset,
        None => raw * factor + offset,
    }
}

/// The integer `n` whose reciprocal `factor` is, within float noise (`1 / 0.001f32` is
/// `999.99994`), if there is one.
#[allow(
    clippy::arithmetic_side_effects,
    reason = "float arithmetic (F is f32 or f64): it neither wraps nor panics"
)]
#[cfg_attr(not(protocol_opt0), inline(always))]
fn reciprocal_integer<F: Float>(factor: F) -> Option<F> {
    let inv = F::ONE / factor;
    let n = if inv >= F::ZERO {
        inv + F::HALF
    } else {
        inv - F::HALF
    }
    .cut_int();
    let off = (inv - n).magnitude();
    (n != F::ZERO && off <= F::NOISE * n.magnitude()).then_some(n)
}

/// The raw value of a physical one for a scaled field whose wire type is a float: the inverse
/// of [`to_physical`], `(physical - offset) / factor`, multiplying by `n` where
/// [`to_physical`] divides by it. No rounding: the caller converts the result to the wire's
/// float type (`as f32`, or to a half), which rounds to the nearest.
///
/// ```
/// use protocol_runtime::field::{to_physical, unscale};
/// assert_eq!(unscale(20.0, 0.1, -5.0), 250.0);
/// assert_eq!(unscale(to_physical(3.0f64, 0.25, 1.0), 0.25, 1.0), 3.0);
/// ```
#[allow(
    clippy::arithmetic_side_effects,
    reason = "float arithmetic (F is f32 or f64): it neither wraps nor panics"
)]
#[inline(always)]
pub fn unscale<F: Float>(physical: F, factor: F, offset: F) -> F {
    match reciprocal_integer(factor) {
        Some(n) => (physical - offset) * n,
        None => (physical - offset) / factor,
    }
}

/// Whether a decoded physical value lies in the clamp range `lo..=hi` of its scaled field,
/// allowing for the rounding of `raw * factor + offset` in `F` (a raw value at the limit is
/// inside).
///
/// ```
/// use protocol_runtime::field::within_clamp;
/// assert!(within_clamp(0.5235000000000001, -0.5235, 0.5235));
/// assert!(!within_clamp(0.56, -0.5235, 0.5235));
/// ```
#[allow(
    clippy::arithmetic_side_effects,
    reason = "float arithmetic (F is f32 or f64): it neither wraps nor panics"
)]
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn within_clamp<F: Float>(physical: F, lo: F, hi: F) -> bool {
    let slack = F::CLAMP_SLACK * (hi - lo).at_least_one();
    physical >= lo - slack && physical <= hi + slack
}

/// A decoded physical value, if it lies in its field's clamp range (see [`within_clamp`]).
///
/// # Errors
///
/// [`DecodeError::ValueOutOfRange`] outside the range: the encoder would clamp the value, so
/// the bytes would not encode back to themselves.
///
/// ```
/// use protocol_runtime::{DecodeError, field::check_clamp};
/// assert_eq!(check_clamp(0.25, -0.5, 0.5), Ok(0.25));
/// assert_eq!(check_clamp(0.75, -0.5, 0.5), Err(DecodeError::ValueOutOfRange { place: protocol_runtime::error::Place::NONE }));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn check_clamp<F: Float>(physical: F, lo: F, hi: F) -> Result<F, DecodeError> {
    if within_clamp(physical, lo, hi) {
        Ok(physical)
    } else {
        Err(DecodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })
    }
}

/// A physical value clamped to `lo..=hi`, as a scaled field with a clamp range encodes it
/// (NaN stays NaN, which [`fit`] refuses).
///
/// ```
/// assert_eq!(protocol_runtime::field::clamp(7.0, -1.0, 1.0), 1.0);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn clamp<F: Float>(physical: F, lo: F, hi: F) -> F {
    if physical < lo {
        lo
    } else if physical > hi {
        hi
    } else {
        physical
    }
}

/// The raw value of a physical one, before the cast to the raw type: `(physical - offset) /
/// factor`, rounded by `rounding`. The result's integer part, toward zero, is the raw value
/// ([`fit`] takes it); `core` has no `round` or `trunc`, so rounding to nearest adds a half
/// away from zero and leaves the cut to the cast. Float noise is relative to the quotient and
/// to the offset's share of it (`offset / factor`), the two magnitudes whose rounding it
/// carries.
///
/// ```
/// use protocol_runtime::field::{Rounding, quantize};
/// assert_eq!(quantize(0.26, 0.1, 0.0, Rounding::Nearest) as i64, 3);
/// assert_eq!(quantize(0.26, 0.1, 0.0, Rounding::Truncate) as i64, 2);
/// // 0.3 / 0.1 is 2.9999999999999996: within float noise of 3.
/// assert_eq!(quantize(0.3, 0.1, 0.0, Rounding::Truncate) as i64, 3);
/// ```
#[allow(
    clippy::arithmetic_side_effects,
    reason = "float arithmetic (F is f32 or f64): it neither wraps nor panics"
)]
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn quantize<F: Float>(physical: F, factor: F, offset: F, rounding: Rounding) -> F {
    let q = (physical - offset) / factor;
    let nearest = if q >= F::ZERO {
        q + F::HALF
    } else {
        q - F::HALF
    };
    match rounding {
        Rounding::Nearest => nearest,
        Rounding::Truncate => {
            let nearest = nearest.cut_int();
            let off = (q - nearest).magnitude();
            let magnitude = q.magnitude() + (offset / factor).magnitude();
            if off <= F::NOISE * magnitude.at_least_one() {
                nearest
            } else {
                q
            }
        }
    }
}

/// An integer type a scaled field's raw value has on the wire.
pub trait RawInt: Copy {
    /// The largest `f64` below every value whose integer part fits (exclusive bound).
    const BELOW: f64;
    /// The smallest `f64` above every value whose integer part fits (exclusive bound).
    const ABOVE: f64;
    /// The largest `f32` below every value whose integer part fits (exclusive bound).
    const BELOW_F32: f32;
    /// The smallest `f32` above every value whose integer part fits (exclusive bound).
    const ABOVE_F32: f32;
    /// `x` cut toward zero (an `as` cast); `x` lies strictly between the bounds.
    fn cut(x: f64) -> Self;
    /// `x` cut toward zero (an `as` cast); `x` lies strictly between the `f32` bounds.
    fn cut_f32(x: f32) -> Self;
}

macro_rules! raw_ints {
    ($($t:ty: $below:expr, $above:expr, $below32:expr;)*) => {$(
        impl RawInt for $t {
            const BELOW: f64 = $below;
            const ABOVE: f64 = $above;
            const BELOW_F32: f32 = $below32;
            // Every upper bound is a power of two: the same number in `f32`.
            const ABOVE_F32: f32 = $above;
            #[cfg_attr(not(protocol_opt0), inline(always))]
            fn cut(x: f64) -> Self {
                x as $t
            }
            #[cfg_attr(not(protocol_opt0), inline(always))]
            fn cut_f32(x: f32) -> Self {
                x as $t
            }
        }
    )*};
}

raw_ints! {
    u8: -1.0, 256.0, -1.0;
    u16: -1.0, 65_536.0, -1.0;
    u32: -1.0, 4_294_967_296.0, -1.0;
    u64: -1.0, 18_446_744_073_709_551_616.0, -1.0;
    i8: -129.0, 128.0, -129.0;
    i16: -32_769.0, 32_768.0, -32_769.0;
    // -2^31 - 1 is no f32; the next one below -2^31 is -2^31 - 256.
    i32: -2_147_483_649.0, 2_147_483_648.0, -2_147_483_904.0;
    // -2^63 - 1 is no f64; the next one below -2^63 is -2^63 - 2048 (in f32, -2^63 - 2^40).
    i64: -9_223_372_036_854_777_856.0, 9_223_372_036_854_775_808.0, -9_223_373_136_366_403_584.0;
}

/// The raw integer of a quantized value ([`quantize`]): its integer part, toward zero.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if that integer does not fit `T`, or the value is NaN:
/// a value the field cannot carry is refused, never saturated.
///
/// ```
/// use protocol_runtime::{EncodeError, field::fit};
/// assert_eq!(fit::<u8>(255.9), Ok(255));
/// assert_eq!(fit::<i8>(-128.7), Ok(-128));
/// assert_eq!(fit::<u8>(256.0), Err(EncodeError::ValueOutOfRange { place: protocol_runtime::error::Place::NONE }));
/// assert_eq!(fit::<u16>(f64::NAN), Err(EncodeError::ValueOutOfRange { place: protocol_runtime::error::Place::NONE }));
/// assert_eq!(fit::<i32>(-2_147_483_648.0f32), Ok(i32::MIN));
/// assert_eq!(fit::<i16>(f32::NAN), Err(EncodeError::ValueOutOfRange { place: protocol_runtime::error::Place::NONE }));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn fit<T: RawInt>(x: impl Float) -> Result<T, EncodeError> {
    x.fit()
}
