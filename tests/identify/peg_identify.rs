//! PM2 on the peg-in-hole: the target built from S1 (events matched by
//! order, their delays, the mean pre-contact state), a fitness that tells the
//! generating physics from a wrong one, and the genetic algorithm fitting IMPACT with
//! a fixed exponent other than PM1's, plus STEP friction.
//!
//! Run with `--nocapture` to see the fitness values and the identified parameters.

use hcm_host::experiment::generate;
use hcm_host::identify::{
    event_errors, event_fitness, identify_rigid, replay_events, RigidParameters, WrenchTarget,
};
use hcm_host::numerics::optimize::GeneticSettings;
use hcm_host::numerics::optimize::Parameters;
use hcm_host::scenario::Model;
use std::collections::BTreeMap;

use hcm_tests::peg_in_hole as peg;

/// `model` started like the target's replay, with the physics of `physics`.
fn as_replay(target: &WrenchTarget, physics: &Model) -> Model {
    hcm_host::identify::with_physics(&target.model, physics)
}

#[test]
fn the_target_and_its_fitness_tell_the_generating_physics_from_a_wrong_one() {
    let scenario = peg();
    let nominal = scenario.model().unwrap();
    let data = generate(&scenario, 6, 3, &hcm_host::progress::Silent).unwrap();
    let all = WrenchTarget::from_data(&nominal, &data, 0, None).unwrap();
    assert!(all.events.len() >= 3, "two wall contacts and the bottom");
    // The two wall contacts (Table 15's): the bottom's peak torque depends on how
    // flat the peg lands and scatters by tens of % from run to run (measured: the
    // nominal replay's is 62 % off the 6 runs' mean), so it is not a fitting target.
    let target = WrenchTarget::from_data(&nominal, &data, 0, Some(2)).unwrap();
    println!(
        "{} events from {} runs ({} left out)",
        target.events.len(),
        target.runs,
        target.left_out.len()
    );
    assert_eq!(target.events.len(), 2);
    assert_eq!(target.events[0].delay, 0.0);
    for pair in target.events.windows(2) {
        assert!(pair[1].delay > pair[0].delay, "events in time order");
    }
    // The nominal physics replayed from the mean pre-contact state makes the mean
    // events to within the 2 % parameter scatter; ten times the stiffness does not.
    let right = event_fitness(&target, &as_replay(&target, &nominal));
    let events = replay_events(&as_replay(&target, &nominal), 0).unwrap();
    for (k, (t, got)) in events.iter().enumerate().take(target.events.len()) {
        let e = event_errors(&target.events[k], got, t - events[0].0);
        println!("event {k}: relative errors {e:.4?} (max F, max T, ∫F, ∫T, delay)");
        assert!(e.iter().all(|e| e.abs() < 0.02), "event {k}: {e:?}");
    }
    let mut stiff = nominal.clone();
    let law = &mut stiff.contacts[0].model.normal.base;
    law.set("stiffness", 1e9).unwrap();
    let wrong = event_fitness(&target, &as_replay(&target, &stiff));
    println!("fitness: nominal {right:.3e}, stiffness × 10 {wrong:.3e}");
    assert!(right < 1e-3, "{right}");
    assert!(wrong > 30.0 * right, "{wrong} vs {right}");
    // Asking for more events than the runs make is an error saying how many they make.
    let error = WrenchTarget::from_data(&nominal, &data, 0, Some(9)).unwrap_err();
    assert!(error.to_string().contains("usually make"), "{error}");
}

#[test]
fn the_genetic_algorithm_fits_impact_with_a_fixed_wrong_exponent() {
    let scenario = peg();
    let nominal = scenario.model().unwrap();
    let data = generate(&scenario, 4, 5, &hcm_host::progress::Silent).unwrap();
    // PM2: exponent 2 instead of PM1's 1.5, everything else to be found.
    let mut pm2 = nominal.clone();
    let law = &mut pm2.contacts[0].model.normal.base;
    law.set("exponent", 2.0).unwrap();
    let target = WrenchTarget::from_data(&pm2, &data, 0, Some(2)).unwrap();
    let parameters = RigidParameters::new(&pm2, 0, &BTreeMap::new()).unwrap();
    assert!(!parameters.names().iter().any(|n| n == "exponent"));
    assert_eq!(parameters.names().len(), 3 + 4, "{:?}", parameters.names());
    let settings = GeneticSettings {
        population: 16,
        generations: 8,
        seed: 2,
        ..GeneticSettings::default()
    };
    let first = parameters.bounds();
    let middle: Vec<f64> = first
        .iter()
        .map(|b| {
            if b.log_scale {
                (b.lower * b.upper).sqrt()
            } else {
                0.5 * (b.lower + b.upper)
            }
        })
        .collect();
    let start = event_fitness(&target, &parameters.apply(&target.model, &middle));
    let found = identify_rigid(
        &pm2,
        &target,
        &parameters,
        &settings,
        &hcm_host::progress::Silent,
    )
    .unwrap();
    println!(
        "fitness {start:.3e} at the box's middle → {:.3e} in {} replays, {:.1} s: {:?}",
        found.fitness, found.evaluations, found.seconds, found.parameters
    );
    assert_eq!(found.model.contacts[0].law().get("exponent").unwrap(), 2.0);
    assert!(found.fitness < 0.25 * start, "{} vs {start}", found.fitness);
    // Its replay makes both wall contacts.
    let replayed = replay_events(&as_replay(&target, &found.model), 0).unwrap();
    assert!(replayed.len() >= 2, "{replayed:?}");
}

#[test]
fn hcm_identify_fits_a_rigid_contact_and_writes_its_friction() {
    use hcm_tests::cli::Hcm;
    let hcm = Hcm::new();
    let scenario = hcm_tests::scenario("peg_in_hole.toml");
    hcm.run("generate")
        .opt("--scenario", &scenario)
        .opt("--runs", "12")
        .opt("--out", hcm.path("peg"))
        .ok();
    let s1 = hcm.path("peg.s1.csv");
    let identify = |extra: &[(&str, &str)]| {
        let mut command = hcm.run("identify");
        command = command
            .opt("--scenario", &scenario)
            .opt("--data", &s1)
            .opt("--out", hcm.path("pm2.toml"));
        for (key, value) in extra {
            command = command.opt(key, value);
        }
        command
    };
    // Least squares fits every touching sample: choosing events is the GA's.
    let lsq = identify(&[("--law", "impact"), ("--events", "2")]).fails();
    assert!(lsq.contains("--events is for"), "{lsq}");
    // By least squares, a law other than the scenario's is fitted in its place, the
    // exponent free.
    let hertz = identify(&[("--law", "hunt_crossley")]).ok();
    assert!(
        hertz.contains("hunt_crossley and STEP friction by least squares"),
        "{hertz}"
    );
    let physics = hcm_host::identify::Physics::read(&hcm.path("pm2.toml")).unwrap();
    assert!(physics.contacts[0].parameters.contains_key("damping"));
    let out = identify(&[
        ("--law", "impact"),
        ("--method", "ga"),
        ("--exponent", "2"),
        ("--events", "2"),
        ("--population", "8"),
        ("--generations", "3"),
    ])
    .ok();
    assert!(out.contains("exponent fixed at 2"), "{out}");
    let physics = hcm_host::identify::Physics::read(&hcm.path("pm2.toml")).unwrap();
    let contact = &physics.contacts[0];
    assert_eq!(contact.parameters["exponent"].as_float(), Some(2.0));
    let friction = contact.friction.expect("friction identified with the law");
    assert!(friction.mu_dynamic <= friction.mu_static && friction.v_static < friction.v_dynamic);
    // The file applies back onto the scenario, friction included.
    let applied = physics
        .apply(&peg(), &hcm.path("pm2.toml"))
        .unwrap()
        .model()
        .unwrap();
    let law = applied.contacts[0].model.friction.unwrap();
    assert_eq!(law.static_coefficient, friction.mu_static);
    assert_eq!(law.dynamic_speed, friction.v_dynamic);
}

/// A fit is never silent: the generating physics, replayed, misses no event's
/// indicator; ten times its stiffness misses them by more than the runs scatter, and a
/// stiffness at either end of its search interval is said.
#[test]
fn a_fit_that_does_not_reproduce_the_events_is_said() {
    use hcm_host::identify::rigid_warnings as warnings;
    let scenario = peg();
    let nominal = scenario.model().unwrap();
    let data = generate(&scenario, 6, 3, &hcm_host::progress::Silent).unwrap();
    let target = WrenchTarget::from_data(&nominal, &data, 0, Some(2)).unwrap();
    let parameters = RigidParameters::new(&nominal, 0, &BTreeMap::new()).unwrap();
    let bounds = parameters.bounds();
    let said = |m: &Model| {
        let w = warnings(
            &bounds,
            &parameters.values(m),
            &target,
            &as_replay(&target, m),
        );
        println!("{w:#?}");
        w
    };
    // The peg's stiffness, 1e8 N/m^n, is the low end of IMPACT's default box: said;
    // nothing else is.
    let w = said(&nominal);
    assert!(
        w.iter()
            .all(|w| w.starts_with("`stiffness` ended at its lower")),
        "{w:#?}"
    );
    let stiffness = nominal.contacts[0].law().get("stiffness").unwrap();
    let with_stiffness = |k: f64| {
        let mut m = nominal.clone();
        m.contacts[0].model.normal.base.set("stiffness", k).unwrap();
        m
    };
    let w = said(&with_stiffness(10.0 * stiffness));
    assert!(
        w.iter().any(|w| w.contains("max_force is off by")),
        "{w:#?}"
    );
    let w = said(&with_stiffness(bounds[0].upper));
    assert!(
        w[0].starts_with("`stiffness` ended at its upper search bound"),
        "{w:#?}"
    );
}
