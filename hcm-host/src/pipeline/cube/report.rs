//! `report.md` of `hcm reproduce cube-toss` and `elbow-toss`: the score table beside the published
//! figures, the fit, the error per phase, the diagnosis, the timings.

use super::phases::{IMPACT_AFTER, REST_ANGLE, REST_DISTANCE, REST_SPAN};
use super::results::CubeResults;
use crate::diagnose::{GAIN_T, MIN_GAIN, RIVAL_T};
use crate::identify::set_options;
use std::fmt::Write;

impl CubeResults {
    /// The report, in markdown.
    pub fn markdown(&self) -> String {
        let mut out = String::new();
        let _ = self.write_markdown(&mut out);
        out
    }

    fn write_markdown(&self, out: &mut String) -> std::fmt::Result {
        writeln!(out, "# hcm reproduce {}\n", self.name)?;
        let stride = match self.fit_stride {
            0 | 1 => String::new(),
            k => format!(
                " The fits (the GA's, the polish's, the diagnosis' candidates') see every \
                 {k}th toss of their part; every toss of the other is predicted and judged."
            ),
        };
        writeln!(
            out,
            "Scenario `{}`, tosses `{}`{}: {} training tosses (even toss numbers), {} held out \
             (odd), never seen by the fit. GA seed {}, population {}, {} generations, polish {} \
             evaluations. A second fold fits the same way on the odd tosses and predicts the \
             even ones: the *cross-validated* rows score every toss with the fit that never \
             saw it.{stride}\n",
            self.scenario,
            self.data,
            self.first
                .map_or(String::new(), |n| format!(" (first {n} runs)")),
            self.training_tosses,
            self.held_out_tosses,
            self.seed,
            self.population,
            self.generations,
            self.polish
        )?;
        self.write_scores(out)?;
        self.write_fit(out)?;
        self.write_phases(out)?;
        self.write_diagnosis(out)?;
        self.write_forecast(out)?;
        self.write_faces(out)?;
        writeln!(out, "## Timings\n\n| stage | wall clock (s) |\n|---|---|")?;
        for t in &self.timings {
            writeln!(out, "| {} | {:.1} |", t.stage, t.seconds)?;
        }
        let total: f64 = self.timings.iter().map(|t| t.seconds).sum();
        writeln!(out, "| total | {total:.1} |")
    }

    fn write_forecast(&self, out: &mut String) -> std::fmt::Result {
        if let Some(f) = &self.forecast {
            f.write_markdown(out)?;
        }
        match &self.cross_validated {
            Some(cv) => cv.write_markdown(self.forecast.as_ref(), out),
            None => Ok(()),
        }
    }

    fn write_faces(&self, out: &mut String) -> std::fmt::Result {
        let Some(faces) = &self.faces else {
            return Ok(());
        };
        let s = &faces.held_out;
        let tried: Vec<String> = (faces.calibration.iter())
            .map(|(scatter, brier)| format!("{scatter}: {brier:.4}"))
            .collect();
        writeln!(
            out,
            "## Final faces\n\nThe face each held-out toss ends on, forecast by ensembles of {} \
             replays of the fitted model from start states drawn with their free-flight fits' \
             covariance and the contact's stiffness, damping and friction scattered by σ = {} \
             (chosen on the training tosses; mean Brier score per σ: {}).\n",
            s.members,
            faces.scatter,
            tried.join(", ")
        )?;
        writeln!(
            out,
            "| held out | right face: replay | ensemble's most probable | Brier: replay | ensemble | \
             gain, 95 % | log-likelihood: replay | ensemble |\n|---|---|---|---|---|---|---|---|"
        )?;
        writeln!(
            out,
            "| {} tosses | {} | {} | {:.4} | {:.4} | {:+.4} ± {:.4} | {:.4} | {:.4} |\n",
            s.tosses,
            s.replay_right,
            s.ensemble_right,
            s.brier.0,
            s.brier.1,
            s.brier_gain[0],
            s.brier_gain[1],
            s.log_likelihood.0,
            s.log_likelihood.1
        )
    }

    fn write_scores(&self, out: &mut String) -> std::fmt::Result {
        writeln!(
            out,
            "## Scores\n\nPosition error: mean over a toss's window frames of |p_pred − p| in % \
             of the body's width; rotation error: mean of the angle of R_predᵀ·R (°) — for a \
             mechanism each link's, then their mean; then mean ± standard deviation and median \
             over tosses.\n"
        )?;
        writeln!(
            out,
            "| tosses | model | position error (%): mean ± std | median | rotation error (°): mean ± std | median |\n|---|---|---|---|---|---|"
        )?;
        for r in &self.scores {
            let (p, q) = (&r.position, &r.rotation);
            writeln!(
                out,
                "| {} ({}) | {} | {:.2} ± {:.2} | {:.2} | {:.2} ± {:.2} | {:.2} |",
                r.part, p.count, r.model, p.mean, p.std, p.median, q.mean, q.std, q.median
            )?;
        }
        for p in &self.published {
            writeln!(
                out,
                "| all 550, in-sample (published, quoted second-hand) | {} | {:.1} ± {:.1} | – | {:.1} ± {:.1} | – |",
                p.simulator, p.position[0], p.position[1], p.rotation[0], p.rotation[1]
            )?;
        }
        if self.published.is_empty() {
            return writeln!(out);
        }
        writeln!(
            out,
            "\nThe published rows are quoted second-hand, not confirmed from the paper: \
             simulators fitted and scored on all 550 tosses of the data set (in-sample); ours \
             are scored on tosses the fit never saw: the held-out rows on the odd tosses, the \
             cross-validated rows on all of them.\n"
        )
    }

    fn write_fit(&self, out: &mut String) -> std::fmt::Result {
        let f = &self.fit;
        writeln!(
            out,
            "## The fit\n\nTraining fitness (mean position % + mean rotation °): {:.4} with the \
             scenario's parameters, {:.4} after the GA, {:.4} after the polish ({} replays of \
             the training tosses).\n",
            f.start_fitness, f.genetic_fitness, f.fitness, f.evaluations
        )?;
        writeln!(
            out,
            "| parameter | fitted value (SI) | second fold (fitted on the odd tosses) |\n|---|---|---|"
        )?;
        for ((name, value), (_, second)) in f.parameters.iter().zip(&self.second_fit.parameters) {
            writeln!(out, "| {name} | {value:.6e} | {second:.6e} |")?;
        }
        writeln!(
            out,
            "\n`physics.toml` holds the law and the friction, and as its `sets` the table offset \
             and the inertia (`{sets}`), which `--physics` applies:\n\n```\nhcm predict \
             --scenario scenarios/{file} --physics physics.toml --data held_out.csv \
             --out predicted.csv\n```\n",
            sets = set_options(&self.sets),
            file = format_args!("{}.toml", self.name.replace('-', "_"))
        )
    }

    fn write_phases(&self, out: &mut String) -> std::fmt::Result {
        writeln!(
            out,
            "## Where the held-out error is\n\nPhases from the recorded poses alone: *flight* \
             before the centre first comes within the circumscribed radius of the table; \
             *first impact* from there to {IMPACT_AFTER} frames after the recorded centre \
             stops falling; *settling* from the first frame after which the recorded centre \
             moves less than {:.0} % of the width and turns less than {REST_ANGLE}° over every \
             {REST_SPAN} frames ahead; *sliding/tumbling* between. Means over the phase's \
             frames of every held-out toss; share = the phase's part of the error summed over \
             all frames. `error_position.svg` and `error_rotation.svg` show the error over \
             time.\n",
            100.0 * REST_DISTANCE
        )?;
        writeln!(
            out,
            "| phase | tosses | frames | fitted: position (%) | rotation (°) | share (position, rotation) | scenario's: position (%) | rotation (°) |\n|---|---|---|---|---|---|---|---|"
        )?;
        let (fitted, scenario) = (&self.timeline.fitted.phases, &self.timeline.scenario.phases);
        for (f, s) in fitted.iter().zip(scenario) {
            writeln!(
                out,
                "| {} | {} | {} | {:.2} | {:.2} | {:.0} %, {:.0} % | {:.2} | {:.2} |",
                f.phase.label(),
                f.tosses,
                f.frames,
                f.position,
                f.rotation,
                100.0 * f.position_share,
                100.0 * f.rotation_share,
                s.position,
                s.rotation
            )?;
        }
        writeln!(out)
    }

    fn write_diagnosis(&self, out: &mut String) -> std::fmt::Result {
        let Some(d) = &self.diagnosis else {
            return writeln!(out, "## Diagnosis\n\nSkipped (`--no-diagnosis`).\n");
        };
        writeln!(
            out,
            "## What the fitted model still gets wrong (diagnose-motion)\n\nEach candidate \
             fitted on the {} training tosses, judged on the {} held-out ones by its gain \
             (the model's score minus the candidate's, % + ° per toss); it helps at t ≥ \
             {GAIN_T} and a gain ≥ {:.0} % of the model's held-out score, and is named if it \
             beats every other helping one by t ≥ {RIVAL_T}.\n",
            d.training_tosses,
            d.held_out_tosses,
            100.0 * MIN_GAIN
        )?;
        for (k, round) in d.rounds.iter().enumerate() {
            writeln!(
                out,
                "Round {}: the model scores {:.3} (training), {:.3} (held out).\n\n| candidate | fitted values | held-out gain: mean ± se | 95 % interval | t | helps |\n|---|---|---|---|---|---|",
                k + 1,
                round.training,
                round.held_out
            )?;
            for c in &round.candidates {
                let values: Vec<String> = (c.parameters.iter())
                    .map(|(n, v)| format!("{n} = {v:.4e}"))
                    .collect();
                writeln!(
                    out,
                    "| {} | {} | {:.4} ± {:.4} | {:.4} to {:.4} | {:.1} | {} |",
                    c.name,
                    values.join(", "),
                    c.gain.mean,
                    c.gain.standard_error,
                    c.gain.interval[0],
                    c.gain.interval[1],
                    c.gain.t(),
                    if c.helps { "yes" } else { "no" }
                )?;
            }
            writeln!(out)?;
        }
        writeln!(out, "**Answer:** {}\n", d.answer)
    }
}
