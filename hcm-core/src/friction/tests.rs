//! The tangential effects against their definitions.

extern crate std;

use super::*;
use nalgebra::Vector3;
use std::format;

fn effects() -> TangentialEffects<f64> {
    TangentialEffects {
        viscous_friction: Some(ViscousFriction { coefficient: 2.0 }),
        torsional_resistance: Some(TorsionalResistance {
            arm: 1e-3,
            spin_rate: 0.5,
        }),
        rolling_resistance: Some(RollingResistance {
            arm: 4e-4,
            roll_rate: 0.2,
        }),
    }
}

#[test]
fn viscous_friction_is_minus_c_times_the_slip() {
    let slip = Vector3::new(0.3, -0.2, 0.0);
    let f = effects().force(&slip);
    assert_eq!(f, Vector3::new(-0.6, 0.4, 0.0));
    assert_eq!(TangentialEffects::default().force(&slip), Vector3::zeros());
}

#[test]
fn torsional_resistance_opposes_the_spin_about_the_normal_only() {
    let law = effects().torsional_resistance.unwrap();
    let n = Vector3::z();
    // −a·f_n·ω_n/√(ω_n² + ω_t²) about n: 3/√9.25 of the full couple a·f_n.
    let c = law.couple(&Vector3::new(0.0, 0.0, 3.0), &n, 50.0);
    let expected = -0.05 * 3.0 / 9.25_f64.sqrt();
    assert!((c - Vector3::new(0.0, 0.0, expected)).norm() < 1e-15, "{c}");
    let fast = law.couple(&Vector3::new(0.0, 0.0, 3e3), &n, 50.0);
    assert!((fast.z + 0.05).abs() < 1e-7, "{fast}");
    // Rotation about a tangent axis is not spin.
    assert_eq!(
        law.couple(&Vector3::new(2.0, 0.0, 0.0), &n, 50.0),
        Vector3::zeros()
    );
    // Below ω_t it fades linearly: smaller, opposing, zero at rest.
    let slow = law.couple(&Vector3::new(0.0, 0.0, -0.1), &n, 50.0);
    assert!(
        (slow.z - 0.05 * 0.1 / 0.26_f64.sqrt()).abs() < 1e-15,
        "{slow}"
    );
    assert_eq!(law.couple(&Vector3::zeros(), &n, 50.0), Vector3::zeros());
}

#[test]
fn rolling_resistance_opposes_rotation_about_tangent_axes() {
    let law = effects().rolling_resistance.unwrap();
    let n = Vector3::z();
    let omega = Vector3::new(3.0, 4.0, 7.0);
    let c = law.couple(&omega, &n, 10.0);
    // Perpendicular to n, along −ω_t (|ω_t| = 5), magnitude a_r·f_n·5/√(25 + 0.04).
    assert!(c.z.abs() < 1e-18);
    let magnitude = 4e-3 * 5.0 / 25.04_f64.sqrt();
    assert!(
        (c - Vector3::new(-0.6, -0.8, 0.0) * magnitude).norm() < 1e-15,
        "{c}"
    );
}

#[test]
fn every_effect_dissipates() {
    // Power of the force on the slip and of the couple on the rotation: never > 0.
    let e = effects();
    let n = Vector3::new(0.0, 0.6, 0.8);
    for k in 0..200 {
        let x = f64::from(k) * 0.37;
        let omega = Vector3::new(x.sin() * 3.0, (1.3 * x).cos(), (0.7 * x).sin() * 0.4);
        let slip = Vector3::new(x.cos(), -0.5 * x.sin(), 0.0);
        let slip = slip - n * slip.dot(&n);
        assert!(e.force(&slip).dot(&slip) <= 0.0);
        let couple = e.couple(&omega, &n, 20.0 + x);
        assert!(couple.dot(&omega) <= 1e-15, "{couple} · {omega}");
        assert!(couple.norm() <= (1e-3 + 4e-4) * (20.0 + x) + 1e-12);
    }
}

#[test]
fn nan_and_infinity_do_not_panic() {
    let e = effects();
    let bad = Vector3::new(f64::NAN, 0.0, 1.0);
    assert!(e.force(&bad).x.is_nan());
    assert!(e
        .couple(&bad, &Vector3::z(), 1.0)
        .iter()
        .any(|c| c.is_nan()));
    // An infinite normal force saturates; at rest it still gives no couple.
    let c = e.couple(&Vector3::new(0.0, 0.0, 1.0), &Vector3::z(), f64::INFINITY);
    assert!(c.iter().all(|c| !c.is_nan()), "{c}");
    let c = e.couple(&Vector3::zeros(), &Vector3::z(), f64::INFINITY);
    assert_eq!(c, Vector3::zeros());
    let f = e.force(&Vector3::new(f64::INFINITY, 0.0, 0.0));
    assert!(f.x.is_finite());
    let f32_effects = e.map(|v| v as f32);
    let c = f32_effects.couple(&Vector3::new(0.0, 0.0, f32::NAN), &Vector3::z(), 1.0);
    assert!(c.z.is_nan());
}

#[test]
fn validation_names_the_field() {
    let mut e = effects();
    assert!(e.validate().is_ok());
    e.torsional_resistance = Some(TorsionalResistance {
        arm: 1e-3,
        spin_rate: 0.0,
    });
    let message = format!("{:?}", e.validate().unwrap_err());
    assert!(
        message.contains("torsional_resistance.spin_rate"),
        "{message}"
    );
    e.torsional_resistance = None;
    e.viscous_friction = Some(ViscousFriction { coefficient: -1.0 });
    let message = format!("{:?}", e.validate().unwrap_err());
    assert!(
        message.contains("viscous_friction.coefficient"),
        "{message}"
    );
}
