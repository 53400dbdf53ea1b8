//! The diagnosis as a report: `DIR/report.md` of `hcm diagnose` (the answer, what is
//! wrong, the cause, the extended model and its gain), and the one-line answer
//! diagnosis.json carries.

use super::gain::{self, GainTable};
use super::naming::RIVAL_T;
use super::naming::{EVIDENCE, FAMILY_T};
use super::quality::DataQuality;
use super::select::BaseFreedom;
use super::structure::Structure;
use super::verdict::GAIN_T;
use super::Diagnosis;
use crate::dataset::MAX_MISFIT;
use std::fmt::Write as _;

/// The report's terms, glossed once for a reader who has not read the paper.
const TERMS: &str = "What the words mean: the *base* model is the physics file given with `--physics`; \
the *extended* model is the base model plus the effects named below, its base parameters re-fitted; \
the *HCM* (hybrid contact model) is the base model plus a small neural network trained on the same runs \
to predict the force the base model gets wrong, for comparison. The *residual* is measured − model force; \
the *noise floor* σ is the data's own force noise, read from the force's second differences; the \
*excess over noise* is √(RMS² − σ²), what a model leaves beyond the noise. *Held-out* runs (and a \
held-out condition) were never fitted. The four *indicators* of a contact are its maximum force, \
impulse, energy loss and duration; their *error* is |measured mean − model| / measured mean (the \
paper's Eq 20), in per cent — or, for an indicator whose measured mean is within two standard errors \
of zero (an elastic contact's energy loss), Δ = |model − measured| in its unit. *RMSE*: root-mean-square error; *RSS*: residual sum of squares; *CV*: \
5-fold cross-validation over whole runs; *BIC*: the Bayesian information criterion's threshold.\n\n";

/// One line from the last gain table (the held-out condition when there is one): the
/// indicator the base model misses most, and what the extended model and the HCM make
/// of it.
fn gain_takeaway(gain: &[GainTable]) -> Option<String> {
    let table = gain.last()?;
    let errors = |label: &str| {
        (table.rows.iter())
            .find(|r| r.judged.model == label)
            .and_then(|r| r.judged.errors)
            .map(|e| e.values())
    };
    let (base, extended) = (errors("base")?, errors("extended")?);
    // Among the indicators whose measured mean is told from zero (a relative error of
    // one that is not means nothing).
    let worst =
        (0..4)
            .filter(|&i| !table.near_zero[i])
            .reduce(|w, i| if base[i] > base[w] { i } else { w })?;
    let names = ["maximum force", "impulse", "energy loss", "duration"];
    let hcm = errors("HCM").map_or(String::new(), |h| {
        format!(" (HCM {:.2} %)", 100.0 * h[worst])
    });
    Some(format!(
        "On the {} ({} runs), the base model's largest error, on the {}, goes {:.2} % → {:.2} % with the extended model{hcm}.",
        table.group, table.runs, names[worst], 100.0 * base[worst], 100.0 * extended[worst]
    ))
}

/// The one-line answer: the named causes, "none", or "unexplained".
pub fn answer(d: &Diagnosis) -> String {
    if !d.data_quality.sufficient {
        return format!("insufficient data ({})", d.data_quality.reasons.join("; "));
    }
    let mut parts: Vec<String> = d.causes.iter().map(|c| c.effect.to_owned()).collect();
    if !d.ambiguous.is_empty() {
        parts.push(format!(
            "ambiguous ({}: the data cannot tell which)",
            d.ambiguous.join(" or ")
        ));
    }
    if d.unexplained_share > 0.0 {
        parts.push(format!(
            "unexplained ({:.0} %)",
            100.0 * d.unexplained_share
        ));
    }
    parts.extend(chance_named(d).map(|n| n.effect.clone()));
    if parts.is_empty() {
        "none".into()
    } else {
        parts.join(" + ")
    }
}

/// Whether the base law, its own parameters re-fitted on the training runs, already
/// leaves nothing but noise where the law as given left structure: then the decision
/// tried no effect (it adds one only to a model whose residual is still structured),
/// and what the base got wrong on these runs was its parameters' values.
fn refit_explains(d: &Diagnosis) -> bool {
    d.causes.is_empty()
        && d.base_structured
        && !d.after.structured
        && d.naming.is_empty()
        && d.not_accepted.is_empty()
        && d.ambiguous.is_empty()
}

/// The report's answer in one line a newcomer reads: each named cause with its
/// values and 95 % intervals and the share of the base model's structured residual
/// the causes explain and leave; or one verdict — insufficient data, ambiguous between
/// two effects, unexplained, or none. (`diagnosis.json`'s `answer` keeps the short
/// form of [`answer`].)
pub fn answer_line(d: &Diagnosis) -> String {
    let line = deterministic_line(d);
    let chances: Vec<String> = chance_named(d)
        .map(|n| {
            format!(
                "{} ({} = {})",
                n.effect,
                n.parameter,
                with_interval(n.value, n.interval)
            )
        })
        .collect();
    if chances.is_empty() {
        line
    } else {
        format!(
            "{line}; and from run to run, chance: {} (section 5)",
            chances.join(" + ")
        )
    }
}

/// The chances the diagnosis named, if it asked for them.
fn chance_named(d: &Diagnosis) -> impl Iterator<Item = &super::NamedChance> {
    d.chance.iter().flat_map(|c| c.named.iter())
}

/// [`answer_line`] of the deterministic phase.
fn deterministic_line(d: &Diagnosis) -> String {
    if !d.data_quality.sufficient {
        return format!("insufficient data ({})", d.data_quality.reasons.join("; "));
    }
    if d.causes.is_empty() {
        return if !d.ambiguous.is_empty() {
            format!(
                "ambiguous between {}: either explains the residual and the data cannot tell which, so neither is named",
                ambiguous_with_values(d)
            )
        } else if d.unexplained_share > 0.0 {
            "unexplained: the base model leaves a structured residual that no catalogued effect explains".into()
        } else if refit_explains(d) {
            "none: the base law's residual is structured as given, and nothing but noise \
             once its own parameters are re-fitted on the training runs, so no effect was \
             tried (section 2 says why)"
                .into()
        } else if d.base_structured {
            // What entered fitted the training runs' structure, then failed the held-out
            // runs: not "nothing but noise".
            "none named: the base model's residual is structured beyond the noise, and the \
             effects that fit it on the training runs do not hold on the held-out runs (the \
             decision below says why)"
                .into()
        } else {
            "none: the base model leaves nothing but noise".into()
        };
    }
    let causes: Vec<String> = (d.causes.iter())
        .map(|c| {
            let values: Vec<String> = (c.parameters.iter())
                .map(|p| format!("{} = {}", p.name, with_interval(p.value, p.ci)))
                .collect();
            let or = if c.effect == "sensor_gain" {
                "; or the bodies' effective mass is g times the scenario's: the momentum balance cannot tell which"
            } else {
                ""
            };
            format!("{} ({}{or})", c.effect, values.join(", "))
        })
        .collect();
    let left = d.unexplained_share.clamp(0.0, 1.0);
    let beyond = if d.partial {
        format!(
            " — a partial answer: the cause's shape is close to what the data show, not equal (it removes at least {:.0} % of the base model's excess), so its value also absorbs part of what is left",
            100.0 * super::naming::PARTIAL_SHARE
        )
    } else if d.ambiguous.is_empty() {
        String::new()
    } else {
        format!(
            "; beyond them, ambiguous between {} (neither named)",
            ambiguous_with_values(d)
        )
    };
    format!(
        "{}; {:.0} % of the base model's structured residual explained, {:.0} % left unexplained{beyond}",
        causes.join(" + "),
        100.0 * (1.0 - left),
        100.0 * left
    )
}

/// The effects `d` could not tell apart, each with its first parameter as fitted where
/// the decision reports one (`sensor_delay (delay = 1.02e-6) and sensor_filter
/// (time_constant = 1.05e-6)`): what either would be, though neither is named.
fn ambiguous_with_values(d: &Diagnosis) -> String {
    let with_value = |name: &str| {
        (d.not_accepted.iter())
            .find(|n| n.effect == name)
            .and_then(|n| n.parameters.first())
            .map_or(name.to_owned(), |p| {
                format!("{name} ({} = {:.3e})", p.name, p.value)
            })
    };
    (d.ambiguous.iter())
        .map(|name| with_value(name))
        .collect::<Vec<_>>()
        .join(" and ")
}

/// `value [lo, hi]` in scientific notation with enough significant digits (3 to 8)
/// that the interval's ends differ from the value where they do.
fn with_interval(value: f64, (lo, hi): (f64, f64)) -> String {
    let half = 0.5 * (hi - lo);
    let digits = if half > 0.0 && half.is_finite() && value != 0.0 && value.is_finite() {
        ((value.abs() / half).log10().ceil() as i64 + 1).clamp(3, 8) as usize
    } else {
        3
    };
    let p = digits - 1;
    format!("{value:.p$e} [{lo:.p$e}, {hi:.p$e}]")
}

/// How the motion the residual is read along was obtained, where it was not simply
/// recorded at the force rows.
fn motion_note(q: &DataQuality) -> Option<String> {
    let mut parts = Vec::new();
    if let Some(m) = q.motion_misfit.filter(|&m| m > MAX_MISFIT) {
        parts.push(format!(
            "the motion recorded on every row does not obey Newton's law with the force through the contacts (median misfit {m:.1} σ, above {}): it was replaced there by the motion the force implies, fitted to it",
            MAX_MISFIT
        ));
    }
    if let Some(g) = q.reconstruction_gap {
        parts.push(format!(
            "the motion was reconstructed from the camera frames and the force (median gap {g:.2} σ to the flight after each contact)"
        ));
    }
    if let Some(delay) = q.sensor_delay {
        parts.push(format!(
            "the force lags the camera by {:.3} ± {:.3} µs, found and undone by the reconstruction",
            1e6 * delay.value,
            1e6 * delay.sd
        ));
    }
    (!parts.is_empty()).then(|| {
        let mut line = parts.join("; ");
        line[..1].make_ascii_uppercase();
        line.push('.');
        line
    })
}

/// The report's head: the answer, the gain in one line, the terms, the runs and noise
/// floor σ (N), and how the motion was obtained.
fn head(md: &mut String, d: &Diagnosis) {
    md.push_str("# hcm diagnose\n\n");
    let _ = writeln!(md, "**Answer: {}.**\n", answer_line(d));
    if let Some((chi, threshold)) = d.sensor_gain.and_then(|g| g.rings) {
        let _ = writeln!(md, "**Sensor.** The force sensor does not read its offset in flight after the contacts (χ² {chi:.0} > {threshold:.0} over the readings from ¼ to 1¼ of a contact's duration after lift-off): it rings or drifts, so the momentum balance's gain is not named.\n");
    }
    if let Some(line) = gain_takeaway(&d.gain) {
        let what = if refit_explains(d) {
            " The extended model here is the base law re-fitted on the training runs, no effect added."
        } else {
            ""
        };
        let _ = writeln!(md, "**Gain.** {line}{what}\n");
    }
    md.push_str(TERMS);
    let _ = writeln!(
        md,
        "Fitted on {} runs; {} held out{}. Noise floor σ = {:.2} N (from {} second differences of the force).\n",
        d.runs.training,
        d.runs.held_out,
        d.runs.condition.as_ref().map_or(String::new(), |c| format!(", including condition `{c}`")),
        d.noise.sigma,
        d.noise.samples
    );
    if let Some(line) = motion_note(&d.data_quality) {
        let _ = writeln!(md, "**Motion.** {line}\n");
    }
}

/// Section 1: the residual of the base and the extended model on the training runs
/// (N), their replay on those runs, and the figures' names.
fn what_is_wrong(md: &mut String, d: &Diagnosis, figures: &[&str]) {
    let _ = writeln!(md, "## 1. What is wrong (training runs)\n");
    let _ = writeln!(md, "| residual | base | extended |\n|---|---|---|");
    type Row = (&'static str, fn(&Structure) -> f64);
    let rows: [Row; 4] = [
        ("RMS in contact (N)", |s| s.contact_rms),
        ("excess over noise (N)", |s| s.excess_rms),
        ("mean in flight (N)", |s| s.flight_mean),
        ("χ² of the time bins", |s| s.chi_squared),
    ];
    for (label, value) in rows {
        let _ = writeln!(
            md,
            "| {label} | {:.3} | {:.3} |",
            value(&d.before),
            value(&d.after)
        );
    }
    let _ = writeln!(
        md,
        "| structured beyond the noise | {} | {} |\n",
        d.before.structured, d.after.structured
    );
    let _ = writeln!(
        md,
        "The models replayed on the training runs (force against the recorded samples, indicators against the runs' means):\n"
    );
    md.push_str(&gain::markdown(std::slice::from_ref(&d.in_sample)));
    md.push('\n');
    let _ = writeln!(
        md,
        "Figures (base vs extended): {}.\n",
        figures
            .iter()
            .map(|f| format!("`{f}.svg`/`.png`"))
            .collect::<Vec<_>>()
            .join(", ")
    );
}

/// Section 2's table of the named causes: each parameter with its value, 95 % interval
/// and the cause's share, and the unexplained share.
fn the_cause(md: &mut String, d: &Diagnosis) {
    let _ = writeln!(md, "## 2. The cause\n");
    if refit_explains(d) {
        let _ = writeln!(md, "No cause is named, and no effect was tried. The base law as given leaves a structured residual on the training runs (χ² {:.1} > {:.1}), but with its own parameters re-fitted on them it leaves noise (χ² {:.1} ≤ {:.1}, σ = {:.2} N), and an effect is only ever added to a model whose residual is still structured. What the base law got wrong on these runs is the values of its parameters, not a missing effect: the extended model below is the base re-fitted, with no effect, and section 4 shows how it predicts the held-out runs.\n",
            d.before.chi_squared, d.before.threshold, d.after.chi_squared, d.after.threshold, d.after.sigma);
    } else if d.causes.is_empty() {
        // The rule as `naming` applies it (the linear ranking's share ≥ 2 % only orders
        // the report's selection steps; it decides nothing).
        let _ = writeln!(md, "No cause is named. Every catalogued effect was re-fitted with the base law; one is named when its RSS drop exceeds ln(n)·σ² per parameter (BIC), its 95 % intervals are finite, no effect of another family comes within {} of it in the criterion, it predicts held-out runs better by {GAIN_T} standard errors of the runs' paired differences, and the residual it leaves is noise — or, re-fitted alone, it removes at least {:.0} % of the base model's excess over the noise and wins on held-out runs by {GAIN_T} standard errors (a partial answer). The effects tried and why none was accepted are listed under the decision below.\n", super::naming::EVIDENCE, 100.0 * super::naming::PARTIAL_SHARE);
    } else {
        let _ = writeln!(md, "| effect | kind | parameter | value | 95 % interval | share |\n|---|---|---|---|---|---|");
        for c in &d.causes {
            for (k, p) in c.parameters.iter().enumerate() {
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {:.4e} | [{:.4e}, {:.4e}] | {} |",
                    if k == 0 { c.effect } else { "" },
                    if k == 0 { c.family.kind() } else { "" },
                    p.name,
                    p.value,
                    p.ci.0,
                    p.ci.1,
                    if k == 0 {
                        format!("{:.1} %", 100.0 * c.share)
                    } else {
                        String::new()
                    }
                );
            }
        }
        md.push('\n');
    }
    let _ = writeln!(
        md,
        "Unexplained share: {:.1} %.\n",
        100.0 * d.unexplained_share
    );
}

/// Section 2's steps of the linear selection: RSS (N²) before and with each effect,
/// cross-validated, against the information criterion.
fn selection_steps(md: &mut String, d: &Diagnosis) {
    let _ = writeln!(md, "Selection steps (add: forward step, `taken` = entered; remove: backward check, `taken` = removed):\n\n| step | effect | shape | RSS before → with (N²) | CV RSS before → with | ΔRSS/σ² vs BIC | share | taken |\n|---|---|---|---|---|---|---|---|");
    for s in &d.selection {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.4e} → {:.4e} | {:.4e} → {:.4e} | {:.1} vs {:.1} | {:.3} | {} |",
            s.action,
            s.effect,
            s.shape.map_or("–".into(), |p| format!("{p}")),
            s.rss.0,
            s.rss.1,
            s.cv_rss.0,
            s.cv_rss.1,
            s.bic.0,
            s.bic.1,
            s.share,
            s.accepted
        );
    }
}

/// Section 2's decision on full re-fits: each step's best trial, RSS (N²) against the
/// information criterion, and every cause not accepted with why.
fn decision(md: &mut String, d: &Diagnosis) {
    let freedom = match d.base_freedom {
        BaseFreedom::Given => "the base's exponent only where the motion was reconstructed, elsewhere a change of it is `stiffness_exponent`",
        BaseFreedom::Fitted => "every parameter the user's fit had free, the exponent among them where the law has one",
    };
    let scattered = if d.before.scattered {
        format!(
            "; the runs scatter beyond the sample noise, so its lead over the best effect of another family must also hold on held-out runs, at {RIVAL_T} standard errors of the runs' paired differences (viscous damping only where hysteresis damping is not better by {FAMILY_T})"
        )
    } else {
        String::new()
    };
    let _ = writeln!(md, "\nThe decision, on full re-fits: each step adds every effect not yet named to the model and re-fits base and effects together ({freedom}); the best by information criterion enters if its RSS drop passes the criterion, its parameters are determined and the best effect of another family scores worse by at least {EVIDENCE} (else `ambiguous`, neither named); it must predict runs it was not fitted on, its gain on held-out runs, run by run, at {GAIN_T} standard errors{scattered}; a cause is named only if the residual then holds nothing but noise, or alone removes at least {:.0} % of the base model's excess and wins on held-out runs (a partial answer); a `stiffness_exponent` only where the momentum balance rules out a force sensor whose gain grows with the force (else `ambiguous` with `sensor_nonlinearity`).", 100.0 * super::naming::PARTIAL_SHARE);
    if d.naming.is_empty() {
        let why = if d.after.structured {
            ""
        } else {
            ": the base law re-fitted alone left no structure to explain"
        };
        let _ = writeln!(md, "\nNo step was taken{why}.");
    } else {
        let _ = writeln!(md, "\n| effect | RSS before → with (N²) | ΔRSS/σ² vs BIC | parameters determined | entered |\n|---|---|---|---|---|");
    }
    for t in &d.naming {
        let _ = writeln!(
            md,
            "| {} | {:.4e} → {:.4e} | {:.1} vs {:.1} | {} | {} |",
            t.effect, t.rss.0, t.rss.1, t.bic.0, t.bic.1, t.determined, t.accepted
        );
    }
    for n in &d.not_accepted {
        let parameters = n
            .parameters
            .iter()
            .map(|p| format!("{} = {:.4e}", p.name, p.value))
            .collect::<Vec<_>>()
            .join(", ");
        let _ = writeln!(
            md,
            "\nNot accepted: `{}` ({parameters}): {}.",
            n.effect, n.reason
        );
    }
}

/// Sections 3 and 4: the extended model's re-fitted base parameters and the gain
/// tables on the held-out runs.
fn extended_and_gain(md: &mut String, d: &Diagnosis) {
    let _ = writeln!(md, "\n## 3. The extended model\n\n`extended.toml`: base law with re-fitted parameters ({}) plus the physical effects; `simulate`, `evaluate` and the core read it. {}\n",
        d.base_parameters.iter().map(|p| format!("{} = {:.5e}", p.name, p.value)).collect::<Vec<_>>().join(", "),
        freedom_rule(d.base_freedom));
    let _ = writeln!(md, "## 4. The gain (held-out runs)\n");
    md.push_str(&gain::markdown(&d.gain));
}

/// The rule [`BaseFreedom`] applies, as a sentence.
fn freedom_rule(freedom: BaseFreedom) -> &'static str {
    match freedom {
        BaseFreedom::Fitted => "The base law was fitted (its physics file records the fit), so every parameter that fit had free is re-tuned with the effects, the exponent among them where the law has one: a change of the exponent is then the base's own freedom, not an effect, and `stiffness_exponent` is not a candidate (a law without a free exponent keeps it).",
        BaseFreedom::Given => "The base law was given, not fitted: its exponent is held (re-tuned only where the motion was reconstructed), and a change of it is the effect `stiffness_exponent`.",
    }
}

/// The report of `d` (report.md) in Markdown; `figures` names the residual figures
/// written beside it (without extension).
pub fn diagnosis_markdown(d: &Diagnosis, figures: &[&str]) -> String {
    let mut md = String::new();
    head(&mut md, d);
    what_is_wrong(&mut md, d, figures);
    the_cause(&mut md, d);
    selection_steps(&mut md, d);
    decision(&mut md, d);
    extended_and_gain(&mut md, d);
    chance_section(&mut md, d);
    md
}

/// Section 5: the chance phase's rounds, what it named and the extended model's
/// forecast of the held-out runs beside the deterministic one's.
fn chance_section(md: &mut String, d: &Diagnosis) {
    let Some(c) = &d.chance else {
        return;
    };
    let _ = writeln!(md, "
## 5. Chance (held-out runs)

After the deterministic effects, the model forecasts each run's force as an ensemble: each member's law parameters drawn with their scatter (Eq 18), read along the run's recorded motion by the fitted sensor, plus the sensor's noise. A run's score is the fair CRPS of its peak force, impulse and the energy the contact takes, each in % of its mean over the training runs, averaged (lower is better; the deterministic model plus the sensor's noise is the reference). Each candidate — a free parameter's scatter σ (relative), the sensor's noise × k — is fitted on the training runs over a grid (its interval: the values the training runs do not tell from the best at 95 %, paired) and judged on {} held-out runs by ensembles of {} members, by the rule of section 2: a gain of {} standard errors, beating every rival.\n", c.held_out, c.members, super::verdict::GAIN_T);
    let _ = writeln!(md, "| round | candidate | fitted | interval | held-out gain (%/run) | ± | t | helps |\n|---|---|---|---|---|---|---|---|");
    for (k, round) in c.rounds.iter().enumerate() {
        for t in &round.trials {
            let _ = writeln!(
                md,
                "| {} | `{}` | {:.4} | {:.4} – {:.4} | {:.4} | {:.4} | {:.1} | {} |",
                k + 1,
                t.effect,
                t.value,
                t.interval.0,
                t.interval.1,
                t.gain.mean,
                t.gain.standard_error,
                t.gain.t(),
                t.helps
            );
        }
        let _ = writeln!(
            md,
            "| {} | *verdict* (reference {:.4} %) | {} | | | | | |",
            k + 1,
            round.reference,
            round.verdict
        );
    }
    for n in &c.named {
        let beside = if n.same_as.is_empty() {
            String::new()
        } else {
            format!(
                "; the held-out runs cannot tell it from {} (one forecast)",
                n.same_as.join(", ")
            )
        };
        let _ = writeln!(
            md,
            "\nNamed: `{}`, {} = {}{beside}; `extended.toml` carries it (`noise` of the contact), and every command's `--members` draws it.",
            n.effect,
            n.parameter,
            with_interval(n.value, n.interval)
        );
    }
    let _ = writeln!(
        md,
        "\nThe forecast of the held-out runs: score {:.4} % (deterministic) → {:.4} % (with the chances named), gain {:.4} ± {:.4} % per run; 50 % and 90 % bands of the indicators hold {:.3} and {:.3} of them ({:.3} and {:.3} without).",
        c.scores.0,
        c.scores.1,
        c.gain.mean,
        c.gain.standard_error,
        c.coverage[0],
        c.coverage[1],
        c.coverage_reference[0],
        c.coverage_reference[1]
    );
}
