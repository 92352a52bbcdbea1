//! The float types a scaled field's physical value has (`f32`, `f64`), as one trait, so that
//! the field rules ([`crate::field`]) compute in the precision of the field's Rust type: an
//! `f32` field never touches `f64` (on a Cortex-M4F, `f32` arithmetic is one instruction and
//! `f64` arithmetic is a soft-float library call).

use core::ops::{Add, Div, Mul, Neg, Sub};

use crate::error::EncodeError;
use crate::field::RawInt;

/// `f32` or `f64`: the arithmetic and the constants the field rules need.
pub trait Float:
    Copy
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + sealed::Sealed
{
    /// `0.0`.
    const ZERO: Self;
    /// `0.5`.
    const HALF: Self;
    /// `1.0`.
    const ONE: Self;
    /// The relative distance within which a quotient is taken for the integer it is near
    /// (`Rounding::Truncate`): some rounding errors of this type, well above its epsilon.
    const NOISE: Self;
    /// The relative slack of a clamp range on decoding: a few rounding errors of
    /// `raw * factor + offset` in this type.
    const CLAMP_SLACK: Self;

    /// The value cut toward zero (its integer part), through an integer cast.
    fn cut_int(self) -> Self;

    /// The value's integer part, toward zero, as `T`.
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] if it does not fit `T`, or the value is NaN.
    fn fit<T: RawInt>(self) -> Result<T, EncodeError>;

    /// The absolute value (`core` has no `abs` on floats).
    #[allow(
        clippy::arithmetic_side_effects,
        reason = "float negation: it neither wraps nor panics"
    )]
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn magnitude(self) -> Self {
        if self >= Self::ZERO { self } else { -self }
    }

    /// The larger of the value and `1.0`.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn at_least_one(self) -> Self {
        if self > Self::ONE { self } else { Self::ONE }
    }
}

impl Float for f64 {
    const ZERO: Self = 0.0;
    const HALF: Self = 0.5;
    const ONE: Self = 1.0;
    const NOISE: Self = 1e-6;
    const CLAMP_SLACK: Self = 1e-9;

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn cut_int(self) -> Self {
        self as i64 as f64
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn fit<T: RawInt>(self) -> Result<T, EncodeError> {
        if self > T::BELOW && self < T::ABOVE {
            Ok(T::cut(self))
        } else {
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE,
            })
        }
    }
}

impl Float for f32 {
    const ZERO: Self = 0.0;
    const HALF: Self = 0.5;
    const ONE: Self = 1.0;
    // `f32::EPSILON` is 1.2e-7: a handful of rounding errors stay below these.
    const NOISE: Self = 4e-6;
    const CLAMP_SLACK: Self = 1e-6;

    /// Through an `i32` (an `i64` would link a soft-float conversion on a 32-bit target):
    /// every `f32` of magnitude 2^23 or more is an integer already.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn cut_int(self) -> Self {
        if self.magnitude() >= 8_388_608.0 {
            self
        } else {
            self as i32 as f32
        }
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn fit<T: RawInt>(self) -> Result<T, EncodeError> {
        if self > T::BELOW_F32 && self < T::ABOVE_F32 {
            Ok(T::cut_f32(self))
        } else {
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE,
            })
        }
    }
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}
