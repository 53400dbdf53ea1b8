//! The contact-frame residual's training rows (`hcm_core::model::point_residual`):
//! at every measured sample where the moving body touches the other, each touching
//! point's five contact-frame features with its lever — the wrench on the moving body
//! each of its five unit outputs makes there — and, as the row's target, the wrench
//! PM2 misses on the body (measured − PM2, world frame, torque about its centre of
//! mass), the same target as the body-state residual's ([`super::wrench_pairs`]).
//!
//! The lever is computed by the core's own assembly, so training weighs each output
//! exactly as the simulation and the controller apply it: the normal output k_n's as
//! δ times the wrench one more newton of normal force makes at the point under PM2's
//! friction law (`point_force_with`, Eq 1's `point_wrench`), the friction scale r_f's
//! as the law's own friction force there, the motion's coefficients' from
//! `tangential_correction`. A torque channel the data lack is neither a target nor
//! a lever row: nothing is learned from it.

use super::summed::SummedRow;
use super::wrench_samples::WrenchSampleError;
use crate::dataset::Dataset;
use crate::identify::{RecordedContact, RecordedSample};
use crate::residual::HostContactModel;
use crate::scenario::Model;
use hcm_core::model::point_residual::{point_features, tangential_correction};
use hcm_core::model::{point_wrench, ContactPoint, PointForce, POINT_OUTPUTS};

/// Each row's run (its index in the data) and time (s).
pub type RowTimes = Vec<(usize, f64)>;

/// The training rows of contact `c` of `physics` (PM2; its residual, if any, left out)
/// from the measured `data`, with each row's run and time.
pub fn point_rows(
    physics: &Model,
    data: &Dataset,
    c: usize,
) -> Result<(Vec<SummedRow>, RowTimes), WrenchSampleError> {
    // Per point, the correction acts on both bodies alike: any pair the rows can be
    // read for (one moving body against a fixed one, or two moving bodies) trains.
    if c >= physics.contacts.len() {
        return Err(WrenchSampleError::NoSuchContact(c));
    }
    let mut model = physics.clone();
    model.contacts[c].model.residual = None;
    let recorded = RecordedContact::from_data(&model, data, c)
        .map_err(|e| WrenchSampleError::Recorded(e.to_string()))?;
    let mut rows = Vec::with_capacity(recorded.samples.len());
    let mut at = Vec::with_capacity(recorded.samples.len());
    for sample in &recorded.samples {
        let got = recorded.predicted(&model, sample);
        rows.push(row(&model.contacts[c].model, &recorded, sample, &got));
        at.push((sample.run, sample.time));
    }
    Ok((rows, at))
}

/// One sample's row: its touching points, and measured − `predicted` as the target
/// (0 with a zero lever row where a channel is not measured).
fn row(
    pm2: &HostContactModel,
    recorded: &RecordedContact,
    sample: &RecordedSample,
    predicted: &[f64; 6],
) -> SummedRow {
    let measured: Vec<bool> = sample.measured.iter().map(|m| m.is_finite()).collect();
    let target = (0..6)
        .map(|k| {
            let d = sample.measured[k] - predicted[k];
            if measured[k] && d.is_finite() {
                d
            } else {
                0.0
            }
        })
        .collect();
    let mut points = touching_points(pm2, recorded, sample);
    for (_, lever) in &mut points {
        for (k, _) in measured.iter().enumerate().filter(|(_, m)| !**m) {
            lever[k * POINT_OUTPUTS..(k + 1) * POINT_OUTPUTS].fill(0.0);
        }
    }
    SummedRow { points, target }
}

/// Each touching point of `sample`: its five features and its lever under `pm2` (the
/// wrench on the mover of each unit output, row-major [wrench component][output]).
pub(crate) fn touching_points(
    pm2: &HostContactModel,
    recorded: &RecordedContact,
    sample: &RecordedSample,
) -> Vec<(Vec<f64>, Vec<f64>)> {
    (sample.points.iter())
        .filter(|p| p.indentation.depth > 0.0)
        .map(|p| (point_features(p).to_vec(), lever(pm2, recorded, sample, p)))
        .collect()
}

/// The wrench on the mover (force x, y, z, torque x, y, z) of each unit output at
/// `point` under `pm2`, row-major [wrench component][output].
fn lever(
    pm2: &HostContactModel,
    recorded: &RecordedContact,
    sample: &RecordedSample,
    point: &ContactPoint<f64>,
) -> Vec<f64> {
    let [r1, r2] = &sample.references;
    let on_mover = |force: &PointForce<f64>| -> [f64; 6] {
        let w = point_wrench(point, force, r1, r2);
        let (f, t) = if recorded.mover_is_1() {
            (w.force_1, w.torque_1)
        } else {
            (w.force_2, w.torque_2)
        };
        [f.x, f.y, f.z, t.x, t.y, t.z]
    };
    let mut columns = [[0.0; 6]; POINT_OUTPUTS];
    // k_n: δ × (the wrench of one more newton of normal force, friction following).
    let law = pm2.point_force(point);
    let physics = law.normal_force;
    let (more, now) = (
        on_mover(&pm2.point_force_with(point, physics + 1.0)),
        on_mover(&law),
    );
    for (column, (more, now)) in columns[0].iter_mut().zip(more.iter().zip(&now)) {
        *column = (more - now) * point.indentation.depth;
    }
    // r_f: the friction law's own force at PM2's normal force.
    if let Some(law) = &pm2.friction {
        columns[1] = on_mover(&PointForce {
            normal_force: 0.0,
            friction: law.force(&point.relative_velocity, &point.normal, physics),
            couple: nalgebra::Vector3::zeros(),
        });
    }
    for (k, column) in columns.iter_mut().enumerate().skip(2) {
        let mut unit = [0.0; POINT_OUTPUTS];
        unit[k] = 1.0;
        let (friction, couple) = tangential_correction(point, &unit);
        *column = on_mover(&PointForce {
            normal_force: 0.0,
            friction,
            couple,
        });
    }
    let mut lever = vec![0.0; 6 * POINT_OUTPUTS];
    for (k, column) in columns.iter().enumerate() {
        for (component, value) in column.iter().enumerate() {
            lever[component * POINT_OUTPUTS + k] = *value;
        }
    }
    lever
}
