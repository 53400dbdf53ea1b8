//! What a model gets wrong: the residual r = measured − model (N) split by contact phase
//! and binned against the motion, and a test of whether it holds more than noise.
//!
//! A model that lacks nothing leaves white noise of the size of the noise floor σ (N,
//! [`super::noise`]): the same RMS in loading and unloading, bin means within σ/√n of
//! zero. A missing effect leaves a pattern, and the pattern names the effect: a residual
//! that follows the indentation rate δ̇ is missing damping, one that follows
//! δ/δ_peak differently in loading and unloading is missing hysteresis, a nonzero mean
//! in flight is a sensor offset.
//!
//! **Structure test.** Under pure noise of standard deviation σ, the mean of the n_b
//! residuals in bin b is N(0, σ²/n_b), so χ² = Σ_b n_b·mean_b²/σ² over the B non-empty
//! bins of time since touch-down is χ²-distributed with B degrees of freedom: mean B,
//! standard deviation √(2B). The residual is called structured when χ² exceeds
//! B + 5·√(2B), about five standard deviations above what noise gives — a threshold
//! that pure noise crosses by chance far less often than once in a thousand records,
//! and that leaves room for σ being an estimate. Where the runs scatter beyond the
//! sample noise (the contact differs a little from run to run), a bin mean's variance
//! is the runs' own spread instead of σ²/n_b (`bin_null_variances`): run-to-run
//! scatter is the data's variability, not structure.

use super::ContactSamples;
use crate::figure::{Band, Colour, Figure, Series};

/// Bins against δ/δ_peak, loading and unloading each.
const DEPTH_BINS: usize = 10;
/// Bins against δ̇/δ̇0.
const RATE_BINS: usize = 10;
/// Bins against time since touch-down / contact duration.
const PHASE_BINS: usize = 20;
/// Standard deviations of χ² above its degrees of freedom that make a residual structured.
const STRUCTURE_SIGMAS: f64 = 5.0;

/// The residuals whose abscissa falls in one bin.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Bin {
    /// Middle of the bin, in the abscissa's units (–).
    pub(crate) centre: f64,
    /// Mean residual measured − model in the bin (N); NaN for an empty bin.
    pub(crate) mean: f64,
    /// Number of samples in the bin.
    pub(crate) count: usize,
}

/// Where and how much a model's force departs from the measured force.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Structure {
    /// Noise floor σ the residual is compared with (N).
    pub(crate) sigma: f64,
    /// Number of samples in contact.
    pub(crate) contact_samples: usize,
    /// RMS of the residual in contact (N); NaN without contact samples (as every RMS or
    /// mean below of an empty set).
    pub(crate) contact_rms: f64,
    /// RMS of the residual in contact while loading, δ̇ > 0 (N).
    pub(crate) loading_rms: f64,
    /// RMS of the residual in contact while unloading, δ̇ < 0 (N).
    pub(crate) unloading_rms: f64,
    /// Number of samples outside contact.
    pub(crate) flight_samples: usize,
    /// Mean residual outside contact (N): the sensor's offset, as every model gives 0 there.
    pub(crate) flight_mean: f64,
    /// RMS of the residual outside contact (N): ≈ σ for a sensor without offset.
    pub(crate) flight_rms: f64,
    /// Part of the contact RMS the noise does not explain, √max(RMS² − σ², 0) (N).
    pub(crate) excess_rms: f64,
    /// Mean residual against δ/δ_peak while loading (δ_peak the event's deepest δ).
    pub(crate) by_depth_loading: Vec<Bin>,
    /// Mean residual against δ/δ_peak while unloading.
    pub(crate) by_depth_unloading: Vec<Bin>,
    /// Mean residual against δ̇/δ̇0 (δ̇0 the event's approach speed), over the range the
    /// data cover.
    pub(crate) by_rate: Vec<Bin>,
    /// Mean residual against time since touch-down / contact duration.
    pub(crate) by_phase: Vec<Bin>,
    /// χ² = Σ n_b·mean_b²/σ² over the non-empty bins of `by_phase` (–).
    pub(crate) chi_squared: f64,
    /// Degrees of freedom of `chi_squared`: the number of non-empty bins of `by_phase`.
    pub(crate) dof: usize,
    /// dof + 5·√(2·dof): χ² above this is about 5 standard deviations beyond pure noise (–).
    pub(crate) threshold: f64,
    /// Whether χ² exceeds `threshold`: the residual holds more than noise.
    pub(crate) structured: bool,
    /// Whether the runs scatter beyond the sample noise (their own spread is the null of
    /// the χ² test, see `bin_null_variances`): their residuals then move together, and
    /// only the runs, not the samples, are independent evidence.
    pub scattered: bool,
}

/// The residual `samples.measured − model_force` (N) summarised against the noise floor
/// `sigma` (N, > 0; otherwise χ² is not finite and nothing is called structured).
/// `model_force` holds one force per sample (N), e.g. from
/// [`ContactSamples::model_force`]; the samples of a run are in time order.
///
/// # Panics
/// If `model_force` and `samples` differ in length.
pub fn residual_structure(samples: &ContactSamples, model_force: &[f64], sigma: f64) -> Structure {
    assert_eq!(
        model_force.len(),
        samples.len(),
        "one model force per sample"
    );
    let residual: Vec<f64> = samples
        .measured
        .iter()
        .zip(model_force)
        .map(|(m, f)| m - f)
        .collect();
    let (depth_fraction, phase) = event_coordinates(samples);
    let contact = |i: &usize| samples.in_contact[*i];
    let all = 0..samples.len();
    let moments = |keep: &dyn Fn(usize) -> bool| {
        Moments::of(all.clone().filter(|&i| keep(i)).map(|i| residual[i]))
    };
    let in_contact = moments(&|i| contact(&i));
    let loading = moments(&|i| contact(&i) && samples.rate[i] > 0.0);
    let unloading = moments(&|i| contact(&i) && samples.rate[i] < 0.0);
    let flight = moments(&|i| !contact(&i));

    let rate_fraction: Vec<f64> = all
        .clone()
        .map(|i| samples.rate[i] / samples.approach_speed[i])
        .collect();
    let depth_points = |sign: f64| {
        all.clone()
            .filter(move |&i| contact(&i) && samples.rate[i] * sign > 0.0)
            .map(|i| (depth_fraction[i], residual[i]))
    };
    let in_contact_points = |x: &[f64]| {
        all.clone()
            .filter(contact)
            .map(|i| (x[i], residual[i]))
            .collect::<Vec<_>>()
    };
    let rate_points = in_contact_points(&rate_fraction);
    let rate_range = finite_range(rate_points.iter().map(|p| p.0)).unwrap_or((-1.0, 1.0));
    let by_phase = bin_means(in_contact_points(&phase), (0.0, 1.0), PHASE_BINS);

    let dof = by_phase.iter().filter(|b| b.count > 0).count();
    let (null, scattered) = bin_null_variances(samples, &residual, &phase, sigma);
    let chi_squared = (by_phase.iter().zip(&null))
        .filter(|(b, _)| b.count > 0)
        .map(|(b, v)| b.mean * b.mean / v)
        .sum::<f64>();
    let threshold = dof as f64 + STRUCTURE_SIGMAS * (2.0 * dof as f64).sqrt();
    let contact_rms = in_contact.rms();
    Structure {
        sigma,
        contact_samples: in_contact.count,
        contact_rms,
        loading_rms: loading.rms(),
        unloading_rms: unloading.rms(),
        flight_samples: flight.count,
        flight_mean: flight.mean(),
        flight_rms: flight.rms(),
        excess_rms: (contact_rms * contact_rms - sigma * sigma).max(0.0).sqrt(),
        by_depth_loading: bin_means(depth_points(1.0), (0.0, 1.0), DEPTH_BINS),
        by_depth_unloading: bin_means(depth_points(-1.0), (0.0, 1.0), DEPTH_BINS),
        by_rate: bin_means(rate_points, rate_range, RATE_BINS),
        by_phase,
        chi_squared,
        dof,
        threshold,
        structured: dof > 0 && chi_squared > threshold,
        scattered,
    }
}

/// Per sample, δ/δ_peak and (t − t_touch-down)/duration within its contact event (both
/// –, NaN outside contact). An event is a stretch of consecutive in-contact samples of
/// one run; δ_peak is its deepest δ and its duration runs from its first to its last
/// sample. The samples' own `max_depth` is the deepest δ *so far*, which equals δ all
/// through loading, so it cannot place a loading sample along the event.
fn event_coordinates(samples: &ContactSamples) -> (Vec<f64>, Vec<f64>) {
    let n = samples.len();
    let (mut depth_fraction, mut phase) = (vec![f64::NAN; n], vec![f64::NAN; n]);
    for event in samples.events() {
        let peak = samples.depth[event.clone()]
            .iter()
            .fold(f64::NEG_INFINITY, |a, &b| a.max(b));
        let (t0, t1) = (samples.time[event.start], samples.time[event.end - 1]);
        for i in event {
            depth_fraction[i] = samples.depth[i] / peak;
            phase[i] = (samples.time[i] - t0) / (t1 - t0);
        }
    }
    (depth_fraction, phase)
}

/// Count, sum and sum of squares of some residuals.
#[derive(Clone, Copy, Default)]
struct Moments {
    count: usize,
    sum: f64,
    squares: f64,
}

impl Moments {
    fn of(values: impl Iterator<Item = f64>) -> Moments {
        values.fold(Moments::default(), |m, v| Moments {
            count: m.count + 1,
            sum: m.sum + v,
            squares: m.squares + v * v,
        })
    }

    /// Mean (N); NaN when empty.
    fn mean(&self) -> f64 {
        self.sum / self.count as f64
    }

    /// Root mean square (N); NaN when empty.
    fn rms(&self) -> f64 {
        (self.squares / self.count as f64).sqrt()
    }
}

/// Smallest and largest finite value, if any.
fn finite_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .filter(|x| x.is_finite())
        .fold(None, |range, x| match range {
            None => Some((x, x)),
            Some((lo, hi)) => Some((x.min(lo), x.max(hi))),
        })
}

/// Mean of the residuals of `points` (abscissa, residual N) in `bins` equal bins
/// spanning `range`; abscissae outside it count in the nearest end bin, non-finite
/// ones nowhere.
fn bin_means(
    points: impl IntoIterator<Item = (f64, f64)>,
    range: (f64, f64),
    bins: usize,
) -> Vec<Bin> {
    let (lo, width) = bin_width(range, bins);
    let mut sums = vec![Moments::default(); bins];
    for (x, r) in points.into_iter().filter(|(x, _)| x.is_finite()) {
        let b = bin_of(x, range, bins);
        sums[b] = Moments {
            count: sums[b].count + 1,
            sum: sums[b].sum + r,
            squares: sums[b].squares + r * r,
        };
    }
    sums.iter()
        .enumerate()
        .map(|(b, m)| Bin {
            centre: lo + (b as f64 + 0.5) * width,
            mean: m.mean(),
            count: m.count,
        })
        .collect()
}

/// The start and width of `bins` equal bins over `range` (width 1 for an empty range).
fn bin_width((lo, hi): (f64, f64), bins: usize) -> (f64, f64) {
    (
        lo,
        if hi > lo {
            (hi - lo) / bins as f64
        } else {
            1.0
        },
    )
}

/// The bin of the finite abscissa `x` (values beyond either end in the end bins).
fn bin_of(x: f64, range: (f64, f64), bins: usize) -> usize {
    let (lo, width) = bin_width(range, bins);
    (((x - lo) / width).floor().max(0.0) as usize).min(bins - 1)
}

/// Runs below which the run-to-run spread of a bin is not estimated (–).
const MIN_RUNS_FOR_SCATTER: usize = 5;

/// The variance (N²) a phase bin's mean residual has when the model lacks nothing:
/// the sample noise's σ²/n_b, or — when the runs scatter beyond it — the spread of the
/// runs' own bin means (runs as the independent units: Σ_r (s_rb − n_rb·m_b)² / n_b²
/// · R/(R − 1), s_rb and n_rb run r's sum and count in bin b, m_b the pooled mean),
/// wherever that is larger. The contact of each run differs a little (`hcm
/// generate`'s parameter scatter, a real rig's run-to-run variation), and with a quiet
/// sensor that difference alone made every residual "structured" and refused every
/// cause. Scatter counts as present only when the runs' spread, summed over the bins,
/// exceeds the noise's by [`STRUCTURE_SIGMAS`] of its own sampling spread
/// (√(2/((R − 1)·B)) relative): without scatter the test is the sample-noise one,
/// unchanged. Nor where the motion was reconstructed: there the runs' spread is the
/// reconstruction's error, already in σ. Also returns whether the runs scatter.
fn bin_null_variances(
    samples: &ContactSamples,
    residual: &[f64],
    phase: &[f64],
    sigma: f64,
) -> (Vec<f64>, bool) {
    let noise = sigma * sigma;
    // Per bin: (count, sum) per run, in the order runs appear.
    let mut per_run: Vec<Vec<(usize, usize, f64)>> = vec![Vec::new(); PHASE_BINS];
    for i in (0..samples.len()).filter(|&i| samples.in_contact[i] && phase[i].is_finite()) {
        let b = bin_of(phase[i], (0.0, 1.0), PHASE_BINS);
        let run = samples.run[i];
        match per_run[b].iter_mut().find(|(r, _, _)| *r == run) {
            Some(slot) => (slot.1, slot.2) = (slot.1 + 1, slot.2 + residual[i]),
            None => per_run[b].push((run, 1, residual[i])),
        }
    }
    let spread: Vec<Option<(f64, f64)>> = (per_run.iter())
        .map(|runs| {
            let r = runs.len();
            let n: usize = runs.iter().map(|x| x.1).sum();
            if r < MIN_RUNS_FOR_SCATTER || n == 0 {
                return None;
            }
            let mean = runs.iter().map(|x| x.2).sum::<f64>() / n as f64;
            let squares: f64 = runs.iter().map(|x| (x.2 - x.1 as f64 * mean).powi(2)).sum();
            let between = squares / (n * n) as f64 * r as f64 / (r - 1) as f64;
            Some((between, noise / n as f64))
        })
        .collect();
    // Motion reconstructed from camera frames carries its own per-contact error
    // (`depth_sd`, `rate_sd`, in the σ the caller passes): its runs' spread is that
    // error, not the contact's scatter, and is not counted twice.
    let reconstructed =
        (0..samples.len()).any(|i| samples.in_contact[i] && samples.reconstructed(i));
    let judged: Vec<(f64, f64)> = if reconstructed {
        Vec::new()
    } else {
        spread.iter().flatten().copied().collect()
    };
    let runs = samples
        .run
        .iter()
        .collect::<std::collections::BTreeSet<_>>()
        .len();
    let ratio = judged.iter().map(|(b, n)| b / n).sum::<f64>() / judged.len().max(1) as f64;
    let sampling = (2.0 / ((runs.max(2) - 1) as f64 * judged.len().max(1) as f64)).sqrt();
    let scattered = !judged.is_empty() && ratio > 1.0 + STRUCTURE_SIGMAS * sampling;
    let null = (per_run.iter().zip(&spread))
        .map(|(runs, s)| {
            let n: usize = runs.iter().map(|x| x.1).sum();
            let plain = noise / n.max(1) as f64;
            match s {
                Some((between, _)) if scattered => between.max(plain),
                _ => plain,
            }
        })
        .collect();
    (null, scattered)
}

/// Colour of the "before" model's curves.
const BEFORE: Colour = Colour::hex(0xd62728);
/// Colour of the "after" model's curves.
const AFTER: Colour = Colour::hex(0x1f77b4);

/// The mean residual of `before` — and of `after`, if given — against time since
/// touch-down, δ/δ_peak while loading, δ/δ_peak while unloading and δ̇/δ̇0, each as
/// (file stem, figure); `labels` names the two models in the legends (e.g. the base and
/// the extended model). Empty bins are left out of the curves. Each figure has the zero
/// line and, shaded, the ±2σ/√n within which a bin's mean of n samples is noise.
pub fn structure_figures<'a>(
    before: &Structure,
    after: Option<&Structure>,
    labels: (&'a str, &'a str),
) -> Vec<(&'static str, Figure<'a>)> {
    type View = (
        &'static str,
        &'static str,
        &'static str,
        fn(&Structure) -> &[Bin],
    );
    let views: [View; 4] = [
        (
            "residual_vs_time",
            "Mean residual over the contact",
            "time since touch-down / contact duration (–)",
            |s| &s.by_phase,
        ),
        (
            "residual_vs_depth_loading",
            "Mean residual while loading",
            "indentation δ / peak indentation (–)",
            |s| &s.by_depth_loading,
        ),
        (
            "residual_vs_depth_unloading",
            "Mean residual while unloading",
            "indentation δ / peak indentation (–)",
            |s| &s.by_depth_unloading,
        ),
        (
            "residual_vs_rate",
            "Mean residual against the indentation rate",
            "indentation rate δ̇ / approach speed δ̇₀ (–)",
            |s| &s.by_rate,
        ),
    ];
    let curve = |bins: &[Bin]| -> Vec<(f64, f64)> {
        bins.iter()
            .filter(|b| b.count > 0)
            .map(|b| (b.centre, b.mean))
            .collect()
    };
    views
        .into_iter()
        .map(|(stem, title, x_label, bins)| {
            let mut series = vec![Series {
                label: labels.0,
                colour: BEFORE,
                points: curve(bins(before)),
            }];
            if let Some(after) = after {
                series.push(Series {
                    label: labels.1,
                    colour: AFTER,
                    points: curve(bins(after)),
                });
            }
            let y_label = "mean residual, measured − model (N)";
            // A bin's mean of n samples with noise σ is noise within ±2σ/√n.
            let noise = bins(before).iter().filter(|b| b.count > 0).map(|b| {
                let half = 2.0 * before.sigma / (b.count as f64).sqrt();
                (b.centre, -half, half)
            });
            let band = Band {
                label: "±2σ/√n: noise of a bin's mean",
                colour: Colour::hex(0xd9d9d9),
                points: noise.collect(),
            };
            let figure = Figure::new(title, x_label, y_label, series);
            (stem, figure.with_band(band).with_zero_line())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::noise::noise_floor;
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rand_distr::Normal;
    use std::f64::consts::PI;

    /// Noise of the simulated sensor (N).
    const SIGMA: f64 = 15.0;
    /// Runs per record.
    const RUNS: usize = 200;
    /// Coefficient of restitution of the simulated motion (–).
    const RESTITUTION: f64 = 0.8;

    /// Appends one sample with measured force 0 (N), filled in by [`record`].
    #[allow(clippy::too_many_arguments)]
    fn push(
        s: &mut ContactSamples,
        run: usize,
        t: f64,
        depth: f64,
        rate: f64,
        v0: f64,
        deepest: f64,
        inside: bool,
    ) {
        s.run.push(run);
        s.time.push(t);
        s.depth.push(depth);
        s.rate.push(rate);
        s.approach_speed.push(v0);
        s.max_depth.push(deepest);
        s.in_contact.push(inside);
        s.measured.push(0.0);
    }

    /// A record of `RUNS` impacts — 20 flight samples 1 ms apart, the contact 1 µs apart
    /// (about 115 samples, loading a quarter sine, unloading a slower quarter sine to
    /// δ̇ = −e·δ̇0), 20 flight samples — with a Hertz model force of about 3000 N peak,
    /// and the measured force model + N(0, σ²) + `extra(sample index)`. Returns the
    /// samples and the model force (N).
    fn record(
        seed: u64,
        extra: impl Fn(&ContactSamples, usize) -> f64,
    ) -> (ContactSamples, Vec<f64>) {
        let noise = Normal::new(0.0, SIGMA).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let w_load = PI * (1.0 + 1.0 / RESTITUTION) / (2.0 * 115e-6);
        let w_unload = RESTITUTION * w_load;
        let t_peak = PI / (2.0 * w_load);
        let t_end = t_peak + PI / (2.0 * w_unload);
        let stiffness = 3000.0 / (1.0 / w_load).powf(1.5);
        let mut s = ContactSamples::default();
        for run in 0..RUNS {
            let v0 = 0.9 + 0.2 * run as f64 / RUNS as f64;
            let amplitude = v0 / w_load;
            for k in (1..=20).rev() {
                let t = -1e-3 * k as f64;
                push(&mut s, run, t, v0 * t, v0, 0.0, 0.0, false);
            }
            let mut deepest = 0.0_f64;
            let mut t = 0.5e-6;
            while t < t_end {
                let (depth, rate) = if t < t_peak {
                    let p = w_load * t;
                    (amplitude * p.sin(), v0 * p.cos())
                } else {
                    let p = w_unload * (t - t_peak);
                    (amplitude * p.cos(), -amplitude * w_unload * p.sin())
                };
                deepest = deepest.max(depth);
                push(&mut s, run, t, depth, rate, v0, deepest, true);
                t += 1e-6;
            }
            for k in 1..=20 {
                let dt = 1e-3 * k as f64;
                let speed = RESTITUTION * v0;
                push(
                    &mut s,
                    run,
                    t_end + dt,
                    -speed * dt,
                    -speed,
                    0.0,
                    0.0,
                    false,
                );
            }
        }
        let model: Vec<f64> = (0..s.len())
            .map(|i| {
                if s.in_contact[i] {
                    stiffness * s.depth[i].max(0.0).powf(1.5)
                } else {
                    0.0
                }
            })
            .collect();
        s.measured = (0..s.len())
            .map(|i| model[i] + rng.sample(noise) + extra(&s, i))
            .collect();
        (s, model)
    }

    /// Damping the model lacks (N·s/m).
    const DAMPING: f64 = 60.0;

    fn damped(s: &ContactSamples, i: usize) -> f64 {
        if s.in_contact[i] {
            DAMPING * s.rate[i]
        } else {
            0.0
        }
    }

    #[test]
    fn pure_noise_is_not_structured() {
        let (s, model) = record(21, |_, _| 0.0);
        let sigma = noise_floor(&s).sigma;
        let structure = residual_structure(&s, &model, sigma);
        eprintln!(
            "pure noise: σ̂ = {sigma:.3} N, contact RMS {:.3} N, excess {:.3} N, χ² = {:.1} (dof {}, threshold {:.1}), flight mean {:.3} N RMS {:.3} N",
            structure.contact_rms, structure.excess_rms, structure.chi_squared, structure.dof,
            structure.threshold, structure.flight_mean, structure.flight_rms
        );
        assert!(s.len() > 30_000 && structure.contact_samples > 20_000);
        assert_eq!(structure.dof, PHASE_BINS);
        assert!(!structure.structured);
        assert!(structure.excess_rms < 0.2 * SIGMA);
        assert!((structure.flight_rms / SIGMA - 1.0).abs() < 0.05);
        assert!(
            structure.flight_mean.abs() < 4.0 * SIGMA / (structure.flight_samples as f64).sqrt()
        );
    }

    #[test]
    fn a_missing_damping_shows_in_the_rate_bins() {
        let (s, model) = record(22, damped);
        let sigma = noise_floor(&s).sigma;
        let structure = residual_structure(&s, &model, sigma);
        eprintln!(
            "damping {DAMPING} N·s/m: σ̂ = {sigma:.3} N, excess {:.2} N, χ² = {:.0} (threshold {:.1})",
            structure.excess_rms, structure.chi_squared, structure.threshold
        );
        assert!(structure.structured);
        assert!(structure.excess_rms > 1.0 * SIGMA);
        // Approach speeds average 1 m/s, so a bin at δ̇/δ̇0 = x holds c·x N on average, up to
        // the spread of x within the bin (half a bin width) and the noise of the mean.
        let width = structure.by_rate[1].centre - structure.by_rate[0].centre;
        let (mut xy, mut xx) = (0.0, 0.0);
        for b in structure.by_rate.iter().filter(|b| b.count >= 100) {
            let expected = DAMPING * b.centre;
            let tolerance = DAMPING * width / 2.0 + 4.0 * SIGMA / (b.count as f64).sqrt();
            eprintln!(
                "  δ̇/δ̇0 {:+.3}: {:+7.2} N (c·δ̇ {:+7.2} N, n = {})",
                b.centre, b.mean, expected, b.count
            );
            assert!((b.mean - expected).abs() < tolerance, "{b:?}");
            (xy, xx) = (
                xy + b.count as f64 * b.centre * b.mean,
                xx + b.count as f64 * b.centre * b.centre,
            );
        }
        let slope = xy / xx;
        eprintln!("  fitted slope {slope:.2} N per unit δ̇/δ̇0");
        assert!((slope / DAMPING - 1.0).abs() < 0.05);
    }

    #[test]
    fn damping_like_residual_has_opposite_signs_in_loading_and_unloading() {
        let (s, model) = record(23, damped);
        let structure = residual_structure(&s, &model, SIGMA);
        assert!(structure.loading_rms > 2.0 * SIGMA && structure.unloading_rms > 2.0 * SIGMA);
        // Near δ_peak the rate, and so the residual, goes to zero: judge the bins below.
        let clear = |bins: &[Bin]| -> Vec<Bin> {
            bins.iter()
                .filter(|b| b.count >= 100 && b.centre < 0.8)
                .copied()
                .collect()
        };
        let (loading, unloading) = (
            clear(&structure.by_depth_loading),
            clear(&structure.by_depth_unloading),
        );
        assert!(loading.len() >= 5 && unloading.len() >= 5);
        assert!(loading.iter().all(|b| b.mean > 0.0), "{loading:?}");
        assert!(unloading.iter().all(|b| b.mean < 0.0), "{unloading:?}");
    }

    #[test]
    fn a_constant_offset_shows_in_the_flight_mean() {
        let offset = 20.0;
        let (s, model) = record(24, |_, _| offset);
        let structure = residual_structure(&s, &model, SIGMA);
        let standard_error = SIGMA / (structure.flight_samples as f64).sqrt();
        eprintln!(
            "offset {offset} N: flight mean {:.3} N (±{standard_error:.3}), flight RMS {:.3} N",
            structure.flight_mean, structure.flight_rms
        );
        assert!((structure.flight_mean - offset).abs() < 4.0 * standard_error);
        let expected_rms = (SIGMA * SIGMA + offset * offset).sqrt();
        assert!((structure.flight_rms / expected_rms - 1.0).abs() < 0.03);
        assert!(structure.structured);
    }

    #[test]
    fn figures_show_both_models() {
        let (s, model) = record(25, damped);
        let before = residual_structure(&s, &model, SIGMA);
        let fixed: Vec<f64> = (0..s.len()).map(|i| model[i] + damped(&s, i)).collect();
        let after = residual_structure(&s, &fixed, SIGMA);
        assert!(!after.structured);
        let figures = structure_figures(&before, Some(&after), ("base law", "extended law"));
        let stems: Vec<_> = figures.iter().map(|f| f.0).collect();
        assert_eq!(
            stems,
            [
                "residual_vs_time",
                "residual_vs_depth_loading",
                "residual_vs_depth_unloading",
                "residual_vs_rate"
            ]
        );
        for (_, figure) in &figures {
            let svg = figure.svg();
            assert!(svg.contains("base law") && svg.contains("extended law"));
            assert!(!figure.png().unwrap().is_empty());
        }
        let alone = structure_figures(&before, None, ("base law", "extended law"));
        assert!(alone.iter().all(|(_, f)| !f.svg().contains("extended law")));
    }
}
