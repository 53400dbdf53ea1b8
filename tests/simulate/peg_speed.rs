//! The shipped peg-in-hole after the stiff steps (RODAS where Dopri5 is held by
//! stability): the three contact events agree with the explicit-only solver's, the run
//! costs a tenth of its steps, and it stays bit-identical from run to run.
//!
//! Run with `--nocapture` to see the differences.

use hcm_host::scenario::{Model, Scenario};
use hcm_host::simulate::{simulate, Simulation};
use std::path::Path;

fn peg() -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/peg_in_hole.toml");
    Scenario::load(&path, &[]).unwrap().resolve(&path).unwrap()
}

/// Each event as the explicit Dopri5 alone found it (commit c7f5ab8, 10 973 + 1 623
/// steps): touch-down (s), lift-off (s), max force (N), max torque (N·m), linear impulse
/// (N·s), angular impulse (N·m·s).
const EXPLICIT: [[f64; 6]; 3] = [
    [
        2.270370826e-2,
        2.366030760e-2,
        38.31178583,
        1.133009784,
        1.974096903e-2,
        5.833962255e-4,
    ],
    [
        4.994873869e-2,
        5.322251879e-2,
        120.4892671,
        5.380847082,
        7.804485192e-2,
        1.734042528e-3,
    ],
    [
        6.896000909e-2,
        6.984858471e-2,
        968.6628219,
        8.406788692,
        4.578824213e-1,
        1.274319142e-3,
    ],
];

/// Allowed differences: times (s) and the four indicators (relative). The impulses'
/// bound is the explicit solver's own change from rtol 1e-9 to 1e-8 (bottom contact:
/// linear 9.8e-5, angular 2.3e-5): the switch of method moves them no more than a
/// tenfold tighter tolerance would.
const TIME: f64 = 1e-8;
const PEAK: f64 = 1e-6;
const IMPULSE: f64 = 1.5e-4;

fn indicators(run: &Simulation) -> Vec<[f64; 6]> {
    run.events
        .iter()
        .map(|e| {
            [
                e.touch_down,
                e.lift_off.unwrap(),
                e.max_force,
                e.max_torque,
                e.linear_impulse.norm(),
                e.angular_impulse.norm(),
            ]
        })
        .collect()
}

#[test]
fn the_three_events_agree_with_the_explicit_solver() {
    let run = simulate(&peg()).unwrap();
    let found = indicators(&run);
    assert_eq!(found.len(), 3, "{found:?}");
    for (event, (now, before)) in found.iter().zip(&EXPLICIT).enumerate() {
        for k in 0..6 {
            let (bound, difference) = if k < 2 {
                (TIME, (now[k] - before[k]).abs())
            } else {
                let relative = (now[k] - before[k]).abs() / before[k];
                (if k < 4 { PEAK } else { IMPULSE }, relative)
            };
            println!(
                "event {event} indicator {k}: {:.10e} vs {:.10e}: {difference:.1e}",
                now[k], before[k]
            );
            assert!(
                difference <= bound,
                "event {event} indicator {k}: {now:?} vs {before:?}"
            );
        }
    }
}

#[test]
fn the_run_takes_a_tenth_of_the_explicit_steps() {
    let run = simulate(&peg()).unwrap();
    let (accepted, rejected) = run.steps;
    println!("steps: {accepted} accepted, {rejected} rejected (explicit only: 10 973, 1 623)");
    assert!(accepted + rejected < 1_260, "{accepted} + {rejected}");
}

#[test]
fn two_runs_are_bit_identical() {
    let model = peg();
    let (one, two) = (simulate(&model).unwrap(), simulate(&model).unwrap());
    assert_eq!(one.events, two.events);
    assert_eq!(one.steps, two.steps);
    assert_eq!(one.end_time.to_bits(), two.end_time.to_bits());
    let samples = |s: &Simulation| format!("{:?}", s.run);
    assert_eq!(samples(&one), samples(&two));
}
