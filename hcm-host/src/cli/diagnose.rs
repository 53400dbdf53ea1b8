//! `hcm diagnose`: what the simulation gets wrong, the cause named, the model extended
//! with it, and the gain measured on held-out runs.

use super::progress_bar;
use anyhow::Context;
use hcm_host::dataset::{needs, Dataset};
use hcm_host::diagnose::catalogue::Kind;
use hcm_host::diagnose::gain::markdown;
use hcm_host::diagnose::structure::{structure_figures, Structure};
use hcm_host::diagnose::{diagnose, DiagnoseSettings, Diagnosis};
use hcm_host::identify::physics::PhysicsBody;
use hcm_host::identify::{FitRecord, Physics};
use hcm_host::output::write_bytes;
use serde_json::json;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Diagnose a physics model against data: what is wrong, why, and the model extended.
///
/// Example: `hcm diagnose --scenario scenarios/flat_shot.toml --data measured.csv --physics base.toml --out diag/`
///
/// Compares the base model's force with the data against the noise floor, names the
/// catalogued effects that explain the difference (with parameters, 95 % intervals and
/// shares), writes the extended model (OUT/extended.toml) and measures its gain on
/// held-out runs (and a held-out condition) beside the base model and the HCM. Writes
/// OUT/report.md, OUT/diagnosis.json and figures.
///
/// Terms:
///   base model      the physics file given with `--physics` (e.g. from `hcm identify`)
///   extended model  the base model plus the effects found
///   noise floor     the data's own force noise σ, from its second differences
///   held-out runs   runs never fitted, on which the gain is measured
///   HCM             hybrid contact model: the base model plus a residual network
///                   trained on the same runs, for comparison
///   residual        measured − model force (N); the network learns it
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Measured data (measured-data CSV).
    #[arg(long)]
    data: PathBuf,
    /// Physics file of the base model (as written by `hcm identify`).
    #[arg(long)]
    physics: PathBuf,
    /// Output directory (created): report.md, diagnosis.json, extended.toml, figures.
    #[arg(long)]
    out: PathBuf,
    /// Which contact of the scenario.
    #[arg(long, default_value_t = 0)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::contact)]
    contact: usize,
    /// Seed of the hold-out draw and of the HCM's training.
    #[arg(long, default_value_t = 1)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::seed)]
    seed: u64,
    /// Share of the runs (inside the fitted range) held out for the gain table. The
    /// condition held out whole is the scenario's first `experiment.holdout_conditions`
    /// entry (else the last condition), e.g. `--set 'experiment.holdout_conditions=["v1.0"]'`.
    #[arg(long, default_value_t = 0.25)]
    #[arg(allow_negative_numbers = true, value_parser = super::numbers::share)]
    holdout: f64,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    if !(args.holdout > 0.0 && args.holdout < 1.0) {
        anyhow::bail!(
            "--holdout must lie strictly between 0 and 1, found {}",
            args.holdout
        );
    }
    let scenario = args.scenario.load()?;
    let physics = Physics::read(&args.physics)?;
    let base = physics.apply(&scenario, &args.physics)?.model()?;
    super::require_one_dimensional(&base, "diagnose")?;
    super::check_contact(args.contact, &base)?;
    let data = Dataset::read(&args.data)?;
    data.require(
        &args.data.display().to_string(),
        &base,
        &[args.contact],
        &needs::DIAGNOSE,
    )?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let bar = progress_bar(1, "diagnosing (noise, selection, re-fit, HCM, gain)");
    let settings = DiagnoseSettings {
        contact: args.contact,
        seed: args.seed,
        holdout_fraction: args.holdout,
        ..DiagnoseSettings::default()
    };
    let diagnosis = diagnose(&base, &data, &settings)?;
    bar.finish_and_clear();

    // The extended model, in the physics-file format every command reads.
    let mut extended = Physics::for_contact(
        &base,
        args.contact,
        &diagnosis.extended.base,
        FitRecord {
            method: "diagnose".into(),
            data: args.data.display().to_string(),
            runs: diagnosis.runs.training,
            ..FitRecord::default()
        },
    );
    extended.contacts[0].effects = diagnosis.extended.effects.iter().copied().collect();
    if let Some(air_drag) = diagnosis.drag.as_ref().and_then(|d| d.air_drag()) {
        extended.bodies.push(PhysicsBody {
            name: diagnosis.drag_body.clone(),
            air_drag,
        });
    }
    extended.write(
        &args.out.join("extended.toml"),
        &format!("extended model of `{}` from hcm diagnose", scenario.name),
    )?;
    write_bytes(
        &args.out.join("diagnosis.json"),
        serde_json::to_string_pretty(&json_of(&diagnosis))?.as_bytes(),
    )?;
    let mut figures = Vec::new();
    for (name, figure) in structure_figures(
        &diagnosis.before,
        Some(&diagnosis.after),
        ("base", "extended"),
    ) {
        write_bytes(
            &args.out.join(format!("{name}.svg")),
            figure.svg().as_bytes(),
        )?;
        write_bytes(&args.out.join(format!("{name}.png")), &figure.png()?)?;
        figures.push(name);
    }
    let report = report(&diagnosis, &figures);
    write_bytes(&args.out.join("report.md"), report.as_bytes())?;
    print!("{report}");
    Ok(())
}

/// diagnosis.json (documented in the README, "hcm diagnose").
fn json_of(d: &Diagnosis) -> serde_json::Value {
    let causes: Vec<_> = d
        .causes
        .iter()
        .map(|c| {
            json!({
                "effect": c.effect,
                "kind": c.kind,
                "parameters": c.parameters.iter().map(|p| (p.name.clone(), json!(p.value))).collect::<serde_json::Map<_, _>>(),
                "ci": c.parameters.iter().map(|p| (p.name.clone(), json!([p.ci.0, p.ci.1]))).collect::<serde_json::Map<_, _>>(),
                "share": c.share,
            })
        })
        .collect();
    json!({
        "causes": causes,
        "unexplained_share": d.unexplained_share,
        "answer": answer(d),
        "noise_sigma": d.noise.sigma,
        "base_structured": d.base_structured,
        "runs": d.runs,
        "base_parameters": d.base_parameters,
        "selection": d.selection,
        "naming": d.naming,
        "data_quality": d.data_quality,
        "not_accepted": d.not_accepted,
        "ambiguous": d.ambiguous,
        "before": d.before,
        "after": d.after,
        "gain": d.gain,
        "in_sample": d.in_sample,
        "air_drag_fit": d.drag,
    })
}

/// The report's terms, glossed once for a reader who has not read the paper.
const TERMS: &str = "What the words mean: the *base* model is the physics file given with `--physics`; \
the *extended* model is the base model plus the effects named below, its base parameters re-fitted; \
the *HCM* (hybrid contact model) is the base model plus a small neural network trained on the same runs \
to predict the force the base model gets wrong, for comparison. The *residual* is measured − model force; \
the *noise floor* σ is the data's own force noise, read from the force's second differences; the \
*excess over noise* is √(RMS² − σ²), what a model leaves beyond the noise. *Held-out* runs (and a \
held-out condition) were never fitted. The four *indicators* of a contact are its maximum force, \
impulse, energy loss and duration; their *error* is |measured mean − model| / measured mean (the \
paper's Eq 20), in per cent. *RMSE*: root-mean-square error; *RSS*: residual sum of squares; *CV*: \
5-fold cross-validation over whole runs; *BIC*: the Bayesian information criterion's threshold.\n\n";

/// One line from the last gain table (the held-out condition when there is one): the
/// indicator the base model misses most, and what the extended model and the HCM make
/// of it.
fn gain_takeaway(gain: &[hcm_host::diagnose::gain::GainTable]) -> Option<String> {
    let table = gain.last()?;
    let errors = |label: &str| {
        (table.rows.iter())
            .find(|r| r.judged.model == label)
            .and_then(|r| r.judged.errors)
            .map(|e| e.values())
    };
    let (base, extended) = (errors("base")?, errors("extended")?);
    let worst = (0..4).fold(0, |w, i| if base[i] > base[w] { i } else { w });
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
fn answer(d: &Diagnosis) -> String {
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
    if parts.is_empty() {
        "none".into()
    } else {
        parts.join(" + ")
    }
}

/// How the motion the residual is read along was obtained, where it was not simply
/// recorded at the force rows.
fn motion_note(q: &hcm_host::diagnose::quality::DataQuality) -> Option<String> {
    let mut parts = Vec::new();
    if let Some(m) = q
        .motion_misfit
        .filter(|&m| m > hcm_host::dataset::newton::MAX_MISFIT)
    {
        parts.push(format!(
            "the motion recorded on every row does not obey Newton's law with the force through the contacts (median misfit {m:.1} σ, above {}): it was replaced there by the motion the force implies, fitted to it",
            hcm_host::dataset::newton::MAX_MISFIT
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

fn report(d: &Diagnosis, figures: &[&str]) -> String {
    let mut md = String::from("# hcm diagnose\n\n");
    let _ = writeln!(md, "**Answer: {}.**\n", answer(d));
    if let Some(line) = gain_takeaway(&d.gain) {
        let _ = writeln!(md, "**Gain.** {line}\n");
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
    md.push_str(&markdown(std::slice::from_ref(&d.in_sample)));
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
    let _ = writeln!(md, "## 2. The cause\n");
    if d.causes.is_empty() {
        let _ = writeln!(md, "No catalogued effect passed the selection (cross-validation across runs, BIC, share ≥ 2 %).\n");
    } else {
        let _ = writeln!(md, "| effect | kind | parameter | value | 95 % interval | share |\n|---|---|---|---|---|---|");
        for c in &d.causes {
            for (k, p) in c.parameters.iter().enumerate() {
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {:.4e} | [{:.4e}, {:.4e}] | {} |",
                    if k == 0 { c.effect } else { "" },
                    if k == 0 {
                        match c.kind {
                            Kind::Physical => "physical",
                            Kind::Measurement => "measurement",
                        }
                    } else {
                        ""
                    },
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
    let _ = writeln!(md, "\nThe decision, on full re-fits (each step adds every effect not yet named to the model, re-fits base and effects together — the base's exponent only where the motion was reconstructed, elsewhere a change of it is `stiffness_exponent` — and takes the best if it passes the information criterion with determined parameters; a cause is named only if the residual then holds nothing but noise):\n\n| effect | RSS before → with (N²) | ΔRSS/σ² vs BIC | parameters determined | entered |\n|---|---|---|---|---|");
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
    let _ = writeln!(md, "\n## 3. The extended model\n\n`extended.toml`: base law with re-fitted parameters ({}) plus the physical effects; `simulate`, `evaluate` and the core read it.\n",
        d.base_parameters.iter().map(|p| format!("{} = {:.5e}", p.name, p.value)).collect::<Vec<_>>().join(", "));
    let _ = writeln!(md, "## 4. The gain (held-out runs)\n");
    md.push_str(&markdown(&d.gain));
    md
}
