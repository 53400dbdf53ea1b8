use super::*;
use crate::effect::{Adhesion, ContactEffect};
use crate::law::{Hertz, NormalLaw};
use crate::residual::{Activation, Envelope, Mlp};

const NONE: [f32; 0] = [];

fn hertz() -> AnyNormalLaw<f32> {
    Hertz {
        stiffness: 1e9,
        exponent: 1.5,
    }
    .into()
}

/// A residual that returns 2 N + 1000·δ (N) on δ ∈ [0, 1 mm], |δ̇| ≤ 2 m/s.
fn model() -> ContactModel<f32, Mlp<3, 1, 1, 1>> {
    let mut residual: Mlp<3, 1, 1, 1> = Mlp::zeroed(Activation::Relu);
    residual.input_layer.weights = [[1000.0], [0.0], [0.0]]; // column by column
    residual.output_layer.weights = [[1.0]];
    residual.output_layer.bias = [2.0];
    residual.envelope = Envelope {
        min: [0.0, -2.0, 0.0],
        max: [1e-3, 2.0, 2.0],
        tolerance: [0.0; 3],
    };
    ContactModel::physics(hertz()).with_residual(residual)
}

fn contact(depth: f32, rate: f32) -> (Indentation<f32>, [f32; 3]) {
    let state = Indentation {
        depth,
        rate,
        approach_speed: 1.0,
    };
    (state, [depth, rate, 1.0])
}

fn fresh() -> ContactMemory<f32> {
    ContactMemory::touch_down()
}

#[test]
fn inside_the_envelope_adds_the_residual() {
    let model = model();
    let (state, input) = contact(1e-4, 0.5);
    let physics = model.law().normal_force(&state);
    let (force, evaluated) = model.normal_force(&state, &fresh(), &input);
    assert_eq!(evaluated, Evaluated::PhysicsAndResidual);
    assert!(
        (force - (physics + 2.1)).abs() < 1e-4,
        "{force} vs {physics}"
    );
}

#[test]
fn outside_the_envelope_returns_exactly_the_law_force() {
    let model = model();
    for (depth, rate) in [(2e-3, 0.5), (1e-4, 3.0), (1e-4, f32::NAN)] {
        let (state, input) = contact(depth, rate);
        let (force, evaluated) = model.normal_force(&state, &fresh(), &input);
        assert_eq!(evaluated, Evaluated::PhysicsOnly);
        assert_eq!(
            force,
            model.law().normal_force(&state),
            "δ = {depth}, δ̇ = {rate}"
        );
    }
}

#[test]
fn out_of_contact_is_zero_even_inside_the_envelope() {
    let model = model();
    // δ = 0 is inside the envelope, where the residual alone would give 2 N.
    for depth in [0.0, -1e-4] {
        let (state, input) = contact(depth, 0.5);
        assert_eq!(
            model.normal_force(&state, &fresh(), &input),
            (0.0, Evaluated::PhysicsOnly)
        );
    }
}

#[test]
fn nan_depth_propagates() {
    let model = model();
    let (state, input) = contact(f32::NAN, 0.5);
    let (force, evaluated) = model.normal_force(&state, &fresh(), &input);
    assert!(force.is_nan());
    assert_eq!(evaluated, Evaluated::PhysicsOnly);
}

#[test]
fn a_residual_input_of_the_wrong_length_switches_the_residual_off() {
    let model = model();
    let (state, _) = contact(1e-4, 0.5);
    for input in [&[1e-4_f32, 0.5][..], &[1e-4, 0.5, 1.0, 0.0][..], &[][..]] {
        let (force, evaluated) = model.normal_force(&state, &fresh(), input);
        assert_eq!(evaluated, Evaluated::PhysicsOnly);
        assert_eq!(force, model.law().normal_force(&state));
    }
}

#[test]
fn effects_are_part_of_the_physics() {
    let mut model = ContactModel::physics(hertz());
    let _ = model.normal.effects.push(ContactEffect::Adhesion(Adhesion {
        pull_off_force: 3.0,
    }));
    let (state, _) = contact(1e-4, 0.5);
    let (force, evaluated) = model.normal_force(&state, &fresh(), &NONE);
    assert_eq!(evaluated, Evaluated::PhysicsOnly);
    assert_eq!(force, hertz().normal_force(&state) - 3.0);
    // Adhesion acts only in contact.
    let (apart, _) = contact(-1e-6, 0.5);
    assert_eq!(model.normal_force(&apart, &fresh(), &NONE).0, 0.0);
}

fn point(depth: f64, position: [f64; 3], slip: [f64; 3]) -> ContactPoint<f64> {
    ContactPoint {
        indentation: Indentation {
            depth,
            rate: 0.0,
            approach_speed: 1.0,
        },
        memory: ContactMemory::touch_down(),
        normal: Vector3::z(),
        position: Vector3::from(position),
        relative_velocity: Vector3::from(slip),
        relative_angular_velocity: Vector3::zeros(),
    }
}

fn box_on_plane() -> ContactModel<f64> {
    ContactModel::physics(AnyNormalLaw::Hertz(Hertz {
        stiffness: 1e6,
        exponent: 1.0,
    }))
    .with_friction(VelocityStepFriction {
        static_coefficient: 0.5,
        dynamic_coefficient: 0.4,
        stiction_speed: 1e-3,
        dynamic_speed: 1e-2,
    })
}

#[test]
fn several_points_add_up_by_eq_1() {
    let model = box_on_plane();
    // Two corners of a box resting 1 mm and 2 mm deep, centre of mass 5 cm above the
    // plane, sliding along +x at 1 m/s; the ground (body 2) is at the origin.
    let points = [
        point(1e-3, [0.1, 0.0, 0.0], [1.0, 0.0, 0.0]),
        point(2e-3, [-0.1, 0.0, 0.0], [1.0, 0.0, 0.0]),
        point(-1e-3, [0.0, 0.1, 0.0], [1.0, 0.0, 0.0]),
    ];
    let centre = Vector3::new(0.0, 0.0, 0.05);
    let load = model.pair_load(&points, &centre, &Vector3::zeros(), &[]);
    // Normal: 1e6·(1e-3 + 2e-3) = 3000 N; friction μ_d = 0.4 against the slip.
    assert!((load.normal_force - 3000.0).abs() < 1e-9);
    let w = load.wrench;
    assert!((w.force_1 - Vector3::new(-1200.0, 0.0, 3000.0)).norm() < 1e-9);
    assert_eq!(w.force_2, -w.force_1);
    // Torque about the centre: Σ (p − c) × F_p, checked by hand about y:
    // corner 1 (0.1, 0, −0.05) × (−400, 0, 1000) → τ_y = −0.05·−400 − 0.1·1000 = −80
    // corner 2 (−0.1, 0, −0.05) × (−800, 0, 2000) → τ_y = −0.05·−800 + 0.1·2000 = 240
    assert!((w.torque_1 - Vector3::new(0.0, 160.0, 0.0)).norm() < 1e-9);
    // Moment balance: the torques about a common point cancel.
    let about_origin_1 = w.torque_1 + centre.cross(&w.force_1);
    assert!((about_origin_1 + w.torque_2).norm() < 1e-9);
    assert_eq!(load.evaluated, Evaluated::PhysicsOnly);
}

#[test]
fn no_touching_point_gives_zero_loads() {
    let model = box_on_plane();
    let points = [point(-1e-3, [0.1, 0.0, 0.0], [1.0, 0.0, 0.0])];
    let load = model.pair_load(&points, &Vector3::zeros(), &Vector3::zeros(), &[]);
    assert_eq!(load.normal_force, 0.0);
    assert_eq!(load.wrench.force_1, Vector3::zeros());
    assert_eq!(load.wrench.torque_2, Vector3::zeros());
}

/// A 2-input residual with 6 outputs: a constant wrench (1, 2, 3) N, (4, 5, 6) N·m.
fn wrench_residual() -> Mlp<2, 1, 6, 1> {
    let mut residual: Mlp<2, 1, 6, 1> = Mlp::zeroed(Activation::Relu);
    residual.output_layer.bias = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    residual.envelope = Envelope {
        min: [-1.0, -1.0],
        max: [1.0, 1.0],
        tolerance: [0.0; 2],
    };
    residual
}

#[test]
fn a_wrench_residual_acts_on_body_1_and_its_reaction_on_body_2() {
    let model = box_on_plane().with_residual(wrench_residual());
    let points = [point(1e-3, [0.0, 0.0, 0.0], [0.0; 3])];
    let (centre, ground) = (Vector3::new(0.0, 0.0, 0.05), Vector3::zeros());
    let physics = model.clone().with_residual(NoResidual);
    let base = physics.pair_load(&points, &centre, &ground, &[]);
    let load = model.pair_load(&points, &centre, &ground, &[0.0, 0.0]);
    assert_eq!(load.evaluated, Evaluated::PhysicsAndResidual);
    let force = Vector3::new(1.0, 2.0, 3.0);
    let torque = Vector3::new(4.0, 5.0, 6.0);
    assert!((load.wrench.force_1 - base.wrench.force_1 - force).norm() < 1e-6);
    assert!((load.wrench.torque_1 - base.wrench.torque_1 - torque).norm() < 1e-6);
    assert_eq!(load.wrench.force_2, -load.wrench.force_1);
    // The pair still balances about a common point.
    let w = load.wrench;
    assert!((w.torque_1 + centre.cross(&w.force_1) + w.torque_2).norm() < 1e-6);
    // The normal force reported is the physics' (a wrench is not a normal force).
    assert_eq!(load.normal_force, base.normal_force);
    // Outside the envelope: the physics alone, exactly.
    let outside = model.pair_load(&points, &centre, &ground, &[5.0, 0.0]);
    assert_eq!(outside, base);
}

#[test]
fn a_normal_force_residual_acts_at_the_first_touching_point() {
    let law = ContactModel::physics(hertz());
    let model = law.clone().with_residual(model().residual);
    let mut p = ContactPoint::along_normal(contact(1e-4, 0.5).0, fresh());
    p.position = Vector3::new(0.0, 0.0, -0.01);
    let input = [1e-4, 0.5, 1.0];
    let load = model.pair_load(&[p], &Vector3::zeros(), &Vector3::zeros(), &input);
    let (scalar, _) = model.normal_force(&p.indentation, &p.memory, &input);
    assert_eq!(load.normal_force, scalar);
    assert_eq!(load.wrench.force_1, Vector3::new(0.0, 0.0, scalar));
    assert_eq!(load.evaluated, Evaluated::PhysicsAndResidual);
}

#[test]
fn nan_anywhere_never_panics() {
    let model = box_on_plane().with_residual(wrench_residual());
    let mut p = point(
        f64::NAN,
        [f64::NAN, 0.0, 0.0],
        [f64::INFINITY, 0.0, f64::NAN],
    );
    p.normal = Vector3::new(f64::NAN, 0.0, 1.0);
    let load = model.pair_load(&[p], &Vector3::zeros(), &Vector3::zeros(), &[f64::NAN, 0.0]);
    assert!(load.normal_force.is_nan());
    assert_eq!(load.evaluated, Evaluated::PhysicsOnly);
}

#[test]
fn tangential_effects_add_viscous_friction_and_a_couple_at_touching_points() {
    use crate::friction::{TangentialEffects, TorsionalResistance, ViscousFriction};
    let mut model = ContactModel::physics(AnyNormalLaw::from(Hertz {
        stiffness: 1e9,
        exponent: 1.5,
    }));
    model.tangential = TangentialEffects {
        viscous_friction: Some(ViscousFriction { coefficient: 3.0 }),
        torsional_resistance: Some(TorsionalResistance {
            arm: 2e-3,
            spin_rate: 0.1,
        }),
        rolling_resistance: None,
    };
    let mut p = point(1e-6, [0.1, 0.0, 0.0], [0.5, 0.0, -7.0]);
    p.relative_angular_velocity = Vector3::new(0.0, 0.0, 4.0);
    let centre = Vector3::new(0.0, 0.0, 0.2);
    let load = model.pair_load(&[p], &centre, &Vector3::zeros(), &[]);
    let f_n = 1e9 * 1e-6_f64.powf(1.5);
    // Viscous: −3·(0.5, 0, 0) beside the normal force (the approach is not slip).
    let w = &load.wrench;
    assert!(
        (w.force_1 - Vector3::new(-1.5, 0.0, f_n)).norm() < 1e-9,
        "{}",
        w.force_1
    );
    // The couple −a·f_n about z, opposite on body 2, beside the forces' moments.
    let arm = Vector3::new(0.1, 0.0, 0.0) - centre;
    let couple = 2e-3 * f_n * 4.0 / 16.01_f64.sqrt();
    let expected = arm.cross(&w.force_1) + Vector3::new(0.0, 0.0, -couple);
    assert!((w.torque_1 - expected).norm() < 1e-9, "{}", w.torque_1);
    let about_ground = Vector3::new(0.1, 0.0, 0.0).cross(&-w.force_1);
    let expected_2 = about_ground + Vector3::new(0.0, 0.0, couple);
    assert!((w.torque_2 - expected_2).norm() < 1e-9, "{}", w.torque_2);
    // Apart: nothing.
    let apart = point(-1e-6, [0.1, 0.0, 0.0], [0.5, 0.0, 0.0]);
    let load = model.pair_load(&[apart], &centre, &Vector3::zeros(), &[]);
    assert_eq!(load.wrench.torque_1, Vector3::zeros());
}

/// A contact-frame residual with constant outputs k_n 1000 N/m, r_f 0.5, c_t −2 N·s/m,
/// c_n 0.3 N·m·s, c_r 0.4 N·m·s, inside δ ∈ [0, 1 cm] (other features unbounded).
fn point_residual() -> PerPoint<Mlp<POINT_INPUTS, 1, POINT_OUTPUTS, 1>> {
    let mut network: Mlp<POINT_INPUTS, 1, POINT_OUTPUTS, 1> = Mlp::zeroed(Activation::Relu);
    network.output_layer.bias = [1000.0, 0.5, -2.0, 0.3, 0.4];
    let wide = 1e6;
    network.envelope = Envelope {
        min: [0.0, -wide, -wide, -wide, -wide],
        max: [1e-2, wide, wide, wide, wide],
        tolerance: [0.0; POINT_INPUTS],
    };
    PerPoint(network)
}

/// The friction law's force at `point` under the law's own normal force.
fn base_point_friction(point: &ContactPoint<f64>) -> Vector3<f64> {
    box_on_plane().point_force(point).friction
}

#[test]
fn a_contact_frame_residual_acts_at_every_touching_point_along_its_own_directions() {
    let model = box_on_plane().with_residual(point_residual());
    let physics = box_on_plane();
    // Two corners, one slipping along +x and spinning, the other at rest and rolling.
    let mut a = point(1e-3, [0.05, 0.0, 0.0], [0.2, 0.0, -0.1]);
    a.relative_angular_velocity = Vector3::new(0.0, 0.0, 3.0);
    let mut b = point(2e-3, [-0.05, 0.0, 0.0], [0.0; 3]);
    b.relative_angular_velocity = Vector3::new(0.0, -5.0, 0.0);
    let (centre, ground) = (Vector3::new(0.0, 0.0, 0.05), Vector3::zeros());
    let base = physics.pair_load(&[a, b], &centre, &ground, &[]);
    let load = model.pair_load(&[a, b], &centre, &ground, &[]);
    assert_eq!(load.evaluated, Evaluated::PhysicsAndResidual);
    // 1000 N/m × δ more at each point (1 N at a, 2 N at b); at a, which slips at
    // 0.2 m/s (beyond v_d: μ_d 0.4), the friction law reads the extra newton (−0.4 N),
    // its force at the law's own normal force is scaled by 1.5, and −2 N·s/m ×
    // 0.2 m/s adds to it; b does not slip.
    assert!((load.normal_force - base.normal_force - 3.0).abs() < 1e-7);
    let law_friction = base_point_friction(&a);
    let extra_force = Vector3::new(-0.8, 0.0, 3.0) + law_friction * 0.5;
    let df = load.wrench.force_1 - base.wrench.force_1;
    assert!((df - extra_force).norm() < 1e-7, "{df}");
    // Torque: the forces' moments about the centre, 0.3 × 3 N·m about the spin +z at
    // a (it spins), 0.4 × 5 N·m about the rolling axis −y at b (it rolls); nothing
    // about what does not move (b does not spin, a does not roll).
    let arm_a = a.position - centre;
    let arm_b = b.position - centre;
    let expected = arm_a.cross(&(Vector3::new(-0.8, 0.0, 1.0) + law_friction * 0.5))
        + arm_b.cross(&Vector3::new(0.0, 0.0, 2.0))
        + Vector3::new(0.0, 0.0, 0.9)
        + Vector3::new(0.0, -2.0, 0.0);
    let dt = load.wrench.torque_1 - base.wrench.torque_1;
    // (The outputs are f32: 0.4 is 0.4 + 6e-9.)
    assert!((dt - expected).norm() < 1e-7, "{dt} vs {expected}");
    // The pair balances: the ground takes the opposite.
    assert!((load.wrench.force_1 + load.wrench.force_2).norm() < 1e-9);
    let w = load.wrench;
    assert!((w.torque_1 + centre.cross(&w.force_1) + w.torque_2).norm() < 1e-9);
    // The pair's own input is not read: a pair input of any length changes nothing.
    assert_eq!(model.pair_load(&[a, b], &centre, &ground, &[7.0]), load);
}

#[test]
fn a_contact_frame_residual_switches_off_point_by_point() {
    let model = box_on_plane().with_residual(point_residual());
    let physics = box_on_plane();
    // One point inside the envelope (1 mm), one beyond it (2 cm): only the first is
    // corrected (1000 N/m × 1 mm).
    let inside = point(1e-3, [0.05, 0.0, 0.0], [0.0; 3]);
    let beyond = point(2e-2, [-0.05, 0.0, 0.0], [0.0; 3]);
    let centre = Vector3::new(0.0, 0.0, 0.05);
    let both = model.pair_load(&[inside, beyond], &centre, &Vector3::zeros(), &[]);
    let base = physics.pair_load(&[inside, beyond], &centre, &Vector3::zeros(), &[]);
    assert!((both.normal_force - base.normal_force - 1.0).abs() < 1e-7);
    // Beyond alone: the physics exactly, and said.
    let alone = model.pair_load(&[beyond], &centre, &Vector3::zeros(), &[]);
    assert_eq!(alone.evaluated, Evaluated::PhysicsOnly);
    assert_eq!(
        alone.wrench,
        physics
            .pair_load(&[beyond], &centre, &Vector3::zeros(), &[])
            .wrench
    );
    // NaN features: no panic, no correction.
    let mut nan = inside;
    nan.relative_velocity = Vector3::new(f64::NAN, 0.0, 0.0);
    let load = model.pair_load(&[nan], &centre, &Vector3::zeros(), &[]);
    assert_eq!(load.evaluated, Evaluated::PhysicsOnly);
}

#[test]
fn the_features_are_the_same_wherever_and_however_turned_the_contact_happens() {
    let mut p = point(1e-3, [0.3, -0.2, 0.1], [0.3, 0.4, -0.5]);
    p.indentation.rate = 0.5;
    p.relative_angular_velocity = Vector3::new(1.0, -2.0, -2.0);
    let features = point_residual::point_features(&p);
    let expected = [1e-3, 0.5, 0.5, 2.0, 5.0_f64.sqrt()];
    for (f, e) in features.iter().zip(expected) {
        assert!((f - e).abs() < 1e-12, "{features:?}");
    }
    // Rotated and moved: the same features.
    let turn = nalgebra::Rotation3::from_euler_angles(0.3, -1.1, 2.0);
    let mut q = p;
    q.normal = turn * p.normal;
    q.position = turn * p.position + Vector3::new(4.0, 5.0, 6.0);
    q.relative_velocity = turn * p.relative_velocity;
    q.relative_angular_velocity = turn * p.relative_angular_velocity;
    for (f, g) in features.iter().zip(point_residual::point_features(&q)) {
        assert!((f - g).abs() < 1e-12);
    }
}
