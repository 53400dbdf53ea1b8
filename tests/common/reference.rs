//! The reference setup of docs/reconstruction.md (steel ball on concrete),
//! shared by the law tests and benchmarks so that every law is exercised at the
//! parameters the paper's examples use.

use hcm_core::geometry::{effective_modulus, sphere_plane, Material};
use hcm_core::law::{
    AnyNormalLaw, Flores, Hertz, HuntCrossley, Impact, LankaraniNikravesh, VariableStiffness,
};
use hcm_core::Real;

/// Ball radius r (m).
pub const BALL_RADIUS: f64 = 0.0127;
/// Ball mass m (kg): steel, ρ = 7800 kg/m³.
pub const BALL_MASS: f64 = 0.06693;
/// Impact speed after a 0.1 m drop (m/s).
pub const IMPACT_SPEED: f64 = 1.4007;

/// The ball's steel: Young's modulus E = 206 GPa, Poisson's ratio ν = 0.3.
pub fn steel<T: Real>() -> Material<T> {
    Material {
        youngs_modulus: T::of(2.06e11),
        poisson_ratio: T::of(0.3),
    }
}

/// The ground's concrete: Young's modulus E = 25.193 GPa, Poisson's ratio ν = 0.25.
pub fn concrete<T: Real>() -> Material<T> {
    Material {
        youngs_modulus: T::of(2.5193e10),
        poisson_ratio: T::of(0.25),
    }
}

/// Eq 3 stiffness of the ball on the ground (N/m^1.5).
pub fn hertz_stiffness<T: Real>() -> T {
    sphere_plane::hertz_stiffness(&steel(), &concrete(), T::of(BALL_RADIUS))
}

/// Hertz's law (Eq 2) for the ball on the ground: the Eq 3 stiffness, exponent 1.5.
pub fn hertz<T: Real>() -> Hertz<T> {
    Hertz {
        stiffness: hertz_stiffness(),
        exponent: T::of(1.5),
    }
}

/// The reference's Lankarani–Nikravesh fit to the ball.
pub fn lankarani_nikravesh<T: Real>() -> LankaraniNikravesh<T> {
    LankaraniNikravesh {
        stiffness: T::of(6.86e9),
        exponent: T::of(1.489),
        restitution: T::of(0.929),
    }
}

/// PM1 of the bouncing ball: c = 2, λ = 987.9 1/m.
pub fn variable_stiffness<T: Real>() -> VariableStiffness<T> {
    VariableStiffness {
        surface_loading: T::of(2.0),
        effective_modulus: effective_modulus(&steel(), &concrete()),
        radius: T::of(BALL_RADIUS),
        damping: T::of(987.9),
        effective_mass: T::of(BALL_MASS),
    }
}

/// The IMPACT law (Eq 8–9) for the ball: k = 6.86·10⁹ N/m^1.5, e = 1.5, damping
/// rising to d_max = 100 N·s/m at δ_max = 10 µm.
pub fn impact<T: Real>() -> Impact<T> {
    Impact {
        stiffness: T::of(6.86e9),
        exponent: T::of(1.5),
        max_damping: T::of(100.0),
        full_damping_depth: T::of(1e-5),
    }
}

/// Hunt–Crossley's law for the ball: k = 6.86·10⁹ N/m^1.5, n = 1.5, χ = 0.07 s/m.
pub fn hunt_crossley<T: Real>() -> HuntCrossley<T> {
    HuntCrossley {
        stiffness: T::of(6.86e9),
        exponent: T::of(1.5),
        damping: T::of(0.07),
    }
}

/// Flores' law for the ball: k = 6.86·10⁹ N/m^1.5, n = 1.5, restitution ce = 0.93.
pub fn flores<T: Real>() -> Flores<T> {
    Flores {
        stiffness: T::of(6.86e9),
        exponent: T::of(1.5),
        restitution: T::of(0.93),
    }
}

/// Every normal law at its reference parameters.
pub fn all_laws<T: Real>() -> [AnyNormalLaw<T>; 6] {
    [
        hertz().into(),
        lankarani_nikravesh().into(),
        variable_stiffness().into(),
        impact().into(),
        hunt_crossley().into(),
        flores().into(),
    ]
}
