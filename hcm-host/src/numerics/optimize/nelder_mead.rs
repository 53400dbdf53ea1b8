//! The local polish after the genetic algorithm: Nelder–Mead's downhill simplex on the
//! genes normalised to [0, 1] over their box (through log(value) where the box is
//! log-scaled), every point clamped into it. The fitness of a toss replay has no
//! gradient worth differencing (a frame's score jumps when a bounce moves by one
//! frame), so a derivative-free method is used; its steps are deterministic, so the
//! same start gives the same result.

use super::{Bound, Observer};

/// Reflection, expansion, contraction and shrink coefficients (the standard ones).
const REFLECT: f64 = 1.0;
const EXPAND: f64 = 2.0;
const CONTRACT: f64 = 0.5;
const SHRINK: f64 = 0.5;

/// The first simplex's edge in normalised genes (–): 5 % of each interval.
const FIRST_STEP: f64 = 0.05;

/// What the polish found.
#[derive(Clone, Debug, PartialEq)]
pub struct Polished {
    /// Best values (the bounds' units).
    pub(crate) best: Vec<f64>,
    /// Their fitness.
    pub(crate) fitness: f64,
    /// Fitness evaluations made.
    pub(crate) evaluations: usize,
}

/// Minimises `fitness` from `start` (inside `bounds`, fitness `start_fitness`) until
/// fewer than two of `budget` evaluations remain (a last shrink may take n more);
/// `progress(evaluations, best)` after each step.
pub fn polish(
    bounds: &[Bound],
    start: &[f64],
    start_fitness: f64,
    budget: usize,
    fitness: impl Fn(&[f64]) -> f64,
    mut progress: impl Observer,
) -> Polished {
    let evaluations = std::cell::Cell::new(0);
    let mut evaluate = |genes: &[f64]| {
        let values: Vec<f64> = bounds
            .iter()
            .zip(genes)
            .map(|(b, &g)| b.value_at(g))
            .collect();
        let f = fitness(&values);
        evaluations.set(evaluations.get() + 1);
        if f.is_nan() {
            f64::INFINITY
        } else {
            f
        }
    };
    let origin: Vec<f64> = bounds
        .iter()
        .zip(start)
        .map(|(b, &v)| b.fraction_of(v))
        .collect();
    let mut simplex: Vec<(Vec<f64>, f64)> = vec![(origin.clone(), start_fitness)];
    for i in 0..origin.len() {
        if evaluations.get() >= budget {
            break;
        }
        let mut vertex = origin.clone();
        // Step inwards at the upper bound, so the vertex differs from the origin.
        vertex[i] += if vertex[i] + FIRST_STEP <= 1.0 {
            FIRST_STEP
        } else {
            -FIRST_STEP
        };
        let f = evaluate(&vertex);
        simplex.push((vertex, f));
        progress.step(evaluations.get(), best_of(&simplex));
    }
    while evaluations.get() + 2 <= budget && simplex.len() == origin.len() + 1 {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        step(&mut simplex, &mut evaluate);
        progress.step(evaluations.get(), best_of(&simplex));
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    let (genes, fitness) = simplex.swap_remove(0);
    Polished {
        best: bounds
            .iter()
            .zip(&genes)
            .map(|(b, &g)| b.value_at(g))
            .collect(),
        fitness,
        evaluations: evaluations.get(),
    }
}

/// The best fitness of a simplex.
fn best_of(simplex: &[(Vec<f64>, f64)]) -> f64 {
    simplex.iter().map(|v| v.1).fold(f64::INFINITY, f64::min)
}

/// One Nelder–Mead step on a simplex sorted best first: reflect the worst vertex
/// through the others' centroid, then expand, contract or shrink.
fn step(simplex: &mut [(Vec<f64>, f64)], evaluate: &mut impl FnMut(&[f64]) -> f64) {
    let n = simplex.len() - 1;
    let centroid: Vec<f64> = (0..n)
        .map(|i| simplex[..n].iter().map(|v| v.0[i]).sum::<f64>() / n as f64)
        .collect();
    let toward = |scale: f64, from: &[f64]| -> Vec<f64> {
        (centroid.iter().zip(from))
            .map(|(c, x)| (c + scale * (c - x)).clamp(0.0, 1.0))
            .collect()
    };
    let worst = simplex[n].clone();
    let reflected = toward(REFLECT, &worst.0);
    let f_reflected = evaluate(&reflected);
    if f_reflected < simplex[0].1 {
        let expanded = toward(EXPAND, &worst.0);
        let f_expanded = evaluate(&expanded);
        simplex[n] = if f_expanded < f_reflected {
            (expanded, f_expanded)
        } else {
            (reflected, f_reflected)
        };
    } else if f_reflected < simplex[n - 1].1 {
        simplex[n] = (reflected, f_reflected);
    } else {
        let contracted = toward(-CONTRACT, &worst.0);
        let f_contracted = evaluate(&contracted);
        if f_contracted < worst.1 {
            simplex[n] = (contracted, f_contracted);
        } else {
            let best = simplex[0].0.clone();
            for vertex in simplex[1..].iter_mut() {
                vertex.0 = (best.iter().zip(&vertex.0))
                    .map(|(b, x)| b + SHRINK * (x - b))
                    .collect();
                vertex.1 = evaluate(&vertex.0);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_polish_finds_the_minimum_of_a_bowl() {
        let bounds = [
            Bound {
                name: "a".into(),
                lower: -1.0,
                upper: 1.0,
                log_scale: false,
            },
            Bound {
                name: "b".into(),
                lower: 1e-2,
                upper: 1e2,
                log_scale: true,
            },
        ];
        let bowl = |x: &[f64]| (x[0] - 0.3).powi(2) + (x[1].ln() - 2f64.ln()).powi(2);
        let start = [0.0, 1.0];
        let found = polish(&bounds, &start, bowl(&start), 200, bowl, |_, _| {});
        assert!((found.best[0] - 0.3).abs() < 1e-3, "{found:?}");
        assert!((found.best[1] - 2.0).abs() < 1e-2, "{found:?}");
        assert!(found.evaluations <= 200);
    }
}
