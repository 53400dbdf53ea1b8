//! hcm-core on a Cortex-M4F: the firmware QEMU's `mps2-an386` runs (`cargo run
//! --release` in this directory; see `.cargo/config.toml`).
//!
//! It decodes the bouncing ball's embedded residual blobs, evaluates the fixed case
//! table of [`cases`] — every normal law, every effect, STEP friction, the Eq 1
//! wrench, the HCM with f32 and int8 weights, a whole bouncing-ball run — and prints
//! over semihosting, one line each:
//!
//! - `case GROUP.ITEM HEX…`: every result as raw `f32` bits (what `tests/controller/firmware.rs`
//!   compares, bit for bit, with the host's evaluation of the same table);
//! - `cost GROUP.ITEM N`: instructions per evaluation (see [`cost`]);
//! - `size flash|ram|stack N`: bytes of flash, static RAM, and peak stack;
//! - `end`; then it exits QEMU with status 0 (1 if a blob failed to decode).
#![no_std]
#![no_main]

mod cases;
mod cost;
mod harness;
mod memory;
mod out;
mod vectors;

use cases::table::{self, MEMORY, STATES};
use cases::{hcm_force, Fixture};
use core::hint::black_box;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug;
use hcm_core::effect::ExtendedLaw;
use hcm_core::law::{AnyNormalLaw, LawKind, NormalLaw};
use hcm_core::wrench::ContactWrench;

#[entry]
fn main() -> ! {
    harness::run(Fixture::decode, cases::evaluate_all, costs)
}

/// Instructions per evaluation of each law, effect, friction, the wrench, the
/// residual and the HCM (f32, int8), decoding, and one whole ball run.
fn costs(counter: &cost::Counter, fixture: &Fixture, report: &mut dyn FnMut(&str, &str, u32)) {
    law_costs(counter, report);
    let input = fixture.hcm_inputs()[1];
    #[cfg(feature = "profile")]
    {
        // `tools/qprof.py`: the int8 HCM eight times between the markers.
        cost::marker_start();
        for _ in 0..8 {
            black_box(hcm_force(&fixture.hcm_int8, black_box(&input)));
        }
        cost::marker_end();
    }
    report(
        "residual",
        "f32",
        counter.instructions(|| {
            black_box(fixture.hcm_f32.residual.evaluate(black_box(&input)));
        }),
    );
    report(
        "residual",
        "int8",
        counter.instructions(|| {
            black_box(fixture.hcm_int8.residual.evaluate(black_box(&input)));
        }),
    );
    report(
        "hcm",
        "f32",
        counter.instructions(|| {
            black_box(hcm_force(&fixture.hcm_f32, black_box(&input)));
        }),
    );
    report(
        "hcm",
        "int8",
        counter.instructions(|| {
            black_box(hcm_force(&fixture.hcm_int8, black_box(&input)));
        }),
    );
    report(
        "decode",
        "f32",
        counter.instructions(|| {
            let blob = black_box(table::BALL_F32_BLOB);
            let decoded: Result<cases::BallResidual, _> = hcm_core::residual::decode(blob);
            black_box(decoded.is_ok());
        }),
    );
    report(
        "ball",
        "run",
        counter.instructions_once(|| {
            black_box(cases::ball::simulate(black_box(&fixture.hcm_f32)).ok());
        }),
    );
}

/// Instructions per evaluation of each normal law, the PM2 with each effect, STEP
/// friction and the Eq 1 wrench.
fn law_costs(counter: &cost::Counter, report: &mut dyn FnMut(&str, &str, u32)) {
    for kind in LawKind::ALL {
        let law = table::law(kind);
        report(
            "law",
            kind.name(),
            counter.instructions(|| {
                black_box(law.normal_force(black_box(&STATES[0])));
            }),
        );
    }
    for effect in table::effects() {
        let mut extended = ExtendedLaw::new(AnyNormalLaw::from(table::ball_pm2()));
        let _ = extended.effects.push(effect);
        report(
            "effect",
            effect.name(),
            counter.instructions(|| {
                black_box(extended.normal_force(black_box(&STATES[2]), black_box(&MEMORY)));
            }),
        );
    }
    let friction = table::friction();
    let [_, _, slip, _] = table::slip_cases();
    let f = friction.force(&slip.relative_velocity, &slip.normal, slip.normal_force);
    report(
        "friction",
        "step",
        counter.instructions(|| {
            let s = black_box(&slip);
            black_box(friction.force(&s.relative_velocity, &s.normal, s.normal_force));
        }),
    );
    report(
        "wrench",
        "eq1",
        counter.instructions(|| {
            let s = black_box(&slip);
            black_box(ContactWrench::assemble(
                s.normal_force,
                &s.normal,
                &f,
                &s.arm_1,
                &s.arm_2,
            ));
        }),
    );
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // hcm-core never panics; should anything else, fail the run (the message would
    // cost kilobytes of formatting code).
    harness::exit(debug::EXIT_FAILURE)
}
