//! Numbers as the report prints them: plain decimals with a unit, under the SI prefix
//! that keeps them between 1 and 1000 (8.67294 mJ, 114.414 µs), never `8.67294e-3`.
//! results.json keeps the raw SI values.

/// SI prefixes from giga to nano, with their factors.
const PREFIXES: [(&str, f64); 7] = [
    ("G", 1e9),
    ("M", 1e6),
    ("k", 1e3),
    ("", 1.0),
    ("m", 1e-3),
    ("µ", 1e-6),
    ("n", 1e-9),
];

/// How the numbers of one column are printed: one unit for the column, so that its
/// rows compare at a glance.
#[derive(Clone, Debug, PartialEq)]
pub struct Scale {
    /// SI value of one printed unit (1e-3 for mJ).
    factor: f64,
    /// The unit printed, with its prefix (`mJ`).
    unit: String,
}

impl Scale {
    /// The SI `unit` itself, without a prefix (N, N·s, m/s: the units people quote
    /// unprefixed across the report's range).
    pub fn plain(unit: &str) -> Self {
        Scale {
            factor: 1.0,
            unit: unit.to_owned(),
        }
    }

    /// The prefix of `unit` that puts `reference` (SI) between 1 and 1000; the plain
    /// unit for 0 or a value that is not finite.
    pub fn prefixed(reference: f64, unit: &str) -> Self {
        let magnitude = reference.abs();
        let prefix = (PREFIXES.iter())
            .find(|(_, factor)| magnitude >= *factor)
            .filter(|_| magnitude.is_finite() && magnitude > 0.0)
            .map_or(("", 1.0), |&(p, f)| (p, f));
        Scale {
            factor: prefix.1,
            unit: format!("{}{unit}", prefix.0),
        }
    }

    /// A mass (kg) in grams under the prefix that suits `reference` (kg): 66.93 g.
    pub fn mass(reference: f64) -> Self {
        let grams = Scale::prefixed(reference * 1e3, "g");
        Scale {
            factor: grams.factor * 1e-3,
            unit: grams.unit,
        }
    }

    /// `value` (SI) to `significant` digits, trailing zeros kept (`2911.86 N`), so
    /// that every row of a table shows the same precision.
    pub fn show(&self, value: f64, significant: usize) -> String {
        format!(
            "{} {}",
            decimals(value / self.factor, significant),
            self.unit
        )
    }

    /// `value` (SI) to at most `significant` digits, trailing zeros dropped
    /// (`12.7 mm`, `0.95 m/s`): for prose.
    pub(crate) fn brief(&self, value: f64, significant: usize) -> String {
        let text = trimmed(decimals(value / self.factor, significant));
        format!("{text} {}", self.unit).trim_end().to_owned()
    }
}

/// `text` (a decimal number) without trailing zeros after the point.
fn trimmed(text: String) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

/// A parameter's value (SI `unit`, `-` or empty for none) for prose: lengths, masses
/// and pressures under an SI prefix (12.7 mm, 66.93 g, 24.02 GPa), others plain or as
/// a power of ten (987.9 1/m, 6.9025 × 10⁹ N/m^n).
pub fn parameter(value: f64, unit: &str, significant: usize) -> String {
    match unit {
        "m" | "Pa" | "s" => Scale::prefixed(value, unit).brief(value, significant),
        "kg" => Scale::mass(value).brief(value, significant),
        "-" | "" => number(value, significant),
        _ => format!("{} {unit}", number(value, significant)),
    }
}

/// `value` with `significant` significant digits in plain decimal notation; `–` for a
/// value that is not finite.
fn decimals(value: f64, significant: usize) -> String {
    if !value.is_finite() {
        return "–".to_owned();
    }
    let order = if value == 0.0 {
        0
    } else {
        value.abs().log10().floor() as i64
    };
    let places = (significant as i64 - 1 - order).max(0) as usize;
    let text = format!("{value:.places$}");
    // Rounding may carry into a new digit (999.9996 → 1000.000): one place fewer.
    let carried = text
        .parse::<f64>()
        .is_ok_and(|rounded| rounded.abs() >= 10f64.powi(order as i32 + 1));
    if carried && places > 0 {
        format!("{value:.*}", places - 1)
    } else {
        text
    }
}

/// A dimensionless number to at most `significant` digits, in plain notation when it
/// reads well (0.9288, 1.4894, 2), else as a power of ten: `6.90246 × 10⁹`.
pub fn number(value: f64, significant: usize) -> String {
    let magnitude = value.abs();
    if !value.is_finite() || magnitude == 0.0 || (1e-3..1e5).contains(&magnitude) {
        return trimmed(decimals(value, significant));
    }
    let exponent = magnitude.log10().floor() as i32;
    let mantissa = value / 10f64.powi(exponent);
    format!(
        "{} × 10{}",
        trimmed(decimals(mantissa, significant)),
        superscript(exponent)
    )
}

/// `exponent` in superscript digits (⁻¹²).
fn superscript(exponent: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits = exponent.unsigned_abs().to_string();
    let sign = if exponent < 0 { "⁻" } else { "" };
    sign.chars()
        .chain(digits.bytes().map(|b| DIGITS[usize::from(b - b'0')]))
        .collect()
}

/// A fraction as per cent with two decimals (0.0602 → `6.02 %`), `–` if not finite.
pub fn percent(fraction: f64) -> String {
    if fraction.is_finite() {
        format!("{:.2} %", 100.0 * fraction)
    } else {
        "–".to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_take_the_prefix_of_their_reference() {
        assert_eq!(Scale::plain("N").show(2924.3149, 6), "2924.31 N");
        assert_eq!(Scale::plain("N·s").show(0.18114523, 6), "0.181145 N·s");
        let energy = Scale::prefixed(8.67294e-3, "J");
        assert_eq!(energy.show(8.672941e-3, 6), "8.67294 mJ");
        assert_eq!(energy.show(8.17156e-3, 3), "8.17 mJ");
        let duration = Scale::prefixed(1.14414e-4, "s");
        assert_eq!(duration.show(1.144141e-4, 6), "114.414 µs");
        // A value of another magnitude keeps the column's unit and its own digits.
        assert_eq!(duration.show(1.2e-3, 3), "1200 µs");
        assert_eq!(Scale::prefixed(0.0, "s").show(0.0, 3), "0.00 s");
    }

    #[test]
    fn prose_drops_trailing_zeros_and_masses_read_in_grams() {
        assert_eq!(Scale::prefixed(0.0127, "m").brief(0.0127, 4), "12.7 mm");
        assert_eq!(Scale::prefixed(0.1, "m").brief(0.1, 4), "100 mm");
        assert_eq!(Scale::mass(0.06693).brief(0.06693, 4), "66.93 g");
        assert_eq!(Scale::mass(2.5).brief(2.5, 4), "2.5 kg");
        assert_eq!(Scale::plain("m/s").brief(1.40071, 4), "1.401 m/s");
        assert_eq!(Scale::plain("m/s").brief(0.95, 4), "0.95 m/s");
    }

    #[test]
    fn rounding_never_adds_a_digit() {
        assert_eq!(decimals(999.9996, 6), "1000.00");
        assert_eq!(decimals(-0.099999996, 3), "-0.100");
        assert_eq!(decimals(f64::NAN, 3), "–");
    }

    #[test]
    fn large_and_small_numbers_read_as_powers_of_ten() {
        assert_eq!(number(6.902464e9, 6), "6.90246 × 10⁹");
        assert_eq!(number(2.5e-7, 2), "2.5 × 10⁻⁷");
        assert_eq!(number(1.489387, 5), "1.4894");
        assert_eq!(number(2.0, 5), "2");
        assert_eq!(parameter(0.0127, "m", 5), "12.7 mm");
        assert_eq!(parameter(2.4021e10, "Pa", 4), "24.02 GPa");
        assert_eq!(parameter(0.06693, "kg", 4), "66.93 g");
        assert_eq!(parameter(987.9, "1/m", 5), "987.9 1/m");
        assert_eq!(parameter(0.93, "-", 5), "0.93");
        assert_eq!(percent(0.0602), "6.02 %");
        assert_eq!(percent(f64::NAN), "–");
    }
}
