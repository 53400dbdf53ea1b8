//! The peg-in-hole's hybrid model on the controller, compiled twice like the
//! ball's table (`../cases`): into the peg's firmware images and into the host test
//! `tests/controller/firmware.rs`, which evaluates the same states in f32 on the host and requires
//! every printed bit pattern to match.
//!
//! For each peg state it runs the whole HCM as the simulator does, in `f32`: the peg's
//! box against the block's five boxes (`hcm_core::geometry::compound`), each touching
//! point's indentation rate from the peg's motion, IMPACT + STEP friction at every
//! point summed by Eq 1, and the residual wrench (the 13-32-32-6 network of
//! `examples/blobs/peg_in_hole.*.hcm`) at the peg's centre of mass
//! (`ContactModel::pair_load`).
//!
//! One image per weight format (`cargo run --release --bin peg-f32`, `--bin
//! peg-int8`), as a controller ships the one network it runs: with both blobs (11.3 kB)
//! one image was 38,968 B, over the 32 KiB a firmware is allowed; each alone fits
//! (the README's controller section has the sizes).

mod states;

use hcm_core::effect::ContactMemory;
use hcm_core::friction::VelocityStepFriction;
use hcm_core::geometry::{compound, Cuboid};
use hcm_core::law::{AnyNormalLaw, Impact, Indentation};
use hcm_core::model::{ContactModel, ContactPoint, Evaluated, Manifold, PairLoad, Residual};
use hcm_core::residual::{decode, BlobError, F32Weights, Int8Weights, Mlp, WeightFormat};
use hcm_core::rigid::RigidState;
use hcm_core::vector;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
pub use states::{PEG_STATES, STATE_NAMES};

/// The peg's residual: 13 inputs (position (m), orientation quaternion w, x, y, z (–),
/// velocity (m/s), body-frame angular velocity (rad/s)), two hidden layers of 32, six
/// outputs (force (N) and torque (N·m) error on the peg, world frame, about its centre
/// of mass), weights stored as `Q`.
pub type PegResidual<Q> = Mlp<13, 32, 6, 2, Q>;

/// A weight format the peg's residual was exported in: its blob (`hcm reproduce
/// peg-in-hole`, shipped in `examples/blobs/`) and the names its results print under.
pub trait PegWeights: WeightFormat {
    /// The exported blob.
    #[allow(dead_code)] // decoded by the images' build script and the host test
    const BLOB: &'static [u8];
    /// The format's name in the printed lines (`f32`, `int8`).
    const NAME: &'static str;
    /// Group of the HCM's loads: `peg_` + [`PegWeights::NAME`].
    const LOAD_GROUP: &'static str;
    /// Group of the residual's raw outputs: `peg_residual_` + [`PegWeights::NAME`].
    const RESIDUAL_GROUP: &'static str;
    /// Whether the image reads its network through `black_box` (see `Held` in
    /// `image.rs`): int8 only, where it pays.
    #[allow(dead_code)] // read by the images, not by the host test
    const HIDE_ADDRESS: bool;
}

impl PegWeights for F32Weights {
    const BLOB: &'static [u8] = include_bytes!("../../../examples/blobs/peg_in_hole.f32.hcm");
    const NAME: &'static str = "f32";
    const LOAD_GROUP: &'static str = "peg_f32";
    const RESIDUAL_GROUP: &'static str = "peg_residual_f32";
    const HIDE_ADDRESS: bool = false;
}

impl PegWeights for Int8Weights {
    const BLOB: &'static [u8] = include_bytes!("../../../examples/blobs/peg_in_hole.int8.hcm");
    const NAME: &'static str = "int8";
    const LOAD_GROUP: &'static str = "peg_int8";
    const RESIDUAL_GROUP: &'static str = "peg_residual_int8";
    const HIDE_ADDRESS: bool = true;
}

/// Where results go: group, item, raw bits (as in `../cases`).
pub type Emit<'a> = &'a mut dyn FnMut(&str, &str, &[u32]);

/// The peg's half extents (m), scenarios/peg_in_hole.toml.
const PEG_HALF_EXTENTS: [f32; 3] = [0.01, 0.01, 0.04];

/// The block's parts, scenarios/peg_in_hole.toml (the block sits at the origin,
/// unrotated): half extents (m) and centre (m) of the bottom and the four walls.
const BLOCK_PARTS: [([f32; 3], [f32; 3]); 5] = [
    ([0.03, 0.03, 0.005], [0.0, 0.0, -0.005]),
    ([0.009, 0.03, 0.025], [0.021, 0.0, 0.025]),
    ([0.009, 0.03, 0.025], [-0.021, 0.0, 0.025]),
    ([0.012, 0.009, 0.025], [0.0, 0.021, 0.025]),
    ([0.012, 0.009, 0.025], [0.0, -0.021, 0.025]),
];

/// The peg's PM2, copied from examples/blobs/peg_in_hole.pm2.toml (the firmware parses
/// nothing at run time): IMPACT with k (N/m^e), e (–), d_max (N·s/m), δ_max (m).
/// `const`: the images hold their model in a `static` (see `image.rs`).
pub const fn peg_pm2() -> Impact<f32> {
    Impact {
        stiffness: 56053002968.84516_f64 as f32,
        exponent: 2.2,
        max_damping: 2813.1546034602707_f64 as f32,
        full_damping_depth: 0.0009941576135986967_f64 as f32,
    }
}

/// The PM2's STEP friction: μ_s, μ_d (–), v_s, v_d (m/s), from the same file.
pub const fn peg_friction() -> VelocityStepFriction<f32> {
    VelocityStepFriction {
        static_coefficient: 0.34490888769866723_f64 as f32,
        dynamic_coefficient: 0.1452826417926094_f64 as f32,
        stiction_speed: 0.00043000131451804735_f64 as f32,
        dynamic_speed: 0.0034786410828258115_f64 as f32,
    }
}

/// The peg's HCM — the PM2, its friction and `residual` — built at run time, as the
/// host test builds it. The images build the same model as a `static` instead
/// (`image.rs`), which lets the compiler see which law it holds.
#[allow(dead_code)] // used by the host test only
pub fn peg_hcm<R>(residual: R) -> ContactModel<f32, R> {
    ContactModel::physics(AnyNormalLaw::from(peg_pm2()))
        .with_friction(peg_friction())
        .with_residual(residual)
}

/// Decodes the embedded blob of `Q`; fails only if it is not a valid 13-32-32-6 blob
/// of `Q`. The images' build script (`hcm-firmware/build.rs`) decodes with it and
/// writes the network into the image; the host test decodes with it and compares.
#[allow(dead_code)] // not in the images: the build decoded their networks
pub fn decode_network<Q: PegWeights>() -> Result<PegResidual<Q>, BlobError> {
    decode(Q::BLOB)
}

/// The block's boxes in the world frame.
#[allow(dead_code)] // used by the `breakdown` feature of the peg images only
pub fn block_parts() -> [Cuboid<f32>; 5] {
    BLOCK
}

/// The block's boxes in the world frame, from [`BLOCK_PARTS`]. A constant, read in
/// place: built on the stack at every call it took 70 instructions per manifold.
static BLOCK: [Cuboid<f32>; 5] = {
    let mut parts = [part(BLOCK_PARTS[0]); 5];
    let mut i = 1;
    while i < parts.len() {
        parts[i] = part(BLOCK_PARTS[i]);
        i += 1;
    }
    parts
};

/// [`BLOCK`] prepared when the image is built ([`compound::Part::of_f32`]): each
/// part's frame, bounds and sums read from flash rather than worked out at every
/// manifold (6,126 → 5,307 instructions per manifold, and 40 B less flash:
/// the code dropped outweighs the 480 B table).
static PREPARED: [compound::Part<f32>; 5] = {
    let mut parts = [compound::Part::of_f32(BLOCK[0]); 5];
    let mut i = 1;
    while i < parts.len() {
        parts[i] = compound::Part::of_f32(BLOCK[i]);
        i += 1;
    }
    parts
};

/// One of [`BLOCK_PARTS`] as an unrotated box.
const fn part((half, centre): ([f32; 3], [f32; 3])) -> Cuboid<f32> {
    Cuboid {
        half_extents: Vector3::new(half[0], half[1], half[2]),
        center: Vector3::new(centre[0], centre[1], centre[2]),
        orientation: UnitQuaternion::new_unchecked(Quaternion::new(1.0, 0.0, 0.0, 0.0)),
    }
}

/// The touching points of the peg in `state` with the block, each with its
/// indentation rate from the peg's motion; every point taken at its touch-down (δ̇0 =
/// δ̇, nothing remembered), as a controller evaluating one state holds it.
pub fn manifold(state: &RigidState<f32>) -> Manifold<f32> {
    let mut points = Manifold::new();
    manifold_into(state, &mut points);
    points
}

/// [`manifold`] into the empty `points`, in place: returned by value, the 516-byte
/// manifold was copied once more (about 450 instructions per peg HCM).
pub fn manifold_into(state: &RigidState<f32>, points: &mut Manifold<f32>) {
    // The orientation once (a square root): `world_angular_velocity` would normalise
    // the quaternion again. ω = R·ω_body as that method computes it.
    let orientation = state.orientation();
    let omega = vector::rotate(&orientation, &state.body_angular_velocity());
    let velocity = state.velocity();
    let peg = Cuboid {
        half_extents: Vector3::from(PEG_HALF_EXTENTS),
        center: state.position(),
        orientation,
    };
    for g in &compound::prepared_contacts(&peg, &PREPARED) {
        // The block is fixed: the relative velocity is the peg's material point's,
        // v + ω × (p − c), per component in nalgebra's order (`hcm_core::vector`: the
        // same bits; nalgebra's generic loops cost several times the arithmetic).
        let arm = vector::sub(&g.point, &peg.center);
        let relative_velocity = vector::add(&velocity, &vector::cross(&omega, &arm));
        let rate = -vector::dot(&relative_velocity, &g.normal);
        // Both hold at most MAX_POINTS: the push cannot fail.
        let _ = points.push(ContactPoint {
            indentation: Indentation {
                depth: g.depth,
                rate,
                approach_speed: rate,
            },
            memory: ContactMemory::touch_down(),
            normal: g.normal,
            position: g.point,
            relative_velocity,
            relative_angular_velocity: omega,
        });
    }
}

/// A full manifold for the host's checks and benchmarks: the peg's contact points at
/// `state` repeated with shifted positions (m), depths and slips (m/s) up to the 8 a box
/// in a rectangular hole can touch at; empty where the peg touches nothing.
#[allow(dead_code)] // used by hcm-ffi's pair_load test and benches/peg_hcm.rs only
pub fn eight_points(state: &RigidState<f32>) -> Manifold<f32> {
    let manifold = manifold(state);
    let mut points = Manifold::new();
    for i in 0..hcm_core::model::MAX_POINTS {
        let Some(mut point) = manifold.get(i % manifold.len().max(1)).copied() else {
            break;
        };
        let s = i as f32;
        point.position += Vector3::new(1e-3 * s, -2e-3 * s, 5e-4 * s);
        point.indentation.depth *= 1.0 + 0.1 * s;
        point.relative_velocity += Vector3::new(0.01 * s, 0.0, -0.02 * s);
        // At most MAX_POINTS pushes: it cannot fail.
        let _ = points.push(point);
    }
    points
}

/// The HCM's loads on the peg in `state` (the state is the residual's input).
#[inline]
pub fn peg_load<R: Residual<f32>>(
    model: &ContactModel<f32, R>,
    state: &RigidState<f32>,
) -> PairLoad<f32> {
    let mut points = Manifold::new();
    manifold_into(state, &mut points);
    model.pair_load(
        &points,
        &state.position(),
        &Vector3::zeros(),
        &state.components,
    )
}

/// Every peg state: its inputs, then the HCM's force (N) and torque (N·m) on the peg,
/// the summed normal force (N), the number of touching points and 1 if the residual
/// took part; and the residual's own six outputs. `hcm` is the peg's HCM over
/// `network` ([`peg_hcm`]).
pub fn evaluate_all<Q: PegWeights, R: Residual<f32>>(
    hcm: &ContactModel<f32, R>,
    network: &PegResidual<Q>,
    emit: Emit<'_>,
) {
    for (state, name) in PEG_STATES.iter().zip(STATE_NAMES) {
        let state = RigidState { components: *state };
        emit("input", name, &state.components.map(f32::to_bits));
        emit(Q::LOAD_GROUP, name, &load_bits(hcm, &state));
        let raw = network.evaluate(&state.components);
        emit(Q::RESIDUAL_GROUP, name, &raw.map(f32::to_bits));
    }
}

fn load_bits<R: Residual<f32>>(model: &ContactModel<f32, R>, state: &RigidState<f32>) -> [u32; 9] {
    let load = peg_load(model, state);
    let (force, torque) = (&load.wrench.force_1, &load.wrench.torque_1);
    // Written out: a loop over the force and torque chained took 132 B more flash.
    [
        force.x.to_bits(),
        force.y.to_bits(),
        force.z.to_bits(),
        torque.x.to_bits(),
        torque.y.to_bits(),
        torque.z.to_bits(),
        load.normal_force.to_bits(),
        // A manifold holds at most 8 points: the cast is lossless.
        manifold(state).len() as u32,
        u32::from(load.evaluated == Evaluated::PhysicsAndResidual),
    ]
}
