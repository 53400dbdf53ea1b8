//! The scenario keys of rigid bodies in 3D: orientation, inertia, boxes and compound
//! bodies, and a contact's friction — as written, and checked into what the
//! simulator uses.

use super::exact::exactly;
use hcm_core::friction::VelocityStepFriction;
use nalgebra::{Matrix3, Quaternion, SymmetricEigen, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// An orientation (body → world) as a scenario writes it: one of
/// `{ quaternion = [w, x, y, z] }` or `{ roll_pitch_yaw = [roll, pitch, yaw] }`.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(try_from = "OrientationTable")]
pub enum OrientationSpec {
    /// A quaternion `[w, x, y, z]` (–), normalised on load.
    Quaternion([f64; 4]),
    /// Angles `[roll, pitch, yaw]` (rad) of R = Rz(yaw)·Ry(pitch)·Rx(roll): rotations
    /// about the fixed world axes x, then y, then z.
    RollPitchYaw([f64; 3]),
}

/// An inertia tensor (kg·m², about the centre of mass, body frame) as written.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(try_from = "InertiaTable")]
pub enum InertiaSpec {
    /// Principal moments `[Ixx, Iyy, Izz]` (kg·m²) along the body axes.
    Principal([f64; 3]),
    /// The full symmetric tensor, row by row (kg·m²).
    Full([[f64; 3]; 3]),
}

/// An orientation table as read, before exactly one form is chosen.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OrientationTable {
    quaternion: Option<Vec<f64>>,
    roll_pitch_yaw: Option<Vec<f64>>,
}

impl TryFrom<OrientationTable> for OrientationSpec {
    type Error = String;

    fn try_from(table: OrientationTable) -> Result<Self, String> {
        match (table.quaternion, table.roll_pitch_yaw) {
            (Some(q), None) => exactly::<4>(&q)
                .map(OrientationSpec::Quaternion)
                .map_err(|e| format!("quaternion [w, x, y, z]: {e}")),
            (None, Some(a)) => exactly::<3>(&a)
                .map(OrientationSpec::RollPitchYaw)
                .map_err(|e| format!("roll_pitch_yaw [roll, pitch, yaw] (rad): {e}")),
            (Some(_), Some(_)) => Err("orientation gives both `quaternion` and `roll_pitch_yaw`: \
                 keep one of the two forms"
                .into()),
            (None, None) => Err("orientation needs one of `quaternion = [w, x, y, z]` or \
                 `roll_pitch_yaw = [roll, pitch, yaw]` (rad)"
                .into()),
        }
    }
}

/// An inertia as read: a list of numbers or a list of rows.
#[derive(Deserialize)]
#[serde(untagged)]
enum InertiaTable {
    Principal(Vec<f64>),
    Full(Vec<Vec<f64>>),
}

impl TryFrom<InertiaTable> for InertiaSpec {
    type Error = String;

    fn try_from(table: InertiaTable) -> Result<Self, String> {
        const WHAT: &str = "inertia: principal moments [Ixx, Iyy, Izz] or a 3×3 tensor \
            [[Ixx, Ixy, Ixz], [Iyx, Iyy, Iyz], [Izx, Izy, Izz]] (kg·m²)";
        match table {
            InertiaTable::Principal(d) => exactly::<3>(&d)
                .map(InertiaSpec::Principal)
                .map_err(|e| format!("{WHAT}: {e}")),
            InertiaTable::Full(rows) => {
                let checked: Result<Vec<[f64; 3]>, String> =
                    rows.iter().map(|row| exactly::<3>(row)).collect();
                let rows = checked.map_err(|e| format!("{WHAT}: a row {e}"))?;
                <[[f64; 3]; 3]>::try_from(rows.as_slice())
                    .map(InertiaSpec::Full)
                    .map_err(|_| format!("{WHAT}: expected 3 rows, found {}", rows.len()))
            }
        }
    }
}

/// One box of a compound body, placed in the body's frame.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PartSpec {
    /// Half extents along the part's own axes (m).
    #[serde(deserialize_with = "super::exact::array")]
    pub(crate) half_extents: [f64; 3],
    /// Centre of the part relative to the body's reference point, body frame (m).
    #[serde(default, deserialize_with = "super::exact::array")]
    pub(crate) position: [f64; 3],
    /// Orientation of the part relative to the body; default: aligned with it.
    #[serde(default)]
    pub(crate) orientation: Option<OrientationSpec>,
}

/// One box of a compound body, checked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Part {
    /// Half extents (m), each > 0.
    pub(crate) half_extents: Vector3<f64>,
    /// Centre relative to the body's reference point, body frame (m).
    pub(crate) position: Vector3<f64>,
    /// Orientation relative to the body (–).
    pub(crate) orientation: UnitQuaternion<f64>,
}

/// Velocity-based STEP friction (Eq 10–11) as a scenario (or a physics file) writes it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSpec {
    /// Static coefficient μ_s (–), reached at `v_static`.
    pub mu_static: f64,
    /// Dynamic coefficient μ_d (–), from `v_dynamic` on.
    pub mu_dynamic: f64,
    /// Stiction transition speed v_s (m/s).
    pub v_static: f64,
    /// Friction transition speed v_d (m/s), > v_s.
    pub v_dynamic: f64,
}

impl FrictionSpec {
    /// The scenario names of the friction parameters, which a contact's `noise` table
    /// may name beside its law's (Eq 18 on friction): μ_s, μ_d (–), v_s, v_d (m/s).
    pub(crate) const PARAMETERS: [&'static str; 4] =
        ["mu_static", "mu_dynamic", "v_static", "v_dynamic"];

    /// The value of the friction parameter called `name` (a `Self::PARAMETERS` name)
    /// in `law`, for Eq 18's noise.
    pub fn parameter<'a>(
        law: &'a mut VelocityStepFriction<f64>,
        name: &str,
    ) -> Option<&'a mut f64> {
        match name {
            "mu_static" => Some(&mut law.static_coefficient),
            "mu_dynamic" => Some(&mut law.dynamic_coefficient),
            "v_static" => Some(&mut law.stiction_speed),
            "v_dynamic" => Some(&mut law.dynamic_speed),
            _ => None,
        }
    }

    /// The spec of the core's friction law `law`.
    pub fn of(law: &VelocityStepFriction<f64>) -> FrictionSpec {
        FrictionSpec {
            mu_static: law.static_coefficient,
            mu_dynamic: law.dynamic_coefficient,
            v_static: law.stiction_speed,
            v_dynamic: law.dynamic_speed,
        }
    }

    /// The core's friction law, checked (coefficients ≥ 0, 0 < v_s < v_d) and in STEP's
    /// order: the coefficient falls (or stays) from μ_s at v_s to μ_d at v_d, so
    /// μ_d ≤ μ_s, over a transition of some width, v_s < v_d. The core itself accepts
    /// the reverse (a simulated run's Eq 18 scatter may cross them); a user's scenario
    /// that gives it has the two keys swapped.
    pub fn law(&self) -> Result<VelocityStepFriction<f64>, String> {
        if self.mu_dynamic > self.mu_static {
            return Err(format!(
                "mu_dynamic {} is above mu_static {}: STEP friction falls from μ_s when \
                 sticking to μ_d when sliding; give mu_dynamic ≤ mu_static (swapped?)",
                self.mu_dynamic, self.mu_static
            ));
        }
        if self.v_dynamic == self.v_static {
            return Err(format!(
                "v_dynamic {} equals v_static: the STEP from μ_s to μ_d needs a width; give \
                 v_dynamic above v_static (e.g. 10 × v_static)",
                self.v_dynamic
            ));
        }
        let law = VelocityStepFriction {
            static_coefficient: self.mu_static,
            dynamic_coefficient: self.mu_dynamic,
            stiction_speed: self.v_static,
            dynamic_speed: self.v_dynamic,
        };
        // The core names its fields; say them as the scenario spells them.
        law.validate().map_err(|e| {
            [
                ("static_coefficient", "mu_static"),
                ("dynamic_coefficient", "mu_dynamic"),
                ("stiction_speed", "v_static"),
                ("dynamic_speed", "v_dynamic"),
            ]
            .iter()
            .fold(e.to_string(), |m, (core, key)| m.replace(core, key))
        })?;
        Ok(law)
    }
}

/// The orientation of `spec` (identity when absent); a quaternion must be finite and
/// non-zero.
pub(super) fn orientation(spec: Option<&OrientationSpec>) -> Result<UnitQuaternion<f64>, String> {
    match spec {
        None => Ok(UnitQuaternion::identity()),
        Some(OrientationSpec::Quaternion([w, x, y, z])) => {
            let q = Quaternion::new(*w, *x, *y, *z);
            let norm = q.norm();
            if !(norm.is_finite() && norm > 0.0) {
                return Err(format!(
                    "quaternion [{w}, {x}, {y}, {z}] must be finite and non-zero (w, x, y, z)"
                ));
            }
            Ok(UnitQuaternion::from_quaternion(q))
        }
        Some(OrientationSpec::RollPitchYaw([roll, pitch, yaw])) => {
            if ![roll, pitch, yaw].iter().all(|a| a.is_finite()) {
                return Err("roll_pitch_yaw angles must be finite (rad)".into());
            }
            Ok(UnitQuaternion::from_euler_angles(*roll, *pitch, *yaw))
        }
    }
}

/// The inertia tensor (kg·m²): as given, or the uniform solid of the shape of `mass`
/// (kg) with `radius` (sphere, m) or `half_extents` (box, m).
pub(super) fn inertia(
    spec: Option<&InertiaSpec>,
    mass: f64,
    default: Option<Matrix3<f64>>,
) -> Result<Matrix3<f64>, String> {
    let tensor = match spec {
        Some(InertiaSpec::Principal(d)) => Matrix3::from_diagonal(&Vector3::from(*d)),
        Some(InertiaSpec::Full(rows)) => Matrix3::from_fn(|i, j| rows[i][j]),
        None => {
            return default.ok_or_else(|| {
                format!(
                    "is required for this shape (mass {mass} kg): give [Ixx, Iyy, Izz] in kg·m²"
                )
            })
        }
    };
    check_inertia(&tensor)?;
    Ok(tensor)
}

/// A physical inertia tensor: finite, symmetric, positive definite, and its principal
/// moments obey the triangle inequality I1 + I2 ≥ I3 (every rigid mass distribution
/// does).
fn check_inertia(tensor: &Matrix3<f64>) -> Result<(), String> {
    if !tensor.iter().all(|x| x.is_finite()) {
        return Err("must be finite (kg·m²)".into());
    }
    let scale = tensor.abs().max();
    if (tensor - tensor.transpose()).abs().max() > 1e-9 * scale {
        return Err("must be symmetric".into());
    }
    let mut moments = SymmetricEigen::new(*tensor).eigenvalues;
    moments.as_mut_slice().sort_by(f64::total_cmp);
    if moments[0] <= 0.0 {
        return Err(format!(
            "must be positive definite; its principal moments are {moments:?} kg·m²"
        ));
    }
    if moments[0] + moments[1] < moments[2] * (1.0 - 1e-9) {
        return Err(format!(
            "principal moments {:.4e}, {:.4e}, {:.4e} kg·m² break I1 + I2 ≥ I3: no rigid body has them",
            moments[0], moments[1], moments[2]
        ));
    }
    Ok(())
}

/// The uniform solid box of `mass` (kg) and `half_extents` (m): diag(b² + c², a² + c²,
/// a² + b²)·m/3 (kg·m²).
pub(super) fn box_inertia(mass: f64, half_extents: &Vector3<f64>) -> Matrix3<f64> {
    let s = half_extents.component_mul(half_extents);
    Matrix3::from_diagonal(&Vector3::new(s.y + s.z, s.x + s.z, s.x + s.y)) * (mass / 3.0)
}

/// Checked half extents (m): three positive finite numbers.
pub(super) fn half_extents(h: &[f64; 3]) -> Result<Vector3<f64>, String> {
    if h.iter().all(|x| *x > 0.0 && x.is_finite()) {
        Ok(Vector3::from(*h))
    } else {
        Err(format!(
            "half_extents {h:?} must be three positive numbers of m"
        ))
    }
}

/// A checked rounding radius (m) of a box of `half_extents` (m): finite, ≥ 0 and
/// below the smallest half extent (the box's core keeps a positive size).
pub(super) fn rounding(r: f64, half_extents: &Vector3<f64>) -> Result<f64, String> {
    let smallest = half_extents.min();
    if (0.0..smallest).contains(&r) {
        Ok(r)
    } else {
        Err(format!(
            "{r} must be a radius of m from 0 (a sharp box) up to, not including, the \
             smallest half extent {smallest}"
        ))
    }
}

/// The checked parts of a compound body.
pub(super) fn parts(specs: &[PartSpec]) -> Result<Vec<Part>, (String, String)> {
    if specs.is_empty() {
        return Err((
            "shape.compound.parts".into(),
            "needs at least one box".into(),
        ));
    }
    specs
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let field = |key: &str| format!("shape.compound.parts[{i}].{key}");
            let position = Vector3::from(p.position);
            if !position.iter().all(|x| x.is_finite()) {
                return Err((field("position"), "must be finite (m)".into()));
            }
            Ok(Part {
                half_extents: half_extents(&p.half_extents)
                    .map_err(|m| (field("half_extents"), m))?,
                position,
                orientation: orientation(p.orientation.as_ref())
                    .map_err(|m| (field("orientation"), m))?,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roll_pitch_yaw_is_rz_ry_rx() {
        let q = orientation(Some(&OrientationSpec::RollPitchYaw([0.35, -0.26, 0.1]))).unwrap();
        let expected = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.1)
            * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), -0.26)
            * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.35);
        assert!(q.angle_to(&expected) < 1e-15);
    }

    #[test]
    fn a_quaternion_is_normalised_and_a_zero_one_refused() {
        let q = orientation(Some(&OrientationSpec::Quaternion([2.0, 0.0, 0.0, 0.0]))).unwrap();
        assert_eq!(q, UnitQuaternion::identity());
        let zero = orientation(Some(&OrientationSpec::Quaternion([0.0; 4])));
        assert!(zero.unwrap_err().contains("non-zero"));
    }

    #[test]
    fn unphysical_inertia_is_refused_with_the_reason() {
        let bad = |spec: InertiaSpec| inertia(Some(&spec), 1.0, None).unwrap_err();
        assert!(bad(InertiaSpec::Principal([1.0, 1.0, 3.0])).contains("I1 + I2 ≥ I3"));
        assert!(bad(InertiaSpec::Principal([1.0, 0.0, 1.0])).contains("positive definite"));
        let skew = [[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(bad(InertiaSpec::Full(skew)).contains("symmetric"));
        let cube = box_inertia(0.37, &Vector3::repeat(0.05));
        // m·s²/6 for a cube of side s = 0.1 m.
        assert!((cube[(0, 0)] - 0.37 * 0.01 / 6.0).abs() < 1e-15);
        assert_eq!(inertia(None, 0.37, Some(cube)).unwrap(), cube);
    }
}
