//! Proper scores of an ensemble forecast against what happened, and how often its
//! bands hold the outcome (Gneiting & Raftery 2007, *Strictly proper scoring rules,
//! prediction, and estimation*, J. Am. Stat. Assoc. 102(477); §4.2 the CRPS, §4.3 the
//! energy score).
//!
//! A forecast of M members x₁…x_M is the distribution that puts 1/M on each. Its
//! scores are negatively oriented (lower is better) and proper: no forecast scores
//! better in expectation than the distribution the outcome is drawn from, so a
//! forecast that is sure where the outcome varies, or spread where it does not, loses
//! to one that spreads as much as the outcome does. A deterministic model is the
//! ensemble of one member, scored by the same formulas (its CRPS is then the absolute
//! error, its energy score the Euclidean error), so the two compare directly.
//!
//! The estimators are the forecast's own scores, with 1/M² in the spread term (not the
//! "fair" 1/(M·(M − 1)), which is undefined for one member): an ensemble of few
//! members is scored as the distribution it is.

/// The continuous ranked probability score of the members `members` for the outcome
/// `observed` (their unit): E|X − y| − ½·E|X − X′| with X, X′ drawn from the members,
/// = (1/M)·Σᵢ|xᵢ − y| − (1/(2M²))·Σᵢ Σⱼ |xᵢ − xⱼ|. NaN for no members or any NaN value.
/// O(M log M): the pair sum from the sorted members, Σᵢ Σⱼ |xᵢ − xⱼ| = 2·Σₖ (2k − M + 1)·x₍ₖ₎
/// (k from 0).
pub fn crps(members: &[f64], observed: f64) -> f64 {
    if members.is_empty() || observed.is_nan() || members.iter().any(|x| x.is_nan()) {
        return f64::NAN;
    }
    let m = members.len() as f64;
    let error = members.iter().map(|x| (x - observed).abs()).sum::<f64>() / m;
    let mut sorted = members.to_vec();
    sorted.sort_by(f64::total_cmp);
    let spread: f64 = (sorted.iter().enumerate())
        .map(|(k, x)| (2.0 * k as f64 - m + 1.0) * x)
        .sum();
    error - spread / (m * m)
}

/// The fair CRPS of the members `members` for the outcome `observed` (their unit):
/// [`crps`] with the spread term over the M·(M − 1) pairs of distinct members,
/// (1/M)·Σᵢ|xᵢ − y| − (1/(2M(M − 1)))·Σᵢ Σⱼ |xᵢ − xⱼ| (Ferro 2014, *Fair scores for
/// ensemble forecasts*, QJRMS 140): in expectation the CRPS of the distribution the
/// members are drawn from, whatever M, so an ensemble of few members fitted by it is
/// not pushed wider. One member: the absolute error. NaN for no members or any NaN.
pub fn fair_crps(members: &[f64], observed: f64) -> f64 {
    let m = members.len() as f64;
    if members.len() < 2 {
        return crps(members, observed);
    }
    // crps = error − S/M² with S = ½·Σᵢ Σⱼ |xᵢ − xⱼ|; the error alone is E|X − y|.
    let error = members.iter().map(|x| (x - observed).abs()).sum::<f64>() / m;
    let spread_m2 = error - crps(members, observed);
    error - spread_m2 * m / (m - 1.0)
}

/// The energy score of the members `members` (each a point of the same dimension) for
/// the outcome `observed` (their unit): E‖X − y‖ − ½·E‖X − X′‖, the CRPS's
/// multivariate form (equal to it in one dimension). NaN for no members, a member of
/// another dimension, or any NaN coordinate. O(M²·d).
pub fn energy_score<P: AsRef<[f64]>>(members: &[P], observed: &[f64]) -> f64 {
    let dimension = observed.len();
    let valid = |p: &[f64]| p.len() == dimension && p.iter().all(|v| !v.is_nan());
    if members.is_empty() || !valid(observed) || members.iter().any(|p| !valid(p.as_ref())) {
        return f64::NAN;
    }
    let points: Vec<&[f64]> = members.iter().map(AsRef::as_ref).collect();
    energy_score_by(&points, observed, euclidean)
}

/// The Euclidean distance between two points of the same dimension (their unit).
pub fn euclidean(a: &[f64], b: &[f64]) -> f64 {
    (a.iter().zip(b))
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The energy score's form with any `distance` between two points (its unit):
/// E d(X, y) − ½·E d(X, X′) over the members, (1/M)·Σᵢ d(xᵢ, y) − (1/M²)·Σ_{i<j} d(xᵢ, xⱼ).
/// Proper where the distance is of negative type (Gneiting & Raftery 2007, §4.3; the
/// Euclidean distance is); NaN for no members. O(M²) distances.
pub fn energy_score_by<T: ?Sized, P: std::borrow::Borrow<T>>(
    members: &[P],
    observed: &T,
    distance: impl Fn(&T, &T) -> f64,
) -> f64 {
    let (error, half_spread) = energy_parts_by(members, observed, distance);
    error - half_spread
}

/// The energy score's two terms: E d(X, y) and ½·E d(X, X′) with 1/M² ([`energy_score_by`]
/// is their difference). The "fair" score, whose expectation is the score of the
/// distribution the members are drawn from whatever their number, puts M/(M − 1) on
/// the second (Ferro 2014); a search that chooses a spread by the score uses it, since
/// 1/M² would favour ensembles narrower than the outcome. NaN for no members.
pub fn energy_parts_by<T: ?Sized, P: std::borrow::Borrow<T>>(
    members: &[P],
    observed: &T,
    distance: impl Fn(&T, &T) -> f64,
) -> (f64, f64) {
    if members.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let m = members.len() as f64;
    let error = (members.iter())
        .map(|p| distance(p.borrow(), observed))
        .sum::<f64>()
        / m;
    let mut spread = 0.0;
    for (i, a) in members.iter().enumerate() {
        for b in &members[i + 1..] {
            spread += distance(a.borrow(), b.borrow());
        }
    }
    // Each unordered pair once: the double sum is twice this.
    (error, spread / (m * m))
}

/// The Brier score Σ_k (p_k − [k = outcome])² of the probabilities `p` of each category
/// for the category `outcome` that happened (–, 0 certain and right … 2 certain and
/// wrong). NaN for an outcome outside `p`.
pub fn brier(p: &[f64], outcome: usize) -> f64 {
    if outcome >= p.len() {
        return f64::NAN;
    }
    (p.iter().enumerate())
        .map(|(k, &pk)| {
            let hit = if k == outcome { 1.0 } else { 0.0 };
            (pk - hit) * (pk - hit)
        })
        .sum()
}

/// The logarithmic score −ln p(outcome) (nats; 0 certain and right, ∞ for a probability
/// of 0). NaN for an outcome outside `p`.
pub fn log_score(p: &[f64], outcome: usize) -> f64 {
    p.get(outcome).map_or(f64::NAN, |p| -p.ln())
}

/// The central band holding `level` (0…1) of the members (their unit): the members'
/// (1 − level)/2 and (1 + level)/2 quantiles with the k-th smallest of M members taken
/// as the k/(M + 1) quantile, linearly interpolated between (Hyndman & Fan's type 6,
/// NumPy's `method="weibull"`). An outcome drawn like the members is as likely to fall
/// in any of the M + 1 gaps between them, so this band holds it `level` of the time —
/// down to the members' range, which it never leaves: with fewer than 2/(1 − level) − 1
/// members (19 for 90 %, 3 for 50 %) the band is the range, holding (M − 1)/(M + 1).
/// One member is a band of zero width; NaN for none or any NaN member.
pub fn central_band(members: &[f64], level: f64) -> (f64, f64) {
    if members.is_empty() || members.iter().any(|x| x.is_nan()) {
        return (f64::NAN, f64::NAN);
    }
    let mut sorted = members.to_vec();
    sorted.sort_by(f64::total_cmp);
    band_of_sorted(&sorted, level)
}

/// The share of outcomes drawn like `members` members that their [`central_band`] of
/// `level` holds (–): the level, or the members' range's (M − 1)/(M + 1) where the band
/// is the range; 0 for one member.
pub fn calibrated_coverage(members: usize, level: f64) -> f64 {
    let m = members as f64;
    f64::min(level, (m - 1.0).max(0.0) / (m + 1.0))
}

/// [`central_band`] of members already sorted, at least one and none NaN.
fn band_of_sorted(sorted: &[f64], level: f64) -> (f64, f64) {
    let level = level.clamp(0.0, 1.0);
    let last = (sorted.len() - 1) as f64;
    let quantile = |q: f64| {
        // Zero-based position of the q quantile: member k (from 0) is the (k + 1)/(M + 1)
        // quantile.
        let h = ((sorted.len() + 1) as f64 * q - 1.0).clamp(0.0, last);
        let (below, above) = (h.floor() as usize, h.ceil() as usize);
        sorted[below] + (h - below as f64) * (sorted[above] - sorted[below])
    };
    (quantile(0.5 * (1.0 - level)), quantile(0.5 * (1.0 + level)))
}

/// Coverage counts of central bands: for each level, how many outcomes fell inside
/// (bounds included) of how many were scored.
#[derive(Clone, Debug, PartialEq)]
pub struct Coverage {
    /// Nominal levels (0…1).
    pub levels: Vec<f64>,
    /// Outcomes inside each level's band.
    pub inside: Vec<usize>,
    /// Outcomes scored.
    pub scored: usize,
}

impl Coverage {
    /// Empty counts for `levels` (0…1).
    pub fn new(levels: &[f64]) -> Coverage {
        Coverage {
            levels: levels.to_vec(),
            inside: vec![0; levels.len()],
            scored: 0,
        }
    }

    /// The share of the outcomes scored inside the band of `level` (–); NaN where
    /// `level` is not counted or nothing was scored.
    pub fn share_at(&self, level: f64) -> f64 {
        match self.levels.iter().position(|l| *l == level) {
            Some(k) if self.scored > 0 => self.inside[k] as f64 / self.scored as f64,
            _ => f64::NAN,
        }
    }

    /// Counts one outcome `observed` against the bands of `members`; an outcome or
    /// ensemble with NaN is not counted.
    pub fn add(&mut self, members: &[f64], observed: f64) {
        if observed.is_nan() || members.is_empty() || members.iter().any(|x| x.is_nan()) {
            return;
        }
        let mut sorted = members.to_vec();
        sorted.sort_by(f64::total_cmp);
        for (level, inside) in self.levels.iter().zip(&mut self.inside) {
            let (low, high) = band_of_sorted(&sorted, *level);
            if (low..=high).contains(&observed) {
                *inside += 1;
            }
        }
        self.scored += 1;
    }

    /// Adds the counts of `other`, of the same levels (another toss's, another fold's).
    pub fn merge(&mut self, other: &Coverage) {
        self.scored += other.scored;
        for (total, inside) in self.inside.iter_mut().zip(&other.inside) {
            *total += inside;
        }
    }

    /// The observed share inside each level's band (0…1); NaN before any outcome.
    pub fn shares(&self) -> Vec<f64> {
        let n = self.scored as f64;
        self.inside.iter().map(|&k| k as f64 / n).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The fair CRPS: two members 0 and 2 for the outcome 1 have error 1 and a pair
    /// spread of 4 over 2·2·1 pair slots, so 0 (the plain CRPS gives 0.5); one member is
    /// the absolute error. Over many small ensembles drawn from N(0, 1) for outcomes
    /// drawn alike, it averages the distribution's own CRPS, 1/√π, where the plain CRPS
    /// of 4 members is larger by E|X − X′|/(2M) = (2/√π)/8.
    #[test]
    fn the_fair_crps_is_unbiased_for_few_members() {
        assert_eq!(fair_crps(&[0.0, 2.0], 1.0), 0.0);
        assert_eq!(crps(&[0.0, 2.0], 1.0), 0.5);
        assert_eq!(fair_crps(&[3.0], 1.0), 2.0);
        assert!(fair_crps(&[], 1.0).is_nan());
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut normal =
            || -> f64 { rand_distr::Distribution::sample(&rand_distr::StandardNormal, &mut rng) };
        let (mut fair, mut plain, n) = (0.0, 0.0, 40_000);
        for _ in 0..n {
            let members = [normal(), normal(), normal(), normal()];
            let y = normal();
            fair += fair_crps(&members, y) / n as f64;
            plain += crps(&members, y) / n as f64;
        }
        let truth = 1.0 / std::f64::consts::PI.sqrt();
        assert!((fair - truth).abs() < 0.01, "{fair} vs {truth}");
        assert!((plain - truth - 2.0 / std::f64::consts::PI.sqrt() / 8.0).abs() < 0.01);
    }

    /// The pair sum written out, for the sorted form to be checked against.
    fn crps_by_pairs(x: &[f64], y: f64) -> f64 {
        let m = x.len() as f64;
        let error: f64 = x.iter().map(|a| (a - y).abs()).sum::<f64>() / m;
        let spread: f64 = x
            .iter()
            .flat_map(|a| x.iter().map(move |b| (a - b).abs()))
            .sum();
        error - spread / (2.0 * m * m)
    }

    #[test]
    fn one_member_scores_its_absolute_and_euclidean_error() {
        assert_eq!(crps(&[2.5], 1.0), 1.5);
        assert_eq!(energy_score(&[[0.0, 3.0]], &[4.0, 0.0]), 5.0);
        assert_eq!(central_band(&[2.0], 0.9), (2.0, 2.0));
    }

    #[test]
    fn the_sorted_crps_is_the_pair_sum_and_the_energy_score_in_one_dimension() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for m in [2, 3, 7, 40] {
            let x: Vec<f64> = (0..m).map(|_| rng.random::<f64>() * 4.0 - 2.0).collect();
            let y = rng.random::<f64>();
            let pairs = crps_by_pairs(&x, y);
            assert!((crps(&x, y) - pairs).abs() < 1e-12, "{m}");
            let points: Vec<[f64; 1]> = x.iter().map(|&v| [v]).collect();
            assert!((energy_score(&points, &[y]) - pairs).abs() < 1e-12, "{m}");
        }
    }

    #[test]
    fn a_point_forecast_at_the_outcome_scores_zero_and_two_equal_halves_a_known_value() {
        assert_eq!(crps(&[1.0, 1.0, 1.0], 1.0), 0.0);
        // Members −1 and 1, outcome 0: E|X − y| = 1, ½E|X − X′| = ½ · ½ · 2 = 0.5.
        assert_eq!(crps(&[-1.0, 1.0], 0.0), 0.5);
    }

    /// Propriety, sampled: outcomes from N(0, 1); ensembles drawn from N(0, s²) for
    /// s = 0.3, 1 and 3. The mean CRPS and energy score are lowest for s = 1, the
    /// outcome's own spread.
    #[test]
    fn the_ensemble_that_spreads_as_the_outcome_does_scores_best() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut normal = move || {
            // Box–Muller (rand_distr is not needed for a test).
            let (u, v): (f64, f64) = (rng.random(), rng.random());
            (-2.0 * (1.0 - u).ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        };
        let spreads = [0.3, 1.0, 3.0];
        let (mut crps_sum, mut energy_sum) = ([0.0; 3], [0.0; 3]);
        for _ in 0..2000 {
            let y = [normal(), normal()];
            for (k, s) in spreads.iter().enumerate() {
                let members: Vec<[f64; 2]> =
                    (0..20).map(|_| [s * normal(), s * normal()]).collect();
                let first: Vec<f64> = members.iter().map(|p| p[0]).collect();
                crps_sum[k] += crps(&first, y[0]);
                energy_sum[k] += energy_score(&members, &y);
            }
        }
        assert!(
            crps_sum[1] < crps_sum[0] && crps_sum[1] < crps_sum[2],
            "{crps_sum:?}"
        );
        assert!(
            energy_sum[1] < energy_sum[0] && energy_sum[1] < energy_sum[2],
            "{energy_sum:?}"
        );
    }

    /// Outcomes drawn like the members fall inside the bands their level of the time,
    /// or the members' range's (M − 1)/(M + 1) where the band is the range: 0.5 and 0.9
    /// for 99 members; 0.5 and 0.857 for 13 (the 90 % band of 13 is their range).
    #[test]
    fn bands_cover_their_level_of_outcomes_drawn_like_the_members() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for members in [99, 13] {
            let mut coverage = Coverage::new(&[0.5, 0.9]);
            for _ in 0..8000 {
                let drawn: Vec<f64> = (0..members).map(|_| rng.random::<f64>()).collect();
                coverage.add(&drawn, rng.random::<f64>());
            }
            assert_eq!(coverage.scored, 8000);
            let m = members as f64;
            for (share, level) in coverage.shares().iter().zip([0.5, 0.9]) {
                let expected = calibrated_coverage(members, level);
                assert_eq!(expected, f64::min(level, (m - 1.0) / (m + 1.0)));
                // 8000 outcomes: a standard error below 0.006.
                assert!(
                    (share - expected).abs() < 0.02,
                    "{members}: {share} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn the_band_interpolates_order_statistics_as_numpy_does() {
        // numpy.quantile([1, 2, 3, 4], [0.25, 0.75], method="weibull") = [1.25, 3.75].
        assert_eq!(central_band(&[4.0, 1.0, 3.0, 2.0], 0.5), (1.25, 3.75));
        // Beyond the members: their range.
        assert_eq!(central_band(&[4.0, 1.0, 3.0, 2.0], 0.9), (1.0, 4.0));
    }

    #[test]
    fn categorical_scores_and_bad_input() {
        assert_eq!(brier(&[1.0, 0.0], 0), 0.0);
        assert_eq!(brier(&[0.0, 1.0], 0), 2.0);
        assert!((brier(&[0.5, 0.25, 0.25], 1) - (0.25 + 0.5625 + 0.0625)).abs() < 1e-15);
        assert_eq!(log_score(&[0.5, 0.5], 1), std::f64::consts::LN_2);
        assert!(brier(&[1.0], 3).is_nan() && log_score(&[1.0], 3).is_nan());
        assert!(crps(&[], 0.0).is_nan() && crps(&[f64::NAN], 0.0).is_nan());
        assert!(energy_score(&[[0.0, 1.0]], &[0.0]).is_nan());
        let mut coverage = Coverage::new(&[0.5]);
        coverage.add(&[f64::NAN], 0.0);
        assert_eq!(coverage.scored, 0);
    }
}
