//! Where the bodies of a scenario touch: for each contact pair, from the two bodies'
//! poses, the single-point kinematics along a line of centres ([`pair_kinematics`]),
//! the manifold of up to eight contact points ([`pair_contacts`]), the signed
//! separation ([`pair_separation`]) and the rate along a line of centres
//! ([`pair_rate`]). The simulator, the scenario's own checks (bodies starting apart)
//! and the indicators read back from measured poses all use it.

mod kinematics;
mod manifold;
mod pose;

pub use kinematics::pair_kinematics;
pub use manifold::{pair_contacts, pair_rate, pair_separation};
pub use pose::Pose;
