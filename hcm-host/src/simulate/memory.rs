//! What each contact point remembers of its current contact: the approach speed δ̇0
//! latched at its touch-down (Lankarani–Nikravesh, Flores) and its deepest indentation
//! δ_max (plasticity), keyed by the point's feature id.
//!
//! The history changes only between accepted solver steps ([`PointMemory::latch`]).
//! A point not yet latched reads δ̇0 = its current δ̇ and δ_max = its current δ — the
//! values a latch at this instant would store — so the force is continuous when the
//! latch happens and the solver needs no restart. A point that touches down inside a
//! step therefore sees δ̇0 follow δ̇ until the step ends; at touch-down the force is
//! ~0 and δ̇ nearly constant over one (short, in-contact) step, so the error is the
//! change of δ̇ over that step.

use hcm_core::effect::ContactMemory;
use hcm_core::model::MAX_POINTS;

/// One point's history.
#[derive(Clone, Copy, Debug, PartialEq)]
struct History {
    feature: u32,
    approach_speed: f64,
    max_depth: f64,
}

/// The history of every point of one contact pair.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointMemory {
    points: heapless::Vec<History, MAX_POINTS>,
}

impl PointMemory {
    /// (δ̇0 (m/s), memory with δ_max (m)) of the point `feature` at depth δ (m) and rate
    /// δ̇ (m/s).
    #[inline]
    pub fn recall(&self, feature: u32, depth: f64, rate: f64) -> (f64, ContactMemory<f64>) {
        match self.points.iter().find(|h| h.feature == feature) {
            Some(h) => (
                h.approach_speed,
                ContactMemory {
                    max_depth: h.max_depth.max(depth),
                },
            ),
            None => (rate, ContactMemory { max_depth: depth }),
        }
    }

    /// Keeps the history of the points in `touching` (feature, δ (m), δ̇ (m/s)) —
    /// latching new ones, deepening δ_max — and forgets the points that let go.
    pub fn latch(&mut self, touching: impl Iterator<Item = (u32, f64, f64)>) {
        let mut next = heapless::Vec::new();
        for (feature, depth, rate) in touching {
            let (approach_speed, memory) = self.recall(feature, depth, rate);
            // A manifold has at most MAX_POINTS points: the push cannot fail.
            let _ = next.push(History {
                feature,
                approach_speed,
                max_depth: memory.max_depth,
            });
        }
        self.points = next;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_keeps_its_touch_down_speed_and_deepest_indentation_until_it_lets_go() {
        let mut memory = PointMemory::default();
        assert_eq!(memory.recall(3, 1e-6, 1.0).0, 1.0);
        memory.latch([(3, 1e-6, 1.0)].into_iter());
        memory.latch([(3, 5e-5, 0.2), (5, 1e-7, 0.9)].into_iter());
        let (speed, deep) = memory.recall(3, 2e-5, -0.5);
        assert_eq!((speed, deep.max_depth), (1.0, 5e-5));
        assert_eq!(memory.recall(5, 1e-7, 0.3).0, 0.9);
        memory.latch([(5, 1e-7, 0.3)].into_iter());
        assert_eq!(memory.recall(3, 1e-6, -0.7).0, -0.7, "3 let go: forgotten");
    }
}
