//! The float type the laws are generic over.

use nalgebra::RealField;

// Compiled on the host too, where its tests run against `f64`.
#[cfg_attr(not(target_os = "none"), allow(dead_code))]
mod pow;

/// A float type a contact law can be evaluated in: `f32` (controller) or `f64`
/// (host simulation).
///
/// It is `nalgebra`'s [`RealField`] (so vectors, `sqrt`, `powf` work the same for
/// both) plus the two things the laws need that `RealField` lacks: literal
/// constants and a saturation bound.
pub trait Real: RealField + Copy {
    /// Largest finite value; law outputs saturate here instead of overflowing.
    const MAX: Self;

    /// Converts an `f64` literal (rounding to nearest for `f32`).
    fn of(value: f64) -> Self;

    /// A count (a number of components, a loop index) as a float; exact below 2²⁴
    /// (`f32`) and 2⁵³ (`f64`). Direct, so a controller without double-precision
    /// hardware does not convert through `f64` in software.
    fn of_count(count: usize) -> Self;

    /// `self` raised to `exponent`, C99 `pow` semantics. On a bare-metal controller
    /// (`target_os = "none"`) `f32` uses the core's own pow (`real/pow.rs`: `f32`
    /// `+ − × ÷` and bit operations only, within one ulp; the `libm` crate's `powf`
    /// computes in software `f64` on a single-precision FPU, 60 instructions more per
    /// call on the Cortex-M4F). Everywhere else, and for `f64`, nalgebra's `powf`, i.e.
    /// the platform's (glibc), which is faster on the host (x86-64: 5 ns against about
    /// 30 ns per call). Each rounds within an ulp, so the two may differ by an ulp or
    /// two — the one reason a law's f32 result on the host can differ from the
    /// controller's (tests/controller/firmware.rs lists each such value).
    fn pow(self, exponent: Self) -> Self;

    /// √self, correctly rounded (IEEE 754 `squareRoot`; unit: the square root of
    /// `self`'s); x < 0 gives NaN. Use it, not nalgebra's `sqrt` or `norm` (write
    /// `v.norm_squared().square_root()`): for `f32` it is
    /// [`hcm_dsp::sqrt_f32`], one `vsqrt.f32` on the Cortex-M4F firmware where
    /// nalgebra's `sqrt` there is the `libm` crate's software `sqrtf` (480 B of flash
    /// with its table; measured: peg images −472 B of flash, −518 instructions per peg
    /// HCM (18,390 → 17,872), ball image −476 B).
    /// Both round correctly, so the results are the same bits on every target but
    /// for NaN's sign and payload ([`hcm_dsp::sqrt_f32`] lists them). `f64`:
    /// nalgebra's `sqrt` (the platform's).
    fn square_root(self) -> Self;

    /// Widens (or, from `f64`, keeps) the value as an `f64`.
    fn to_f64(self) -> f64;

    /// An `f32` (a stored weight or scale) as `Self`, exactly. Direct, so a controller
    /// without double-precision hardware does not convert through `f64` in software.
    fn of_f32(value: f32) -> Self;

    /// `self` rounded to `f32` (nearest); direct, for the same reason.
    fn to_f32(self) -> f32;

    /// `self` clamped to [−limit, limit] (limit > 0, same unit as `self`), times
    /// `scale` (the scale's unit); NaN gives 0.
    ///
    /// `f32` scales to 2³¹/limit and back through Rust's saturating `as i32`: two
    /// `vcvt` and two multiplies on a Cortex-M4F, whose FPU has no `vmin`/`vmax` (a
    /// compare-and-select clamp takes eight instructions and two branches); `scale`
    /// rides on the multiply back, for free. It rounds |self| < 2²⁴·limit/2³¹ down to a
    /// multiple of limit/2³¹ (3.3e-9 for limit 7), below `f32` resolution elsewhere.
    /// `f64` (the host) compares, then multiplies.
    fn clamp_magnitude_scaled(self, limit: Self, scale: Self) -> Self;

    /// Converts between float types: `f64` → `f32` rounds to nearest.
    #[inline]
    fn cast<U: Real>(self) -> U {
        U::of(self.to_f64())
    }

    /// Clamps ±∞ to ±[`Real::MAX`]; NaN passes through unchanged.
    #[inline]
    fn saturate(self) -> Self {
        if self > Self::MAX {
            Self::MAX
        } else if self < -Self::MAX {
            -Self::MAX
        } else {
            self
        }
    }

    /// True for NaN.
    #[inline]
    #[allow(clippy::eq_op)]
    fn is_nan(self) -> bool {
        self != self
    }

    /// `self` if it is finite and strictly positive, otherwise `None`.
    #[inline]
    fn positive(self) -> Option<Self> {
        if self > Self::zero() && self < Self::MAX {
            Some(self)
        } else {
            None
        }
    }
}

impl Real for f32 {
    const MAX: Self = f32::MAX;

    #[inline]
    fn of(value: f64) -> Self {
        value as f32
    }

    #[inline]
    fn pow(self, exponent: Self) -> Self {
        #[cfg(target_os = "none")]
        let power = pow::powf(self, exponent);
        #[cfg(not(target_os = "none"))]
        let power = nalgebra::ComplexField::powf(self, exponent);
        power
    }

    #[inline]
    fn square_root(self) -> Self {
        hcm_dsp::sqrt_f32(self)
    }

    #[inline]
    fn of_count(count: usize) -> Self {
        count as f32
    }

    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }

    #[inline]
    fn of_f32(value: f32) -> Self {
        value
    }

    #[inline]
    fn to_f32(self) -> f32 {
        self
    }

    #[inline]
    fn clamp_magnitude_scaled(self, limit: Self, scale: Self) -> Self {
        const RANGE: f32 = 2_147_483_648.0;
        (self * (RANGE / limit)) as i32 as f32 * (limit * scale / RANGE)
    }
}

impl Real for f64 {
    const MAX: Self = f64::MAX;

    #[inline]
    fn of(value: f64) -> Self {
        value
    }

    #[inline]
    fn pow(self, exponent: Self) -> Self {
        nalgebra::ComplexField::powf(self, exponent)
    }

    #[inline]
    fn square_root(self) -> Self {
        nalgebra::ComplexField::sqrt(self)
    }

    #[inline]
    fn of_count(count: usize) -> Self {
        count as f64
    }

    #[inline]
    fn to_f64(self) -> f64 {
        self
    }

    #[inline]
    fn of_f32(value: f32) -> Self {
        f64::from(value)
    }

    #[inline]
    fn to_f32(self) -> f32 {
        self as f32
    }

    #[inline]
    fn clamp_magnitude_scaled(self, limit: Self, scale: Self) -> Self {
        if self.is_nan() {
            0.0
        } else {
            self.clamp(-limit, limit) * scale
        }
    }
}
