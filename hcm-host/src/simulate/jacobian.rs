//! The system's Jacobian for the linearly implicit steps taken where the run is
//! stiff ([`hcm_core::integrate::Rodas4`]): ∂f/∂y by central differences over the
//! moving bodies' components, W = d·I − J factored by LU with partial pivoting.
//!
//! Why: STEP friction's slope μ_s·f_n/v_s at stiction (Eq 10–11) gives the slip a
//! decay rate far beyond the motion's own (the shipped peg's landing on two points at
//! v_s = 0.1 mm/s: ~10⁷ /s), which an explicit step must resolve; a step that solves
//! with W does not. The contacts' impulse integrals feed nothing back, so their
//! columns are zero and are not differenced.
//!
//! RODAS needs J accurate (it is not a W-method): with one-sided differences
//! (increment √(10⁻¹⁶·|y|)) the landing took 1 437 steps, with central ones 1 095 —
//! and with increments near v_s the truncation error of the STEP law's curvature made
//! it thrash (13 000 steps). Measured increments u·max(10⁻⁵, |y|) with u from 10⁻²⁴ to
//! 10⁻²⁰ under the cube root all gave 1 095–1 117 steps; 10⁻²² is their middle.

use super::layout::StateVector;
use super::system::RigidSystem;
use hcm_core::integrate::{LinearlyImplicit, OdeSystem};
use nalgebra::{DMatrix, DVector, DVectorViewMut, Dyn, LU};

/// The central-difference increment is ∛(u·max(10⁻⁵, |yⱼ|)) in yⱼ's unit: u (that
/// unit squared) balances the truncation error against roundoff for the peg (module doc).
const ROUNDOFF: f64 = 1e-22;

/// The kept Jacobian, its factored W and the working space of the differences.
#[derive(Clone, Debug, Default)]
pub struct Linearisation {
    jacobian: DMatrix<f64>,
    factored: Option<LU<f64, Dyn, Dyn>>,
    /// Working states: the perturbed point and f just above and below it.
    probe: Option<[StateVector; 3]>,
}

impl<const JOINT_PATH: bool> LinearlyImplicit<f64, StateVector> for RigidSystem<'_, JOINT_PATH> {
    fn jacobian(
        &mut self,
        time: f64,
        state: &StateVector,
        _rate: &StateVector,
        time_rate: &mut StateVector,
    ) {
        // The equations do not read the time.
        time_rate.0.fill(0.0);
        let n = state.0.len();
        let [mut probe, mut above, mut below] = self
            .linear
            .probe
            .take()
            .unwrap_or_else(|| [state.clone(), state.clone(), state.clone()]);
        probe.0.clone_from(&state.0);
        let mut jacobian = std::mem::take(&mut self.linear.jacobian);
        jacobian.resize_mut(n, n, 0.0);
        jacobian.fill(0.0);
        for j in 0..self.layout.body_components() {
            let y = state.0[j];
            let step = (ROUNDOFF * y.abs().max(1e-5)).cbrt();
            probe.0[j] = y + step;
            let up = probe.0[j];
            self.derivative(time, &probe, &mut above);
            probe.0[j] = y - step;
            // The increments as represented, so the quotient is exact in them.
            let span = up - probe.0[j];
            self.derivative(time, &probe, &mut below);
            probe.0[j] = y;
            for i in 0..n {
                jacobian[(i, j)] = (above.0[i] - below.0[i]) / span;
            }
        }
        self.linear.jacobian = jacobian;
        self.linear.probe = Some([probe, above, below]);
    }

    fn factor(&mut self, diagonal: f64) -> bool {
        let j = &self.linear.jacobian;
        let w = DMatrix::from_fn(j.nrows(), j.ncols(), |r, c| {
            let d = if r == c { diagonal } else { 0.0 };
            d - j[(r, c)]
        });
        let finite = w.iter().all(|x| x.is_finite());
        let lu = w.lu();
        let ok = finite && lu.is_invertible();
        self.linear.factored = ok.then_some(lu);
        ok
    }

    fn solve(&self, rhs: &mut StateVector) {
        if let Some(lu) = &self.linear.factored {
            let n = rhs.0.len();
            let mut view = DVectorViewMut::from_slice(&mut rhs.0, n);
            lu.solve_mut(&mut view);
        }
    }
}

impl<const JOINT_PATH: bool> RigidSystem<'_, JOINT_PATH> {
    /// An estimate of the spectral radius of the kept Jacobian (1/s): the growth
    /// ‖Jᵏx‖ per power from k = 8 to 16 (a ratio of powers, so a dominant complex pair
    /// — a contact's oscillation — counts by its modulus too). 0 before any Jacobian.
    pub(super) fn spectral_radius(&self) -> f64 {
        let j = &self.linear.jacobian;
        let n = j.nrows();
        if n == 0 {
            return 0.0;
        }
        let mut x = DVector::from_element(n, 1.0 / (n as f64).sqrt());
        let mut log_growth = 0.0;
        for k in 1..=POWERS {
            x = j * x;
            let norm = x.norm();
            if !(norm > 0.0 && norm.is_finite()) {
                return if norm == 0.0 { 0.0 } else { f64::INFINITY };
            }
            x /= norm;
            if k > POWERS / 2 {
                log_growth += norm.ln();
            }
        }
        (log_growth / (POWERS / 2) as f64).exp()
    }
}

/// Powers of J in the spectral-radius estimate.
const POWERS: usize = 16;
