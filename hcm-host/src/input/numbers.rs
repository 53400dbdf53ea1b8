//! Value parsers for the numeric options (the CLI's, and the Python API's for the same
//! values, so that both refuse a value with the same words). clap's own say "invalid digit found in
//! string" for `--runs 1e9` and "unexpected argument '-5'" for `--runs -5`: neither
//! what the option takes nor what is wrong with the value. One parser per kind of
//! number; each message says what was expected, with an example, and why the value
//! is not it. Options taking them set `allow_negative_numbers` so that a negative
//! value reaches the parser instead of being read as a flag.

/// `--runs`: runs per condition.
pub fn runs(text: &str) -> Result<usize, String> {
    count(text, 1, "a whole number of runs ≥ 1, e.g. --runs 100")
}

/// `--threads`: worker threads of the parallel work.
pub fn threads(text: &str) -> Result<usize, String> {
    count(
        text,
        1,
        "a whole number of worker threads ≥ 1, e.g. --threads 2",
    )
}

/// `hcm power --seeds`: data sets per effect and strength.
pub fn seeds(text: &str) -> Result<u64, String> {
    whole(text, 1, "a whole number of seeds ≥ 1, e.g. --seeds 10")
}

/// `--seed`: any 64-bit unsigned integer.
pub fn seed(text: &str) -> Result<u64, String> {
    whole(
        text,
        0,
        "a seed: a whole number from 0 to 18446744073709551615, e.g. --seed 7",
    )
}

/// `--contact`: the index of a `[[contact]]` of the scenario.
pub fn contact(text: &str) -> Result<usize, String> {
    count(
        text,
        0,
        "the index of a [[contact]] of the scenario, counted from 0, e.g. --contact 0",
    )
}

/// `--epochs`: training epochs.
pub fn epochs(text: &str) -> Result<usize, String> {
    count(text, 1, "a whole number of epochs ≥ 1, e.g. --epochs 200")
}

/// `--int8-epochs`: fine-tuning epochs, 0 for plain rounding.
pub fn fine_tuning_epochs(text: &str) -> Result<usize, String> {
    count(
        text,
        0,
        "a whole number of epochs ≥ 0 (0: plain rounding), e.g. --int8-epochs 20",
    )
}

/// `--population`: GA individuals (crossover needs two).
pub fn population(text: &str) -> Result<usize, String> {
    count(
        text,
        2,
        "a whole number of individuals ≥ 2, e.g. --population 60",
    )
}

/// `--generations`: GA generations.
pub fn generations(text: &str) -> Result<usize, String> {
    count(
        text,
        1,
        "a whole number of generations ≥ 1, e.g. --generations 150",
    )
}

/// `--holdout`: a share of runs, strictly between 0 and 1.
pub fn share(text: &str) -> Result<f64, String> {
    let expected = "a share strictly between 0 and 1, e.g. --holdout 0.25";
    match text.trim().parse::<f64>() {
        Ok(x) if x > 0.0 && x < 1.0 => Ok(x),
        Ok(x) => Err(format!("expected {expected} ({x} is not)")),
        Err(_) => Err(format!("expected {expected} (`{text}` is not a number)")),
    }
}

/// A finite number in SI units (`force --depth`, `--rate`, `--approach-speed`).
pub fn number(text: &str) -> Result<f64, String> {
    let expected = "a finite number in SI units, e.g. 1e-5 or -0.3";
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!("expected {expected} (`{text}` is not finite)")),
        Err(_) => Err(format!("expected {expected} (`{text}` is not a number)")),
    }
}

/// [`whole`] as a `usize`.
fn count(text: &str, min: u64, expected: &str) -> Result<usize, String> {
    let n = whole(text, min, expected)?;
    usize::try_from(n).map_err(|_| format!("expected {expected} ({n} is too large)"))
}

/// A whole number ≥ `min`, else "expected `expected` (why `text` is not one)".
fn whole(text: &str, min: u64, expected: &str) -> Result<u64, String> {
    let text = text.trim();
    let reason = match text.parse::<u64>() {
        Ok(n) if n >= min => return Ok(n),
        Ok(n) => format!("{n} is below {min}"),
        Err(_) => why_not_whole(text),
    };
    Err(format!("expected {expected} ({reason})"))
}

/// Why `text`, which does not parse as a `u64`, is not a whole number ≥ 0.
fn why_not_whole(text: &str) -> String {
    let digits = !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit());
    match text.parse::<f64>() {
        _ if digits => format!("{text} is larger than the largest, {}", u64::MAX),
        Ok(x) if x < 0.0 => format!("{text} is negative"),
        Ok(x) if x.fract() == 0.0 && x < u64::MAX as f64 && text.contains(['e', 'E']) => {
            format!("{text} is in scientific notation: write its digits, {x:.0}")
        }
        Ok(x) if x.is_finite() && x.fract() == 0.0 => format!("{text} is too large"),
        Ok(x) if x.is_finite() => format!("{text} is not a whole number"),
        Ok(_) => format!("{text} is not finite"),
        Err(_) => format!("`{text}` is not a number"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_numbers_in_range_are_taken() {
        assert_eq!(runs("100"), Ok(100));
        assert_eq!(seed("0"), Ok(0));
        assert_eq!(seed("18446744073709551615"), Ok(u64::MAX));
        assert_eq!(contact("0"), Ok(0));
        assert_eq!(population("2"), Ok(2));
        assert_eq!(share("0.25"), Ok(0.25));
        assert_eq!(number("-1e-5"), Ok(-1e-5));
    }

    #[test]
    fn each_refusal_says_what_was_expected_and_why() {
        let expected = "expected a whole number of runs ≥ 1, e.g. --runs 100";
        let cases = [
            (
                "1e9",
                "1e9 is in scientific notation: write its digits, 1000000000",
            ),
            ("-5", "-5 is negative"),
            ("0", "0 is below 1"),
            ("2.5", "2.5 is not a whole number"),
            ("abc", "`abc` is not a number"),
            ("inf", "inf is not finite"),
            ("1e30", "1e30 is too large"),
        ];
        for (text, reason) in cases {
            assert_eq!(runs(text), Err(format!("{expected} ({reason})")), "{text}");
        }
        let seed = seed("-1").unwrap_err();
        assert!(
            seed.starts_with("expected a seed: a whole number from 0"),
            "{seed}"
        );
        assert!(seed.ends_with("(-1 is negative)"), "{seed}");
        assert!(seed.contains("18446744073709551615"), "{seed}");
        let huge = super::seed("18446744073709551616").unwrap_err();
        assert!(huge.ends_with("is larger than the largest, 18446744073709551615)"));
        assert!(share("1").unwrap_err().contains("(1 is not)"));
        assert!(number("NaN").unwrap_err().contains("not finite"));
    }
}
