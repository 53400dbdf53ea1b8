//! Which fitted parameters the filmed motion fixes (each said where the data
//! cannot fix it). Each parameter is moved from the fit, the
//! others held, by [`STEP`] (a factor on a log-scaled parameter, a share of the box on
//! a linear one), both ways within its box; the training fitness it costs, the smaller
//! of the two, is its *rise*. A parameter whose rise stays under [`LOOSE`] of the
//! fitness is not fixed by the data: a ball that rolls without slipping after each
//! bounce says nothing of its friction coefficient beyond "enough to roll".

use crate::numerics::optimize::Bound;

/// How far each parameter is moved: ×/÷ 1.25 on a log scale, ±10 % of its box on a
/// linear one (–).
pub const STEP: (f64, f64) = (1.25, 0.1);

/// Rise of the fitness, as a share of it, below which a parameter is not fixed (–).
pub const LOOSE: f64 = 0.01;

/// One parameter's probe.
#[derive(Clone, Debug, PartialEq)]
pub struct Sensitivity {
    /// Parameter name.
    pub name: String,
    /// The smaller training-fitness rise of the two moves (% + °); +∞ where neither
    /// move fits in the box.
    pub rise: f64,
    /// Whether the data leave it loose: `rise` < [`LOOSE`] × the fitness.
    pub loose: bool,
    /// Whether the fit ended within [`AT_BOUND`] of its box's width (log width on a log
    /// scale) from a bound: the data may want it beyond.
    pub at_bound: bool,
}

/// Share of the box's width within which a value counts as at its bound (–).
pub const AT_BOUND: f64 = 1e-3;

/// Whether `value` lies within [`AT_BOUND`] of the box's width from one of its ends.
fn at_bound(bound: &Bound, value: f64) -> bool {
    let (lower, upper, x) = if bound.log_scale {
        (bound.lower.ln(), bound.upper.ln(), value.ln())
    } else {
        (bound.lower, bound.upper, value)
    };
    let margin = AT_BOUND * (upper - lower);
    x <= lower + margin || x >= upper - margin
}

/// The probes of every gene of `best` (fitness `fitness`) in `bounds`, `score` being
/// the training fitness; `names` are the genes' names as the fit reports them. Costs
/// two fitness evaluations per gene.
pub fn probe(
    bounds: &[Bound],
    names: &[String],
    best: &[f64],
    fitness: f64,
    score: impl Fn(&[f64]) -> f64,
) -> Vec<Sensitivity> {
    (bounds.iter().enumerate())
        .map(|(i, bound)| {
            let moves = if bound.log_scale {
                [best[i] * STEP.0, best[i] / STEP.0]
            } else {
                let step = STEP.1 * (bound.upper - bound.lower);
                [best[i] + step, best[i] - step]
            };
            let rise = (moves.iter())
                .map(|&x| x.clamp(bound.lower, bound.upper))
                .filter(|&x| x != best[i])
                .map(|x| {
                    let mut genes = best.to_vec();
                    genes[i] = x;
                    score(&genes) - fitness
                })
                .fold(f64::INFINITY, f64::min);
            Sensitivity {
                name: names.get(i).cloned().unwrap_or_else(|| bound.name.clone()),
                rise,
                loose: rise < LOOSE * fitness.abs(),
                at_bound: at_bound(bound, best[i]),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gene_the_score_ignores_is_loose_and_one_it_reads_is_not() {
        let bounds = [
            Bound::of_row(&("felt", 0.0, 10.0, false)),
            Bound::of_row(&("ignored", 1e-3, 1e3, true)),
        ];
        let names = ["felt".to_owned(), "ignored".to_owned()];
        let score = |g: &[f64]| 1.0 + (g[0] - 5.0).powi(2);
        let found = probe(&bounds, &names, &[5.0, 1.0], 1.0, score);
        assert!(
            !found[0].loose && (found[0].rise - 1.0).abs() < 1e-12,
            "{found:?}"
        );
        assert!(found[1].loose && found[1].rise == 0.0, "{found:?}");
        assert!(!found[0].at_bound && !found[1].at_bound);
        let ends = probe(&bounds, &names, &[10.0, 1e3], 1.0, score);
        assert!(ends[0].at_bound && ends[1].at_bound, "{ends:?}");
    }
}
