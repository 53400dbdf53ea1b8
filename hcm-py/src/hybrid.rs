//! The hybrid contact model (paper Section 3.2, Eq 12) evaluated over many contact
//! states in one call, through the core in f32: the arithmetic a controller runs
//! (`ContactModel::normal_force`, the residual's envelope rule included), with the
//! physics of a scenario's contact (after `with_physics`) and an exported blob.

use crate::errors::{hcm_error, message};
use crate::laws::equal_lengths;
use crate::scenario::Scenario;
use hcm_core::effect::{ContactMemory, ExtendedLaw};
use hcm_core::law::Indentation;
use hcm_core::model::{ContactModel, Evaluated, Residual};
use hcm_host::residual::{ContactResidual, Stored, HIDDEN, INPUTS, WIDTH};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

/// The physics of one contact plus its decoded 1D force residual (3-16-16-1).
#[pyclass(module = "hcm._hcm", frozen)]
pub struct HybridModel {
    physics: ExtendedLaw<f32>,
    residual: Stored<INPUTS, WIDTH, 1, HIDDEN>,
}

/// What one batch evaluation returns: the hybrid force, the physics alone (N), and
/// whether the residual took part, per state.
type Forces<'py> = (
    Bound<'py, PyArray1<f32>>,
    Bound<'py, PyArray1<f32>>,
    Bound<'py, PyArray1<bool>>,
);

#[pymethods]
impl HybridModel {
    /// Contact `contact` of `scenario` (its law and effects, cast to f32) with the
    /// residual in `blob` (an `hcm export` file's bytes, f32 or int8 weights).
    #[new]
    fn new(scenario: &Scenario, blob: &[u8], contact: usize) -> PyResult<Self> {
        let model = scenario.model()?;
        let c = &model.contacts[model.check_contact(contact).map_err(message)?];
        let residual = match ContactResidual::decode(blob).map_err(hcm_error)? {
            ContactResidual::Force(stored) => stored,
            other => {
                return Err(message(format!(
                    "the blob holds a {} network; the hybrid normal force takes the 1D \
                     contact's {INPUTS}-{WIDTH}-{WIDTH}-1 network (`hcm train` on force data)",
                    other.shape()
                )))
            }
        };
        Ok(HybridModel {
            physics: c.model.normal.cast::<f32>(),
            residual,
        })
    }

    /// Normal force (N) at indentations `depth` δ (m), rates `rate` δ̇ (m/s) and
    /// approach speeds δ̇0 (m/s), element-wise (equal lengths, f32), each a fresh
    /// contact (touch-down memory). NaN in gives NaN out, never an error.
    fn force<'py>(
        &self,
        py: Python<'py>,
        depth: PyReadonlyArray1<'py, f32>,
        rate: PyReadonlyArray1<'py, f32>,
        approach_speed: PyReadonlyArray1<'py, f32>,
    ) -> PyResult<Forces<'py>> {
        let (depth, rate, approach) = (
            depth.as_slice()?,
            rate.as_slice()?,
            approach_speed.as_slice()?,
        );
        let n = equal_lengths(&[depth.len(), rate.len(), approach.len()])?;
        let mut force = vec![0.0f32; n];
        let mut physics = vec![0.0f32; n];
        let mut used = vec![false; n];
        py.detach(|| match &self.residual {
            Stored::F32(mlp) => self.fill(
                mlp.as_ref(),
                [depth, rate, approach],
                [&mut force, &mut physics],
                &mut used,
            ),
            Stored::Int8(mlp) => self.fill(
                mlp.as_ref(),
                [depth, rate, approach],
                [&mut force, &mut physics],
                &mut used,
            ),
        });
        Ok((
            PyArray1::from_vec(py, force),
            PyArray1::from_vec(py, physics),
            PyArray1::from_vec(py, used),
        ))
    }

    /// Whether the residual's weights are int8 (else f32).
    #[getter]
    fn int8(&self) -> bool {
        matches!(self.residual, Stored::Int8(_))
    }
}

impl HybridModel {
    /// Evaluates every state with `residual` (the core's loop body, one state at a time).
    fn fill<R: Residual<f32>>(
        &self,
        residual: &R,
        [depth, rate, approach]: [&[f32]; 3],
        [force, physics]: [&mut [f32]; 2],
        used: &mut [bool],
    ) {
        let model = ContactModel::physics(self.physics.clone()).with_residual(residual);
        let memory = ContactMemory::touch_down();
        for i in 0..force.len() {
            let state = Indentation {
                depth: depth[i],
                rate: rate[i],
                approach_speed: approach[i],
            };
            let input = [depth[i], rate[i], approach[i]];
            let (f, evaluated) = model.normal_force(&state, &memory, &input);
            force[i] = f;
            physics[i] = model.physics_normal_force(&state, &memory);
            used[i] = evaluated == Evaluated::PhysicsAndResidual;
        }
    }
}
