//! Round tick values for one axis: a step of 1, 2 or 5 × 10ⁿ, ticks at the step's
//! multiples, and the axis range widened to whole ticks — so every label is a short
//! round number and the grid lines fall on them.

/// Data magnitude beyond which values are clamped before choosing ticks (data units): far
/// beyond any physical quantity here, and far enough from `f64::MAX` that spans and
/// widened ranges cannot overflow.
const LARGEST: f64 = 1e300;
/// Relative resolution of a range: a range narrower than this fraction of its values is
/// widened to it, since `f64` cannot label finer steps meaningfully (–).
const RESOLUTION: f64 = 1e-9;
/// Least fraction of the axis the data should span before a finer step is tried (–).
const MIN_COVERAGE: f64 = 0.75;
/// Largest magnitude labelled in plain notation; larger ticks use a power of ten (data
/// units).
const PLAIN_BELOW: f64 = 1e5;
/// Most decimals a plain label may have; finer steps use a power of ten.
const PLAIN_DECIMALS: i32 = 4;

/// The ticks of one axis: `index` from `first` to `last`, tick value `index × step`
/// with step = `mantissa × 10^exponent` (data units).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Ticks {
    /// 1, 2 or 5.
    mantissa: i64,
    /// Power of ten of the step.
    exponent: i32,
    /// Index of the lowest tick: it lies at or below the data.
    first: i64,
    /// Index of the highest tick: it lies at or above the data.
    last: i64,
}

impl Ticks {
    /// Round ticks covering `low`–`high` (data units) in about `intervals` steps
    /// (between 0.63 and 1.6 times as many, plus up to two for the widening to whole
    /// ticks; up to twice as many where a coarser step would leave more than a quarter of
    /// the axis empty). A zero-width range is widened about its value (to ±50 % of it, at
    /// least ±0.5), a reversed or non-finite one replaced by 0–1.
    pub(super) fn new(low: f64, high: f64, intervals: usize) -> Ticks {
        let (low, high) = widened(low, high);
        let raw = (high - low) / intervals.max(1) as f64;
        let exponent = raw.log10().floor() as i32;
        let fraction = raw / 10f64.powi(exponent);
        // Nearest of 1, 2, 5, 10 on a log scale: the boundaries are their geometric means.
        let (mantissa, exponent) = match fraction {
            f if f < 2f64.sqrt() => (1, exponent),
            f if f < 10f64.sqrt() => (2, exponent),
            f if f < 50f64.sqrt() => (5, exponent),
            _ => (1, exponent + 1),
        };
        let ticks = Ticks::covering(low, high, mantissa, exponent);
        // E.g. forces from −3 N to 1700 N: steps of 500 N would spend a fifth of the axis
        // on −500–0 N; steps of 200 N spend a tenth.
        let (first, last) = ticks.range();
        if (high - low) / (last - first) >= MIN_COVERAGE {
            return ticks;
        }
        let finer = ticks.finer(low, high);
        let limit = 2 * intervals.max(1) as i64;
        if finer.last - finer.first <= limit {
            finer
        } else {
            ticks
        }
    }

    /// The ticks of the next finer round step (10 → 5 → 2 → 1) covering `low`–`high`.
    fn finer(&self, low: f64, high: f64) -> Ticks {
        let (mantissa, exponent) = match self.mantissa {
            5 => (2, self.exponent),
            2 => (1, self.exponent),
            _ => (5, self.exponent - 1),
        };
        Ticks::covering(low, high, mantissa, exponent)
    }

    /// The ticks of step `mantissa × 10^exponent` from the last multiple at or below
    /// `low` to the first at or above `high`.
    fn covering(low: f64, high: f64, mantissa: i64, exponent: i32) -> Ticks {
        let step = mantissa as f64 * 10f64.powi(exponent);
        // A value within a millionth of a step of a tick is on it (rounding in `low / step`).
        let first = (low / step + 1e-6).floor() as i64;
        let last = ((high / step - 1e-6).ceil() as i64).max(first + 1);
        Ticks {
            mantissa,
            exponent,
            first,
            last,
        }
    }

    /// The next coarser round step (1 → 2 → 5 → 10) over the same range, for when the
    /// labels of these ticks do not fit.
    pub(super) fn coarser(&self) -> Ticks {
        let (mantissa, exponent) = match self.mantissa {
            1 => (2, self.exponent),
            2 => (5, self.exponent),
            _ => (1, self.exponent + 1),
        };
        let (low, high) = self.range();
        Ticks::covering(low, high, mantissa, exponent)
    }

    #[cfg(test)]
    /// The distance between ticks (data units).
    pub(super) fn step(&self) -> f64 {
        self.value(1) - self.value(0)
    }

    /// The axis range: the lowest and the highest tick (data units).
    pub(super) fn range(&self) -> (f64, f64) {
        (self.value(self.first), self.value(self.last))
    }

    /// The tick values, lowest first (data units).
    pub(super) fn values(&self) -> impl Iterator<Item = f64> + '_ {
        (self.first..=self.last).map(|i| self.value(i))
    }

    /// The value of tick `index`: the decimal number `index × mantissa × 10^exponent`
    /// rounded once to `f64`, so labels print exactly (data units).
    fn value(&self, index: i64) -> f64 {
        let digits = (index * self.mantissa) as f64;
        if self.exponent < 0 {
            digits / 10f64.powi(-self.exponent)
        } else {
            digits * 10f64.powi(self.exponent)
        }
    }

    /// Each tick's label, lowest first: plain numbers with just the decimals the step
    /// needs ("0.25"), or for very large values or very fine steps a mantissa times a power
    /// of ten ("1.2×10⁻⁴"), all mantissas with the decimals the largest tick needs.
    /// Negative values take the minus sign "−".
    pub(super) fn labels(&self) -> Vec<String> {
        let largest = self.first.abs().max(self.last.abs()) * self.mantissa;
        let magnitude = largest as f64 * 10f64.powi(self.exponent);
        if magnitude < PLAIN_BELOW && -self.exponent <= PLAIN_DECIMALS {
            let decimals = (-self.exponent).max(0) as usize;
            return (self.first..=self.last)
                .map(|i| format!("{}{:.decimals$}", sign(i), self.value(i).abs()))
                .collect();
        }
        // The digits of a tick beyond its leading one, in units of the step's power of ten.
        let places = |digits: i64| digits.checked_ilog10().unwrap_or(0) as i32;
        let decimals = places(largest).max(0) as usize;
        (self.first..=self.last)
            .map(|i| {
                let digits = (i * self.mantissa).abs();
                if digits == 0 {
                    return "0".to_owned();
                }
                let shift = places(digits);
                let leading = digits as f64 / 10f64.powi(shift);
                let power = superscript(self.exponent + shift);
                format!("{}{leading:.decimals$}×10{power}", sign(i))
            })
            .collect()
    }
}

/// The sign written before tick `index`: the minus sign for negative ones.
fn sign(index: i64) -> &'static str {
    if index < 0 {
        "−"
    } else {
        ""
    }
}

/// `low`–`high` made a finite range of non-zero width that `f64` can resolve into ticks:
/// clamped to ±[`LARGEST`], a single value widened about it, empty or reversed → 0–1.
fn widened(low: f64, high: f64) -> (f64, f64) {
    if low.is_nan() || high.is_nan() || low > high {
        return (0.0, 1.0);
    }
    let (low, high) = (low.clamp(-LARGEST, LARGEST), high.clamp(-LARGEST, LARGEST));
    let centre = 0.5 * (low + high);
    let magnitude = low.abs().max(high.abs());
    let half = if low == high {
        0.5 * magnitude.max(1.0)
    } else {
        (0.5 * (high - low)).max(RESOLUTION * magnitude)
    };
    (centre - half, centre + half)
}

/// `power` in superscript digits, e.g. −4 → "⁻⁴".
fn superscript(power: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let sign = if power < 0 { "⁻" } else { "" };
    let digits: String = power
        .unsigned_abs()
        .to_string()
        .bytes()
        .map(|b| DIGITS[(b - b'0') as usize])
        .collect();
    format!("{sign}{digits}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tick values and labels of `low`–`high` in about 5 intervals.
    fn ticks(low: f64, high: f64) -> (Vec<f64>, Vec<String>) {
        let ticks = Ticks::new(low, high, 5);
        (ticks.values().collect(), ticks.labels())
    }

    /// True if `step` is 1, 2 or 5 × 10ⁿ (up to rounding).
    fn round_step(step: f64) -> bool {
        let fraction = step / 10f64.powf(step.log10().floor());
        [1.0, 2.0, 5.0, 10.0]
            .iter()
            .any(|m| (fraction - m).abs() < 1e-9)
    }

    #[test]
    fn a_force_range_gets_ticks_every_500_n_from_0_to_3500() {
        let (values, labels) = ticks(0.0, 3074.0);
        assert_eq!(
            values,
            [0.0, 500.0, 1000.0, 1500.0, 2000.0, 2500.0, 3000.0, 3500.0]
        );
        assert_eq!(
            labels,
            ["0", "500", "1000", "1500", "2000", "2500", "3000", "3500"]
        );
    }

    #[test]
    fn small_values_share_a_power_of_ten() {
        let (values, labels) = ticks(1.1e-4, 1.9e-4);
        assert_eq!(values, [1.0e-4, 1.2e-4, 1.4e-4, 1.6e-4, 1.8e-4, 2.0e-4]);
        assert_eq!(
            labels,
            [
                "1.0×10⁻⁴",
                "1.2×10⁻⁴",
                "1.4×10⁻⁴",
                "1.6×10⁻⁴",
                "1.8×10⁻⁴",
                "2.0×10⁻⁴"
            ]
        );
        let (_, labels) = ticks(0.0, 2.2e6);
        assert_eq!(labels[0], "0");
        assert_eq!(labels[1], "5.0×10⁵");
        assert_eq!(labels.last().unwrap(), "2.5×10⁶");
    }

    #[test]
    fn negative_ranges_take_a_minus_sign_and_cross_zero_on_a_tick() {
        let (values, labels) = ticks(-37.2, 25.1);
        assert_eq!(values, [-40.0, -30.0, -20.0, -10.0, 0.0, 10.0, 20.0, 30.0]);
        assert_eq!(labels, ["−40", "−30", "−20", "−10", "0", "10", "20", "30"]);
        let (values, labels) = ticks(-0.93, -0.12);
        assert_eq!(values, [-1.0, -0.8, -0.6, -0.4, -0.2, 0.0]);
        assert_eq!(labels, ["−1.0", "−0.8", "−0.6", "−0.4", "−0.2", "0.0"]);
    }

    #[test]
    fn a_finer_step_is_taken_rather_than_leave_much_of_the_axis_empty() {
        // Steps of 500 would show −500–2000 for data from −3 to 1700.
        let (values, _) = ticks(-3.0, 1700.0);
        assert_eq!(values.first(), Some(&-200.0));
        assert_eq!(values.last(), Some(&1800.0));
        assert_eq!(values.len(), 11);
        // Not when the finer step would crowd the axis.
        let ticks = Ticks::new(-3.0, 1700.0, 2);
        assert_eq!(ticks.range(), (-1000.0, 2000.0));
    }

    #[test]
    fn labels_have_just_the_decimals_the_step_needs() {
        assert_eq!(
            ticks(0.0, 1.0).1,
            ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]
        );
        assert_eq!(
            ticks(0.0, 118.3).1,
            ["0", "20", "40", "60", "80", "100", "120"]
        );
        let (_, labels) = ticks(0.011, 0.019);
        assert_eq!(labels.first().unwrap(), "0.010");
        assert_eq!(labels.last().unwrap(), "0.020");
    }

    #[test]
    fn a_single_value_or_a_zero_width_range_gets_ticks_around_it() {
        let (values, labels) = ticks(4.0, 4.0);
        assert_eq!(values, [2.0, 3.0, 4.0, 5.0, 6.0]);
        assert_eq!(labels, ["2", "3", "4", "5", "6"]);
        let (values, _) = ticks(0.0, 0.0);
        assert!(values.contains(&0.0) && values[0] < 0.0 && *values.last().unwrap() > 0.0);
        // A range below f64's resolution at its magnitude still gets distinct ticks.
        let (values, labels) = ticks(1e10, 1e10 + 1e-6);
        assert!(values.windows(2).all(|w| w[1] > w[0]), "{values:?}");
        assert!(labels.windows(2).all(|w| w[1] != w[0]), "{labels:?}");
    }

    #[test]
    fn empty_reversed_and_huge_ranges_stay_finite() {
        for (low, high) in [
            (f64::INFINITY, f64::NEG_INFINITY),
            (1.0, 0.0),
            (f64::NAN, 1.0),
            (-f64::MAX, f64::MAX),
            (1e300, 1e300),
        ] {
            let ticks = Ticks::new(low, high, 5);
            let values: Vec<f64> = ticks.values().collect();
            assert!((2..=12).contains(&values.len()), "{low}–{high}: {values:?}");
            assert!(values.iter().all(|v| v.is_finite()), "{low}–{high}");
        }
        assert_eq!(ticks(1.0, 0.0).0, [0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
    }

    #[test]
    fn ticks_are_round_cover_the_data_and_number_about_as_asked() {
        let ranges = [
            (0.0, 3074.0),
            (-146.4, 3074.0),
            (1e-7, 9e-7),
            (-2.5e4, 1.3e4),
            (0.3, 0.31),
            (17.0, 9000.0),
        ];
        for (low, high) in ranges {
            for intervals in [3, 5] {
                let ticks = Ticks::new(low, high, intervals);
                let (first, last) = ticks.range();
                assert!(first <= low && last >= high, "{low}–{high}");
                assert!(round_step(ticks.step()), "{low}–{high}: {}", ticks.step());
                let n = ticks.values().count() - 1;
                let (n, asked) = (n as f64, intervals as f64);
                assert!(n >= 0.63 * asked && n <= 1.6 * asked + 2.0, "{n}");
                // Each tick is a whole multiple of the step.
                for v in ticks.values() {
                    let k = v / ticks.step();
                    assert!((k - k.round()).abs() < 1e-6, "{v} / {}", ticks.step());
                }
            }
        }
    }

    #[test]
    fn coarser_steps_go_1_2_5_10() {
        let ticks = Ticks::new(0.0, 10.0, 10);
        assert_eq!(ticks.step(), 1.0);
        let steps: Vec<f64> = std::iter::successors(Some(ticks), |t| Some(t.coarser()))
            .take(4)
            .map(|t| t.step())
            .collect();
        assert_eq!(steps, [1.0, 2.0, 5.0, 10.0]);
        assert_eq!(ticks.coarser().coarser().range(), (0.0, 10.0));
    }
}
