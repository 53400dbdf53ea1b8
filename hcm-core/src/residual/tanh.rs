//! tanh as one rational function: the residual's activation, in `f32` on the
//! controller and in `f64` in the host's training, with the same formula.
//!
//! ```text
//! z_c     = clamp(z, −7, 7)                      (NaN → 0: Real::clamp_magnitude_scaled)
//! tanh(z) ≈ z_c·P(z_c²) / Q(z_c²),   P and Q of degree 3 in z²
//! ```
//!
//! The coefficients are a minimax fit of |R − tanh| on [0, 7] (a differential-correction
//! linear programme on 4000 Chebyshev-clustered points, reference tanh to 40 digits),
//! written here in `f64` and rounded to `f32` by [`Real::of`]. Odd by construction, so
//! only z ≥ 0 was fitted; beyond ±7 the value is R(±7), off by the 1.7e-6 that tanh
//! still has to go to ±1 there.
//!
//! Measured maximum error against the platform's `f64` `tanh` (libm) over the whole
//! real line (`tests::error_over_the_whole_real_line`): 9.4e-7 in `f64`, 1.2e-6 in
//! `f32`; its slope differs from tanh's own, 1 − tanh², by at most 1.3e-5
//! (`tests::slope_is_tanh_slope`), which is the slope training back-propagates. That is not a loss of accuracy for the
//! residual: training (`f64`) and inference (`f32`) evaluate this same function, so the
//! network is fitted to it, and the host → blob → core round trip still differs by
//! `f32` rounding only.
//!
//! Why not libm: one `tanhf` costs tens of instructions and a branch per call (an
//! `expm1f` inside), and the 3-16-16-1 residual calls it 32 times: it dominated the
//! HCM's evaluation. Why this degree and this clamp: on a Cortex-M4F (no SIMD, no
//! `vmin`) each coefficient costs two instructions and a compare-and-select clamp
//! eight; degree 3/3 and the two-`vcvt` clamp of [`Real::clamp_magnitude_scaled`] make
//! one activation about 20 instructions, against 38 for the degree-5/4, ±9 version
//! this replaced (1.6e-9 in `f64`, a precision `f32` cannot hold: it erred 3.7e-7
//! there anyway). Only `+ − × ÷`, compares and the saturating conversion (each exactly
//! specified: IEEE 754, Rust's `as`; no fused multiply-add): the result is
//! bit-identical on every target, the Cortex-M4F included.
//!
//! NaN gives 0 (the conversion's rule), ±∞ gives ±R(7): the activation never
//! produces NaN. [`crate::residual::Mlp::evaluate`] returns NaN for a NaN input itself.

use crate::Real;

/// |z| beyond which the approximation holds its value (dimensionless).
const CLAMP: f64 = 7.0;

/// P's coefficients, z⁰ first (in z², dimensionless).
const NUMERATOR: [f64; 4] = [
    0.999_995_691_923_303_1,
    0.123_014_120_912_939_74,
    2.276_351_627_452_438_8e-3,
    3.927_367_297_618_706e-6,
];

/// Q's coefficients, z⁰ first (in z², dimensionless); all positive, so Q ≥ 1.
const DENOMINATOR: [f64; 4] = [
    1.0,
    0.456_332_456_117_331_5,
    2.106_906_473_276_32e-2,
    1.422_856_626_267_319e-4,
];

/// k = c₃/d₃: with z_k = k·z and v = z_k², z·P(z²)/Q(z²) = z_k·P̃(v)/Q̃(v) with P̃ and
/// Q̃ both monic (dimensionless).
const K: f64 = NUMERATOR[3] / DENOMINATOR[3];

/// P̃'s coefficients below the leading 1, v⁰ first: p̃ᵢ = cᵢ·k^(6−2i)/c₃.
const MONIC_NUMERATOR: [f64; 3] = monic(&NUMERATOR);

/// Q̃'s coefficients below the leading 1, v⁰ first: q̃ᵢ = dᵢ·k^(6−2i)/d₃.
const MONIC_DENOMINATOR: [f64; 3] = monic(&DENOMINATOR);

/// The coefficients of c(v/k²)·k⁶/c₃ below its leading 1 (see [`K`]).
const fn monic(c: &[f64; 4]) -> [f64; 3] {
    let k2 = K * K;
    [
        c[0] * k2 * k2 * k2 / c[3],
        c[1] * k2 * k2 / c[3],
        c[2] * k2 / c[3],
    ]
}

/// tanh(z) to within 1.2e-6 in `f64` and `f32`; NaN gives 0, ±∞ gives ±R(7).
///
/// Evaluated as z_k·P̃(v)/Q̃(v) (see `K`): the same rational function as z·P/Q, but
/// with monic polynomials, split as (v + c₂)·v² + (c₁·v + c₀) around the v² both
/// share — four instructions a polynomial on the Cortex-M4F instead of six, and k
/// rides on the clamp's multiply.
#[inline]
pub fn tanh<T: Real>(z: T) -> T {
    let z = z.clamp_magnitude_scaled(T::of(CLAMP), T::of(K));
    let v = z * z;
    let v2 = v * v;
    z * monic_cubic(v, v2, &MONIC_NUMERATOR) / monic_cubic(v, v2, &MONIC_DENOMINATOR)
}

/// c₀ + c₁·v + c₂·v² + v³ as (v + c₂)·v² + (c₁·v + c₀), given v and v².
///
/// Written out rather than folded over the array: at `opt-level = "s"` (the firmware's)
/// LLVM keeps a loop, and each pass then converts an `f64` coefficient to `f32` at
/// run time — a software call on the single-precision Cortex-M4F, which made one
/// residual evaluation cost 14 000 instructions instead of 2 000. Unrolled, every
/// `T::of(constant)` folds to a constant.
#[inline(always)]
fn monic_cubic<T: Real>(v: T, v2: T, c: &[f64; 3]) -> T {
    let [c0, c1, c2] = *c;
    (v + T::of(c2)) * v2 + (T::of(c1) * v + T::of(c0))
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
        // Inside the clamp: 2 million points on [0, 7], and the odd half by symmetry
        // of both functions (checked below).
        let inside = worst((0..=2_000_000).map(|i| 7.0 * f64::from(i) / 2e6));
        // Beyond: out to 1e30 geometrically, and the infinities.
        let beyond = worst(
            (0..=3000)
                .map(|i| 7.0 * 10_f64.powf(f64::from(i) / 100.0))
                .chain([f64::INFINITY]),
        );
        std::println!(
            "tanh error: f64 {:.2e} inside ±7, {:.2e} beyond; f32 {:.2e} / {:.2e}",
            inside.0,
            beyond.0,
            inside.1,
            beyond.1
        );
        assert!(
            inside.0 < 1.7e-6 && beyond.0 < 1.7e-6,
            "{inside:?} {beyond:?}"
        );
        assert!(
            inside.1 < 2.0e-6 && beyond.1 < 2.0e-6,
            "{inside:?} {beyond:?}"
        );
        // Beyond ±7 the value holds at R(±7), within 1.7e-6 below 1.
        for z in [7.5_f32, 1e10, f32::MAX, f32::INFINITY] {
            assert_eq!(tanh(z), tanh(7.0_f32), "{z}");
            assert_eq!(tanh(-z), -tanh(7.0_f32), "{z}");
        }
        assert!((1.0 - tanh(7.0_f32)) < 1.7e-6 && tanh(7.0_f32) < 1.0);
    }

    #[test]
    fn slope_is_tanh_slope() {
        // Central differences in f64 on (0, 7), against 1 − R², the slope training uses.
        let h = 1e-6;
        let worst = (1..7000)
            .map(|i| f64::from(i) * 1e-3)
            .map(|z| {
                let numeric = (tanh(z + h) - tanh(z - h)) / (2.0 * h);
                (1.0 - tanh(z) * tanh(z) - numeric).abs()
            })
            .fold(0.0_f64, f64::max);
        std::println!("slope error {worst:.2e}");
        assert!(worst < 1.3e-5, "{worst}");
    }

    #[test]
    fn odd_monotone_and_bounded_within_the_error_bound() {
        let mut previous = -1.0_f32;
        for i in -12_000..=12_000 {
            let z = i as f32 * 1e-3;
            let value = tanh(z);
            // Exactly odd (compared as values: the clamp turns −0 into +0).
            assert_eq!(value, -tanh(-z), "odd at {z}");
            // Never down by more than the f32 error bound (rounding near saturation).
            assert!(
                value >= previous - 4e-7,
                "monotone at {z}: {value} < {previous}"
            );
            assert!(value.abs() <= 1.0 + f32::EPSILON, "bounded at {z}");
            previous = value;
        }
        // NaN converts to 0 (see the module docs): the activation never makes NaN.
        assert_eq!(tanh(f32::NAN), 0.0);
        assert_eq!(tanh(f64::NAN), 0.0);
    }
}
