// The body of the peg's firmware images, `include!`d by `src/bin/peg_f32.rs` and
// `src/bin/peg_int8.rs`, which differ only in the weight format `Weights` they name:
// boot, print the table of [`peg`] for the network the build decoded from the blob
// (`NETWORK`, `build.rs`), the costs and the sizes over semihosting in the ball image's
// format (`case GROUP.ITEM HEX…`, `cost GROUP.ITEM N`, `size flash|ram|stack N`, `end`),
// and exit QEMU with status 0.

#[path = "../cost.rs"]
mod cost;
#[path = "../harness.rs"]
mod harness;
#[path = "../memory.rs"]
mod memory;
#[path = "../out.rs"]
mod out;
#[path = "../peg/mod.rs"]
mod peg;
#[path = "../vectors.rs"]
mod vectors;

use core::convert::Infallible;
use core::hint::black_box;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug;
use hcm_core::effect::ExtendedLaw;
use hcm_core::friction::TangentialEffects;
use hcm_core::law::AnyNormalLaw;
use hcm_core::model::{ContactModel, Correction, Residual};
use hcm_core::residual::Excursion;
use hcm_core::rigid::RigidState;
use peg::{peg_friction, peg_load, peg_pm2, PegResidual, PegWeights, PEG_STATES};

#[entry]
fn main() -> ! {
    harness::run(
        || Ok::<_, Infallible>(network()),
        |network, emit| peg::evaluate_all(&PEG_HCM, network, emit),
        costs,
    )
}

/// The peg's HCM in this image: what `peg::peg_hcm` builds at run time, held in a
/// `static` instead. The physics is a constant of the firmware; read from a `static`,
/// the compiler sees which law, effects and tangential effects the model holds and
/// keeps the code of IMPACT + STEP alone, where a model built at run time carries
/// every law's arm, the effect loop and the tangential couples. Measured: peg-f32
/// 32,684 → 30,216 B of flash, peg-int8 29,840 → 27,388 B; 37,330 → 37,022
/// instructions per HCM.
///
/// Its residual is the image's `NETWORK`, decoded from the blob when the image is
/// built (`build.rs`) rather than at start-up into a RAM `static`: no decoder in the
/// image (`decode_network` was 2,334 B of code, with the CRC, serde's and the layers'
/// readers), no blob beside the network, no copy of it in RAM. Measured: peg-f32
/// 29,976 → 24,168 B of flash, static RAM 7,132 → 4 B, peak stack 15,792 → 3,872 B;
/// peg-int8 25,800 → 21,228 B, 4,188 → 4 B, 9,904 → 3,872 B. Instructions per HCM
/// 17,872 → 17,860 (f32) and 18,071 → 18,167 (int8: the kernels specialised on the
/// network's now constant address, which [`network`] hides since).
static PEG_HCM: ContactModel<f32, Held> = ContactModel {
    normal: ExtendedLaw {
        base: AnyNormalLaw::Impact(peg_pm2()),
        effects: heapless::Vec::new(),
    },
    friction: Some(peg_friction()),
    tangential: TangentialEffects {
        viscous_friction: None,
        torsional_resistance: None,
        rolling_resistance: None,
    },
    residual: Held,
};

/// The network as [`PEG_HCM`]'s residual, read through [`network`].
struct Held;

/// The image's network; in the int8 image its address hidden from the optimiser
/// (`black_box`). Seen as the constant it is, LLVM specialised the int8 image's layer
/// kernels on it: every weight addressed from the absolute address (an `addw` before
/// each load) and the int8 inner loop spilling an accumulator — 14,999 against 14,656
/// instructions per int8 HCM. Not in the f32 image: there the network's activation,
/// read from the constant, lets the compiler drop the other activations' code (the
/// hidden address gave −24 instructions for +1.5 kB of flash, over the 24 KiB budget).
fn network() -> &'static PegResidual<Weights> {
    if Weights::HIDE_ADDRESS {
        black_box(&NETWORK)
    } else {
        &NETWORK
    }
}

impl Residual<f32> for Held {
    #[inline]
    fn correction(&self, input: &[f32]) -> Option<Correction<f32>> {
        Residual::correction(network(), input)
    }

    #[inline]
    fn excursion(&self, input: &[f32]) -> Option<Excursion> {
        Residual::excursion(network(), input)
    }
}

/// Instructions per evaluation of the peg's contact manifold, its residual and its
/// whole HCM at the second wall contact's peak.
fn costs(
    counter: &cost::Counter,
    network: &&PegResidual<Weights>,
    report: &mut dyn FnMut(&str, &str, u32),
) {
    let state = RigidState {
        components: PEG_STATES[3],
    };
    let name = Weights::NAME;
    #[cfg(feature = "profile")]
    {
        cost::marker_start();
        for _ in 0..8 {
            black_box(peg_load(&PEG_HCM, black_box(&state)));
        }
        cost::marker_end();
        return;
    }
    report(
        "peg",
        "manifold",
        // Into a manifold in place, as `peg_load` builds it (returned by value it
        // is copied once more: 516 B, about 450 instructions).
        counter.instructions(|| {
            let mut points = hcm_core::model::Manifold::new();
            peg::manifold_into(black_box(&state), &mut points);
            black_box(&points);
        }),
    );
    #[cfg(feature = "breakdown")]
    breakdown(counter, &state, report);
    report(
        "peg_residual",
        name,
        counter.instructions(|| {
            black_box(network.evaluate(black_box(&state.components)));
        }),
    );
    report(
        "peg_hcm",
        name,
        counter.instructions(|| {
            black_box(peg_load(&PEG_HCM, black_box(&state)));
        }),
    );
    // The HCM given the manifold, in one call (`ContactModel::pair_load`: the physics
    // at each point, the residual once), as a controller with contact detection of its
    // own calls it (and C through `hcm_pair_load`).
    let points = peg::manifold(&state);
    report(
        "peg_pair",
        name,
        counter.instructions(|| {
            black_box(PEG_HCM.pair_load(
                black_box(&points),
                &state.position(),
                &nalgebra::Vector3::zeros(),
                &state.components,
            ));
        }),
    );
}

/// Sub-parts of the peg's HCM, each one's instructions counted on its own
/// (`--features breakdown`).
#[cfg(feature = "breakdown")]
fn breakdown(
    counter: &cost::Counter,
    state: &RigidState<f32>,
    report: &mut dyn FnMut(&str, &str, u32),
) {
    use hcm_core::geometry::{box_box, compound, Cuboid};
    use hcm_core::model::{ContactModel, Residual};
    use nalgebra::{UnitQuaternion, Vector3};
    let peg = Cuboid {
        half_extents: Vector3::new(0.01, 0.01, 0.04),
        center: state.position(),
        orientation: state.orientation(),
    };
    let block = peg::block_parts();
    report("peg", "compound_contacts", counter.instructions(|| {
        black_box(compound::contacts(black_box(&peg), black_box(&block)));
    }));
    for (i, part) in block.iter().enumerate() {
        let n = box_box::contacts(&peg, part).len();
        let name = ["box_box_0", "box_box_1", "box_box_2", "box_box_3", "box_box_4"][i];
        let c = counter.instructions(|| {
            black_box(box_box::contacts(black_box(&peg), black_box(part)));
        });
        report("peg", name, c * 10 + n as u32);
    }
    report("peg", "state_pose", counter.instructions(|| {
        let s = black_box(state);
        black_box((s.orientation(), s.world_angular_velocity()));
    }));
    let _ = UnitQuaternion::<f32>::identity();
    let points = peg::manifold(state);
    report("peg", "points", points.len() as u32);
    let physics = ContactModel {
        normal: PEG_HCM.normal.clone(),
        friction: PEG_HCM.friction,
        tangential: PEG_HCM.tangential,
        residual: hcm_core::model::NoResidual,
    };
    report("peg", "pair_load_physics", counter.instructions(|| {
        black_box(physics.pair_load(black_box(&points), &state.position(), &Vector3::zeros(), &state.components));
    }));
    report("peg", "pair_load_full", counter.instructions(|| {
        black_box(PEG_HCM.pair_load(black_box(&points), &state.position(), &Vector3::zeros(), &state.components));
    }));
    report("peg", "correction", counter.instructions(|| {
        black_box(PEG_HCM.residual.correction(black_box(&state.components[..])));
    }));
    let p = &points[0];
    report("peg", "law_point", counter.instructions(|| {
        let p = black_box(p);
        black_box(physics.physics_normal_force(&p.indentation, &p.memory));
    }));
    let f = physics.physics_normal_force(&p.indentation, &p.memory);
    report("peg", "friction_point", counter.instructions(|| {
        let p = black_box(p);
        black_box(physics.friction.as_ref().map(|l| l.force(&p.relative_velocity, &p.normal, black_box(f))));
    }));
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // hcm-core never panics; should anything else, fail the run.
    harness::exit(debug::EXIT_FAILURE)
}
