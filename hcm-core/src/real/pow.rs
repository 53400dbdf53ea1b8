//! xʸ in `f32` from `f32` `+ − × ÷`, compares, bit casts and integer operations only:
//! [`Real::pow`](crate::Real::pow) for `f32`, bit-identical on every target.
//!
//! ```text
//! xʸ = 2^t,  t = y·log2 x                              (t kept as th + tl, ~40 bits)
//! x  = 2^e·m,  m ∈ [1, 2),  c = 2^(j/16) nearest m    (16 table entries, hi + lo)
//! log2 x = e + j/16 + (log2 c − j/16) + log2(m/c)
//! log2(m/c) = (2/ln 2)·(s + s³/3 + s⁵/5),  s = (m − c)/(m + c),  |s| ≤ 0.0135
//! 2^t = 2^K · 2^(i/16) · 2^r,  16·th rounded = 16K + i,  |r| ≤ 1/32 (degree-4 2^r − 1)
//! ```
//!
//! The one hard part of a single-precision pow is t: with |log2 x| up to 149 a
//! rounding of y·log2 x in `f32` (2⁻²⁴ relative) is up to 2⁻¹⁷ absolute, 64 ulp of the
//! result. So log2 x is carried as an exact integer-plus-sixteenths part, a hi and a
//! lo (s itself is the quotient plus its remainder's correction), and y·log2 x is
//! formed with Dekker's exact product (Veltkamp's 12-bit split, no fused
//! multiply-add) — a double-`f32` t good to about 2⁻³⁴ relative by analysis. The exponential
//! then adds one rounding (the table's hi plus a small correction), so results are within
//! one ulp of xʸ and almost always correctly rounded.
//!
//! Measured against `f64` `powf` rounded to `f32` (tests below, fixed seed): 10⁷ points
//! with x log-uniform in [1e-12, 1e4] and y uniform in [0.5, 4]: max 1 ulp, 99.21 %
//! correctly rounded; y in [−4, 4]: max 1 ulp, 99.24 %; x within 2^±0.1 of 1 with
//! |y| ≤ 1500, results near overflow and underflow (2^t, t in [−155, 130]) and
//! subnormal x: max 1 ulp (98.9–99.2 %); ∞ and 0 on exactly the inputs where `powf`
//! gives them. The misrounded 0.8 % come from the last roundings of 2^r (|q| ≤ 0.022
//! times 2⁻²⁴, about 0.01 ulp); a 64-entry table would shrink them fourfold for 384 B
//! more flash.
//!
//! Why not libm's `powf`: it computes in `f64`, software on a single-precision FPU
//! (about 250 instructions per call on the Cortex-M4F, most of a contact law's cost),
//! and the host's glibc `powf` rounds some results differently from the controller's
//! `libm` crate, so `f32` laws were not bit-identical host ↔ controller. The special
//! cases (zeros, infinities, NaN, negative x, |y| > 2⁶⁴) follow C99/IEEE 754 `pow`,
//! handled here too, so `libm::powf` is not linked at all.

/// 2^(i/16) rounded to `f32`, i = 0..16 (dimensionless).
const EXP2_HI: [f32; 16] = [
    1.0,
    1.044_273_7,
    1.090_507_7,
    1.138_788_6,
    1.189_207_1,
    1.241_857_8,
    1.296_839_6,
    1.354_255_6,
    core::f32::consts::SQRT_2,
    1.476_826_2,
    1.542_210_8,
    1.610_490_3,
    1.681_792_9,
    1.756_252_2,
    1.834_008_1,
    1.915_206_6,
];

/// 2^(i/16) − [`EXP2_HI`]\[i\] rounded to `f32` (dimensionless): the pair is 2^(i/16)
/// to 48 bits.
const EXP2_LO: [f32; 16] = [
    0.0,
    4.833_47e-8,
    -1.307_754e-8,
    5.386_222_3e-8,
    3.797_635_3e-8,
    4.496_838e-8,
    -4.018_999_5e-8,
    -1.012_335e-8,
    2.420_323_5e-8,
    -4.500_899e-8,
    8.070_905e-9,
    9.836_217e-9,
    -2.475_532_7e-8,
    -9.235_77e-9,
    -1.123_927_8e-8,
    9.845_328e-9,
];

/// 2/ln 2 as hi + lo (dimensionless): log2(m/c) = (2/ln 2)·atanh(s).
const TWO_OVER_LN2: (f32, f32) = (2.885_39, 3.851_926e-8);

/// 1/ln 2 (dimensionless).
const INV_LN2: f32 = core::f32::consts::LOG2_E;

/// Minimax coefficients of 2^r − 1 on |r| ≤ 1/32, r¹ first (dimensionless); error
/// 2.5e-12, far below `f32` rounding.
const EXP2_POLY: [f32; 4] = [
    core::f32::consts::LN_2,
    0.240_226_5,
    0.055_505_74,
    0.009_618_364,
];

/// Quadratic (m − 1)·(a − b·m) ≈ 16·log2 m on [1, 2] (error ≤ 0.13): picks the table
/// entry nearest m in ratio without a table search.
const INDEX_FIT: (f32, f32) = (27.09, 5.545);

/// |y| beyond which xʸ is 1, 0 or ∞ for every `f32` x (the smallest |log2 x| ≠ 0 is
/// 1.7e-7); also keeps Veltkamp's split from overflowing.
const LARGE_EXPONENT: f32 = 18_446_744_073_709_551_616.0; // 2⁶⁴

/// 1.5·2²³: adding it rounds a float below 2²² to an integer held in the low bits.
const ROUNDER: f32 = 12_582_912.0;

/// xʸ with C99 `pow` semantics, within one ulp (see the module documentation).
pub fn powf(x: f32, y: f32) -> f32 {
    if x > 0.0 && x <= f32::MAX && magnitude(y) <= LARGE_EXPONENT {
        positive(x, y)
    } else {
        special(x, y)
    }
}

/// |v| by clearing the sign bit.
#[inline(always)]
fn magnitude(v: f32) -> f32 {
    f32::from_bits(v.to_bits() & 0x7fff_ffff)
}

/// xʸ for finite x > 0 and |y| ≤ 2⁶⁴.
fn positive(x: f32, y: f32) -> f32 {
    let (whole, hi, lo) = log2(x);
    let (th, tl) = times(y, whole, hi, lo);
    exp2(th, tl)
}

/// log2 x for finite x > 0 as `whole + hi + lo`: `whole` = e + j/16 exactly (at most
/// 12 significant bits, |·| ≤ 150), |hi + lo| ≤ 0.04, together good to ~2⁻⁴⁰.
#[inline(always)]
fn log2(x: f32) -> (f32, f32, f32) {
    // A subnormal x is scaled by 2²³ into the normal range first.
    let (bits, bias) = if x < f32::MIN_POSITIVE {
        ((x * 8_388_608.0).to_bits(), 127 + 23)
    } else {
        (x.to_bits(), 127)
    };
    let exponent = (bits >> 23) as i32 - bias;
    let m = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000);
    let j = ((m - 1.0) * (INDEX_FIT.0 - INDEX_FIT.1 * m) + 0.5) as i32; // 0..=16
    let entry = (j & 15) as usize;
    // c = 2^(j/16) rounded; j = 16 gives 2·2⁰ = 2 by the exponent field.
    let c = f32::from_bits(EXP2_HI[entry].to_bits() + (((j >> 4) as u32) << 23));
    let u = m - c; // exact: m/c within 2^±0.04
    let (vh, vl) = (c + m, m - ((c + m) - c)); // m + c exactly (c's exponent ≥ m's)
    let sh = u / vh;
    let (p, pe) = product(sh, vh);
    let sl = (((u - p) - pe) - sh * vl) / vh; // the quotient's remainder, divided
    let (ch, cl) = TWO_OVER_LN2;
    let (lh, le) = product(sh, ch);
    let s2 = sh * sh;
    let series = sh * s2 * (ch / 3.0 + ch / 5.0 * s2);
    // log2 c − j/16 = log2(1 − lo/2^(j/16)): the table entry's own rounding.
    let entry_error = -(EXP2_LO[entry] / EXP2_HI[entry]) * INV_LN2;
    let lo = (series + entry_error) + ((sh * cl + sl * ch) + le);
    let whole = (exponent * 16 + j) as f32 * 0.0625;
    (whole, lh, lo)
}

/// y·(whole + hi + lo) as th + tl: whole has at most 12 significant bits, so the
/// 12-bit halves of y multiply it exactly; y·hi is Dekker's exact product.
#[inline(always)]
fn times(y: f32, whole: f32, hi: f32, lo: f32) -> (f32, f32) {
    let (yh, yl) = split(y);
    let (big, small) = (yh * whole, yl * whole);
    let (hh, hl) = split(hi);
    let p = y * hi;
    let pe = ((yh * hh - p) + yh * hl + yl * hh) + yl * hl;
    // Fast two-sums: |big| ≥ |p| (|whole| ≥ 1/16 > 0.04 ≥ |hi|) or big = 0; then the
    // sum renormalised (small may reach 2⁻¹²·|big|, far above th's ulp).
    let sum = big + p;
    let rest = (p - (sum - big)) + (small + (pe + y * lo));
    let th = sum + rest;
    (th, rest - (th - sum))
}

/// 2^(th + tl) for |tl| ≪ 1/32, rounded once (once more for a subnormal result).
#[inline(always)]
fn exp2(th: f32, tl: f32) -> f32 {
    if th > 128.0 {
        return f32::INFINITY; // 2^t ≥ 2¹²⁸: beyond f32::MAX and its rounding
    }
    if th < -151.0 {
        return 0.0; // 2^t < 2⁻¹⁵⁰: rounds to zero
    }
    let shifted = th * 16.0 + ROUNDER;
    let k = shifted.to_bits() as i32 - ROUNDER.to_bits() as i32; // 16·th rounded
    let r = (th - (shifted - ROUNDER) * 0.0625) + tl; // th − k/16 is exact
    let [e1, e2, e3, e4] = EXP2_POLY;
    let q = r * (e1 + r * (e2 + r * (e3 + r * e4)));
    let entry = (k & 15) as usize;
    let (hi, lo) = (EXP2_HI[entry], EXP2_LO[entry]);
    let mantissa = hi + (hi * q + lo);
    // 2^(k >> 4) in two normal factors: the scale spans 2⁻¹⁵¹…2¹²⁸.
    let scale = k >> 4;
    mantissa * power_of_two(scale >> 1) * power_of_two(scale - (scale >> 1))
}

/// 2ⁿ for −126 ≤ n ≤ 127.
#[inline(always)]
fn power_of_two(n: i32) -> f32 {
    f32::from_bits(((n + 127) as u32) << 23)
}

/// Veltkamp's split: a = hi + lo exactly, each with at most 12 significant bits.
#[inline(always)]
fn split(a: f32) -> (f32, f32) {
    let c = a * 4097.0;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// Dekker's product: a·b = p + e exactly (barring underflow), without fused
/// multiply-add.
#[inline(always)]
fn product(a: f32, b: f32) -> (f32, f32) {
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// Every case outside the fast path, as C99 Annex F `pow` defines it.
#[cold]
fn special(x: f32, y: f32) -> f32 {
    if y == 0.0 || x == 1.0 {
        return 1.0; // even for a NaN other operand
    }
    if x.is_nan() || y.is_nan() {
        return x + y;
    }
    let (ax, ay) = (magnitude(x), magnitude(y));
    // Every f32 of magnitude ≥ 2²⁴ is an even integer.
    let small = ay < 16_777_216.0;
    let integer = !small || (y as i32) as f32 == y;
    let odd = small && integer && (y as i32) & 1 == 1;
    if x < 0.0 && ax != f32::INFINITY && !integer {
        return f32::NAN;
    }
    let grows = (ax > 1.0) == (y > 0.0);
    let result = if ax == 0.0 {
        if y < 0.0 {
            f32::INFINITY
        } else {
            0.0
        }
    } else if ax == 1.0 {
        1.0 // x = −1: y is ±∞ or an even integer here
    } else if ay > LARGE_EXPONENT || ax == f32::INFINITY {
        if grows {
            f32::INFINITY
        } else {
            0.0
        }
    } else {
        positive(ax, y)
    };
    if odd && x.is_sign_negative() {
        -result
    } else {
        result
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::powf;

    /// The reference: `f64` `powf` (glibc here), rounded to `f32`.
    fn reference(x: f32, y: f32) -> f32 {
        (x as f64).powf(y as f64) as f32
    }

    /// Distance in ulps between two non-negative results (∞ is one past f32::MAX).
    fn ulps(a: f32, b: f32) -> u32 {
        a.to_bits().abs_diff(b.to_bits())
    }

    /// xorshift64*: a fixed-seed uniform stream in [0, 1).
    struct Stream(u64);

    impl Stream {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// (largest error in ulps, share correctly rounded) over `count` points.
    fn measure(count: usize, mut point: impl FnMut(&mut Stream) -> (f32, f32)) -> (u32, f64) {
        let mut stream = Stream(0x9e37_79b9_7f4a_7c15);
        let (mut worst, mut exact) = (0, 0usize);
        for _ in 0..count {
            let (x, y) = point(&mut stream);
            let error = ulps(powf(x, y), reference(x, y));
            worst = worst.max(error);
            exact += usize::from(error == 0);
        }
        (worst, exact as f64 / count as f64)
    }

    /// x log-uniform in [1e-12, 1e4] (m), the laws' indentations and ratios.
    fn log_uniform(stream: &mut Stream) -> f32 {
        (10f64).powf(-12.0 + 16.0 * stream.next()) as f32
    }

    #[test]
    fn within_one_ulp_for_the_laws_exponents() {
        let (worst, share) = measure(10_000_000, |s| {
            (log_uniform(s), (0.5 + 3.5 * s.next()) as f32)
        });
        std::println!(
            "y in [0.5, 4]: max {worst} ulp, {:.4} % correctly rounded",
            100.0 * share
        );
        assert!(worst <= 1, "{worst} ulp");
        assert!(share > 0.99, "{share} correctly rounded");
    }

    #[test]
    fn within_one_ulp_for_negative_exponents() {
        let (worst, share) = measure(10_000_000, |s| {
            (log_uniform(s), (-4.0 + 8.0 * s.next()) as f32)
        });
        std::println!(
            "y in [-4, 4]: max {worst} ulp, {:.4} % correctly rounded",
            100.0 * share
        );
        assert!(worst <= 1, "{worst} ulp");
        assert!(share > 0.99, "{share} correctly rounded");
    }

    #[test]
    fn within_one_ulp_near_one_and_at_the_range_ends() {
        // x within 2^±0.1 of 1 with large |y|: t = y·log2 x spans the whole range.
        let near_one = measure(2_000_000, |s| {
            let x = (2f64).powf(0.2 * s.next() - 0.1) as f32;
            (x, (-1500.0 + 3000.0 * s.next()) as f32)
        });
        // Results near overflow and into the subnormals and zero: t in [−155, 130].
        let ends = measure(2_000_000, |s| {
            let x = log_uniform(s);
            let t = if s.next() < 0.5 {
                120.0 + 10.0 * s.next()
            } else {
                -155.0 + 35.0 * s.next()
            };
            (x, (t / (x as f64).log2()) as f32)
        });
        // Subnormal x.
        let subnormal = measure(2_000_000, |s| {
            let x = f32::from_bits(1 + (s.next() * 8_388_607.0) as u32);
            (x, (-0.8 + 1.6 * s.next()) as f32)
        });
        // Overflow and underflow exactly where powf has them: ∞ and 0 on the same inputs.
        let mut stream = Stream(7);
        for _ in 0..2_000_000 {
            let x = log_uniform(&mut stream);
            let t = 100.0 + 60.0 * stream.next();
            for y in [
                (t / (x as f64).log2()) as f32,
                (-t * 1.2 / (x as f64).log2()) as f32,
            ] {
                let (got, want) = (powf(x, y), reference(x, y));
                assert_eq!(
                    got == f32::INFINITY,
                    want == f32::INFINITY,
                    "pow({x:e}, {y:e}): {got:e} vs {want:e}"
                );
                assert_eq!(
                    got == 0.0,
                    want == 0.0,
                    "pow({x:e}, {y:e}): {got:e} vs {want:e}"
                );
            }
        }
        for (name, (worst, share)) in [
            ("near 1", near_one),
            ("range ends", ends),
            ("subnormal x", subnormal),
        ] {
            std::println!(
                "{name}: max {worst} ulp, {:.4} % correctly rounded",
                100.0 * share
            );
            assert!(worst <= 1, "{name}: {worst} ulp");
        }
    }

    #[test]
    fn special_cases_follow_c99_pow() {
        let values = [
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            0.5,
            -0.5,
            2.0,
            -2.0,
            3.0,
            -3.0,
            2.5,
            -2.5,
            1e-40,
            -1e-40,
            f32::MAX,
            -f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            16_777_217.0,
            -16_777_215.0,
            1e20,
            -1e20,
            1.000_000_1,
            0.999_999_9,
            7.0,
            -7.0,
        ];
        for &x in &values {
            for &y in &values {
                let (got, want) = (powf(x, y), reference(x, y));
                let same = got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan());
                let close = got.is_finite()
                    && want.is_finite()
                    && got.signum() == want.signum()
                    && ulps(got.abs(), want.abs()) <= 1;
                assert!(
                    same || close,
                    "pow({x:e}, {y:e}) = {got:e}, powf gives {want:e}"
                );
            }
        }
    }

    #[test]
    fn monotonic_in_x_for_fixed_y() {
        for y in [0.5f32, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, -1.0, -2.5] {
            let mut x = 1e-12f32;
            let mut last = powf(x, y);
            while x < 1e4 {
                x = f32::from_bits(x.to_bits() + 997); // ~1.2e-4 relative steps
                let now = powf(x, y);
                let ordered = if y > 0.0 { now >= last } else { now <= last };
                assert!(ordered, "pow({x:e}, {y}) = {now:e} after {last:e}");
                last = now;
            }
        }
    }
}
