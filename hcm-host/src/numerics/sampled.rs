//! Signals sampled at ascending times: a value between the samples, and the output of
//! a first-order low-pass filter. Shared by the generator's sensor (`experiment`) and
//! the diagnosis' sensor model (`diagnose::sensor`), so that both read a signal alike.

/// `v` sampled at ascending times `t`, at time `s`: cubic Hermite between the two
/// neighbouring samples with central-difference slopes (one-sided at the ends); the
/// end value outside.
pub fn hermite(t: &[f64], v: &[f64], s: f64) -> f64 {
    hermite_after(t, v, s, t.partition_point(|&x| x <= s))
}

/// [`hermite`] given `j`, the number of samples at or before `s`.
fn hermite_after(t: &[f64], v: &[f64], s: f64, j: usize) -> f64 {
    let n = t.len();
    if j == 0 {
        return v.first().copied().unwrap_or(0.0);
    }
    if j == n {
        return v[n - 1];
    }
    let (a, b) = (j - 1, j);
    let slope = |i: usize| {
        let (l, r) = (i.saturating_sub(1), (i + 1).min(n - 1));
        if t[r] > t[l] {
            (v[r] - v[l]) / (t[r] - t[l])
        } else {
            0.0
        }
    };
    let h = t[b] - t[a];
    if h <= 0.0 {
        return v[b];
    }
    let x = (s - t[a]) / h;
    let (x2, x3) = (x * x, x * x * x);
    (2.0 * x3 - 3.0 * x2 + 1.0) * v[a]
        + (x3 - 2.0 * x2 + x) * h * slope(a)
        + (-2.0 * x3 + 3.0 * x2) * v[b]
        + (x3 - x2) * h * slope(b)
}

/// `v` sampled at ascending times `t`, read `tau` (s) earlier at each sample: [`hermite`]
/// at t − τ, the first value held before the first sample (a lagging sensor).
pub fn delayed(t: &[f64], v: &[f64], tau: f64) -> Vec<f64> {
    if !t.is_sorted() {
        return t.iter().map(|&ti| hermite(t, v, ti - tau)).collect();
    }
    // Ascending t: the read times t − τ ascend too, so the samples at or before each one
    // are counted on from the last instead of searched for again (the same count as
    // `hermite`'s binary search, so the same values; this runs once per sample and
    // fitted delay in the diagnosis' fits).
    let mut j = 0;
    t.iter()
        .map(|&ti| {
            let s = ti - tau;
            while j < t.len() && t[j] <= s {
                j += 1;
            }
            hermite_after(t, v, s, j)
        })
        .collect()
}

/// `v` sampled at ascending times `t` through a first-order low-pass filter of time
/// constant `tau` (s), at rest on `v[0]` at `t[0]`: exact for `v` linear between the
/// samples, y₊ = v₊ − m·T + (y − v + m·T)·e^(−h/T) with m the slope (v per s). `v` itself
/// for T ≤ 0 (or not finite).
pub fn low_pass(t: &[f64], v: &[f64], tau: f64) -> Vec<f64> {
    if !(tau > 0.0 && tau.is_finite()) || v.is_empty() {
        return v.to_vec();
    }
    let mut y = Vec::with_capacity(v.len());
    y.push(v[0]);
    for k in 1..v.len() {
        let h = t[k] - t[k - 1];
        let previous = y[k - 1];
        y.push(if h > 0.0 {
            let slope = (v[k] - v[k - 1]) / h;
            v[k] - slope * tau + (previous - v[k - 1] + slope * tau) * (-h / tau).exp()
        } else {
            previous
        });
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_is_exact_for_a_quadratic_and_holds_the_ends() {
        let t: Vec<f64> = (0..8).map(|k| 0.5 * k as f64).collect();
        let v: Vec<f64> = t.iter().map(|x| 3.0 * x * x - x + 2.0).collect();
        for s in [0.6, 1.25, 2.0, 2.9] {
            let exact = 3.0 * s * s - s + 2.0;
            assert!((hermite(&t, &v, s) - exact).abs() < 1e-12, "{s}");
        }
        assert_eq!(hermite(&t, &v, -1.0), v[0]);
        assert_eq!(hermite(&t, &v, 9.0), v[7]);
    }

    #[test]
    fn a_delayed_signal_is_hermite_at_each_earlier_time_bit_for_bit() {
        // Repeated times, reads before the first and after the last sample, and an
        // unsorted series (searched for each sample instead).
        let t = [0.0, 0.1, 0.1, 0.25, 0.4, 0.7, 0.7, 1.0];
        let v = [1.0, -2.0, 0.5, 3.0, 2.5, -1.0, 4.0, 0.0];
        let unsorted = [0.3, 0.1, 0.5, 0.2];
        for tau in [0.0, 0.05, 0.1, 0.35, -0.2, 2.0, f64::NAN] {
            for (t, v) in [(&t[..], &v[..]), (&unsorted[..], &v[..4])] {
                let got = delayed(t, v, tau);
                for (k, &ti) in t.iter().enumerate() {
                    let want = hermite(t, v, ti - tau);
                    assert_eq!(got[k].to_bits(), want.to_bits(), "τ = {tau}, sample {k}");
                }
            }
        }
    }

    #[test]
    fn the_filter_follows_a_ramp_one_time_constant_late_and_holds_a_constant() {
        let t: Vec<f64> = (0..200).map(|k| 1e-6 * k as f64).collect();
        let ramp: Vec<f64> = t.iter().map(|x| 1e6 * x).collect();
        let y = low_pass(&t, &ramp, 5e-6);
        // After many time constants the output of a ramp a·t is a·(t − T).
        assert!((y[199] - (ramp[199] - 5.0)).abs() < 1e-6, "{}", y[199]);
        let flat = low_pass(&t, &[3.0; 200], 5e-6);
        assert!(flat.iter().all(|&v| v == 3.0));
        assert_eq!(low_pass(&t, &ramp, 0.0), ramp);
    }
}
