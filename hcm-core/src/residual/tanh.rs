//! tanh as one rational function: the residual's activation, in `f32` on the
//! controller and in `f64` in the host's training, with the same formula.
//!
//! ```text
//! z_c     = clamp(z, −9, 9)                       (NaN passes through)
//! tanh(z) ≈ z_c·P(z_c²) / Q(z_c²),   P of degree 5, Q of degree 4 in z²
//! ```
//!
//! The coefficients are a minimax fit of |R − tanh| on [0, 9] (a differential-correction
//! linear programme on 6000 Chebyshev-clustered points, reference tanh to 40 digits),
//! written here in `f64` and rounded to `f32` by [`Real::of`]. Odd by construction, so
//! only z ≥ 0 was fitted. Beyond ±9 the value is R(±9) = ±(1 − 3.2e-8): off by at most
//! 3.2e-8 (`f32` rounds it to 1 − 6e-8).
//!
//! Measured maximum error against the platform's `f64` `tanh` (libm) over the whole
//! real line (`tests::error_over_the_whole_real_line`): 1.6e-9 for |z| ≤ 9 and 3.2e-8
//! beyond, in `f64`; 3.7e-7 (3 `f32` ulps of 1) in `f32`, where the rounding of the
//! coefficients and of each multiply-add, not the fit, is the limit (libm's own
//! `tanhf` is within about one ulp, 1.2e-7). That rounding also makes the `f32`
//! values non-decreasing only to within that bound where they reach ±1, and lets them
//! exceed ±1 by one ulp.
//!
//! Why not libm: one `tanhf` costs tens of instructions and a branch per call (an
//! `expm1f` inside), and the 3-16-16-1 residual calls it 32 times: it dominated the
//! HCM's evaluation. This is 2 compares, 11 multiply-adds and one division, with no
//! branch, so the compiler evaluates four or eight neurons at once in SIMD registers.
//! Only `+ − × ÷` (each correctly rounded by IEEE 754, no fused multiply-add): the
//! result is bit-identical on every target, the Cortex-M4F included.

use crate::Real;

/// |z| beyond which the approximation holds its value (dimensionless).
const CLAMP: f64 = 9.0;

/// P's coefficients, z⁰ first (in z², dimensionless).
const NUMERATOR: [f64; 6] = [
    0.999_999_995_763_990_1,
    0.136_834_550_775_560_5,
    3.872_786_631_720_800_3e-3,
    2.809_851_158_290_997e-5,
    3.080_682_366_352_214e-8,
    -1.236_903_905_626_757e-11,
];

/// Q's coefficients, z⁰ first (in z², dimensionless); all positive, so Q ≥ 1.
const DENOMINATOR: [f64; 5] = [
    1.0,
    0.470_167_864_938_513_04,
    2.726_210_004_097_58e-2,
    3.946_534_925_041_366_7e-4,
    1.293_772_169_667_729_4e-6,
];

/// tanh(z) to within 3.2e-8 in `f64` and 3.7e-7 in `f32`; NaN stays NaN, ±∞ gives ±R(9).
#[inline]
pub fn tanh<T: Real>(z: T) -> T {
    let limit = T::of(CLAMP);
    // Compares, not `max`/`min`: they are false for NaN, which then passes through
    // (`f32::min(NaN, 9)` would be 9). No clamp of the result to [−1, 1]: in `f32` it
    // may exceed 1 by one ulp, harmless to the network, and the four compares it
    // would take cost a third of the function on a Cortex-M4F.
    let z = if z > limit {
        limit
    } else if z < -limit {
        -limit
    } else {
        z
    };
    let square = z * z;
    z * horner(square, &NUMERATOR) / horner(square, &DENOMINATOR)
}

/// c₀ + c₁·x + c₂·x² + …, by Horner's rule, unrolled by hand.
///
/// Written out rather than folded over the array: at `opt-level = "s"` (the firmware's)
/// LLVM keeps a loop, and each pass then converts an `f64` coefficient to `f32` at
/// run time — a software call on the single-precision Cortex-M4F, which made one
/// residual evaluation cost 14 000 instructions instead of 2 000. Unrolled, every
/// `T::of(constant)` folds to a constant.
#[inline(always)]
fn horner<T: Real, const N: usize>(x: T, c: &[f64; N]) -> T {
    let term = |i: usize| c.get(i).map_or(T::zero(), |&value| T::of(value));
    // Degree ≤ 5: the two polynomials above have 6 and 5 coefficients.
    const _: () = assert!(NUMERATOR.len() <= 6 && DENOMINATOR.len() <= 6);
    ((((term(5) * x + term(4)) * x + term(3)) * x + term(2)) * x + term(1)) * x + term(0)
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::tanh;

    /// The largest |approximation − libm tanh| over `points` in f64 and in f32 (the
    /// f32 result against the f64 libm value of the f32 input).
    fn worst(points: impl Iterator<Item = f64>) -> (f64, f64) {
        points.fold((0.0_f64, 0.0_f64), |(wide, narrow), z| {
            let single = z as f32;
            let reference = f64::from(single).tanh();
            (
                wide.max((tanh(z) - z.tanh()).abs()),
                narrow.max((f64::from(tanh(single)) - reference).abs()),
            )
        })
    }

    #[test]
    fn error_over_the_whole_real_line() {
        // Inside the clamp: 2 million points on [0, 9], and the odd half by symmetry
        // of both functions (checked below).
        let inside = worst((0..=2_000_000).map(|i| 9.0 * f64::from(i) / 2e6));
        // Beyond: out to 1e30 geometrically, and the infinities.
        let beyond = worst(
            (0..=3000)
                .map(|i| 9.0 * 10_f64.powf(f64::from(i) / 100.0))
                .chain([f64::INFINITY]),
        );
        std::println!(
            "tanh error: f64 {:.2e} inside ±9, {:.2e} beyond; f32 {:.2e} / {:.2e}",
            inside.0,
            beyond.0,
            inside.1,
            beyond.1
        );
        assert!(inside.0 < 1.7e-9, "{inside:?}");
        assert!(beyond.0 < 3.3e-8, "{beyond:?}");
        assert!(
            inside.1 < 4.0e-7 && beyond.1 < 4.0e-7,
            "{inside:?} {beyond:?}"
        );
        // f32 saturates at R(±9), one ulp inside ±1.
        assert_eq!(tanh(9.5_f32), 1.0 - f32::EPSILON / 2.0);
        assert_eq!(tanh(f32::NEG_INFINITY), -(1.0 - f32::EPSILON / 2.0));
    }

    #[test]
    fn odd_monotone_and_bounded_within_the_error_bound() {
        let mut previous = -1.0_f32;
        for i in -12_000..=12_000 {
            let z = i as f32 * 1e-3;
            let value = tanh(z);
            assert_eq!(value.to_bits(), (-tanh(-z)).to_bits(), "odd at {z}");
            // Never down by more than the f32 error bound (rounding near saturation).
            assert!(
                value >= previous - 4e-7,
                "monotone at {z}: {value} < {previous}"
            );
            assert!(value.abs() <= 1.0 + f32::EPSILON, "bounded at {z}");
            previous = value;
        }
        assert!(tanh(f32::NAN).is_nan() && tanh(f64::NAN).is_nan());
    }
}
