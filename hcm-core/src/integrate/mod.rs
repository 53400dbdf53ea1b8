//! Adaptive ODE integration with dense output and event location.
//!
//! [`Dopri5`] integrates y' = f(t, y) (t in s; the units of y are the caller's) with
//! the Dormand–Prince 5(4) pair (Dormand & Prince 1980) under error control, one
//! accepted step per call, and keeps Shampine's 4th-order continuous extension of the
//! last step (as in the DOPRI5 code of Hairer, Nørsett & Wanner, *Solving Ordinary
//! Differential Equations I*). [`locate_crossing`] finds where an event function (a
//! gap, a velocity) changes sign inside that step, and [`Dopri5::restart`] continues
//! from the event after the caller has changed the system (a contact began, an
//! approach speed was latched).
//!
//! ## When to use it
//!
//! For simulating a contact as the paper's laws describe it: a smooth free-flight phase
//! of many milliseconds and a contact of microseconds whose start and end must be found
//! precisely (the approach speed δ̇0 is latched at touch-down; restitution is read at
//! lift-off). A fixed-step method must use the contact's step all along or miss the
//! instants; this one takes long steps in flight, short ones in contact, and locates
//! touch-down and lift-off to a time tolerance (1e-12 s is reachable in f64).
//! [`OdeSystem::step_limit`] (e.g. gap / closing speed) keeps a step from jumping over a
//! whole contact.
//!
//! It is explicit: for a contact stiffer than the tolerance lets it follow, the steps
//! shrink to the contact's natural period and [`Settings::max_steps`] bounds the run.
//! Like the laws, it is `no_std`, allocates nothing, and never panics: every failure is
//! an [`IntegrationError`].
//!
//! ## Example
//!
//! A body falling from 0.1 m (state [z (m), v (m/s)]), stopped at z = 0:
//!
//! ```
//! use hcm_core::integrate::{locate_crossing, Dopri5, OdeSystem, Settings};
//!
//! struct Fall;
//! impl OdeSystem<f64, [f64; 2]> for Fall {
//!     fn derivative(&mut self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
//!         *dy = [y[1], -9.81];
//!     }
//! }
//!
//! let mut stepper = Dopri5::new(&mut Fall, 0.0, [0.1, 0.0], Settings::new(1e-10, 1e-12));
//! let mut scratch = [0.0; 2];
//! let impact = loop {
//!     stepper.step(&mut Fall, 1.0)?;
//!     if let Some(t) = locate_crossing(&stepper, |_, y| y[0], 1e-12, &mut scratch) {
//!         break t;
//!     }
//! };
//! assert!((impact - (2.0 * 0.1 / 9.81_f64).sqrt()).abs() < 1e-11);
//! # Ok::<(), hcm_core::integrate::IntegrationError>(())
//! ```

mod dense;
mod dopri5;
mod error;
mod event;
mod hermite;
mod interval;
mod rodas4;
mod state;
mod vector;

pub use dense::DenseOutput;
pub use dopri5::{Dopri5, Settings};
pub use error::IntegrationError;
pub use event::locate_crossing;
pub use hermite::{cubic_hermite, hermite_zero};
pub use rodas4::Rodas4;
pub use state::{LinearlyImplicit, OdeState, OdeSystem};
