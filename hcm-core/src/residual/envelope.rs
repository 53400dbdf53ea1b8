//! The training envelope: the box of inputs the residual was trained on, widened by a
//! tolerance per input, and the report of which input left it and by how much.
//!
//! An input that was constant in training (the ball's approach speed δ̇0 is the same
//! in every run) has min = max: without a tolerance, a controller whose measured δ̇0
//! differs in the seventh digit would silently get physics only. The host sets each
//! input's tolerance from the data when it exports the network (see
//! `hcm_host::train::envelope_tolerance`): the inputs are compared with
//! [min − tolerance, max + tolerance].

/// The box of inputs the network was trained on, in raw units: outside it the
/// residual is an extrapolation and the hybrid model switches it off.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Envelope<const INPUTS: usize> {
    /// Smallest value of each input seen in training (the input's unit).
    pub min: [f32; INPUTS],
    /// Largest value of each input seen in training (the input's unit).
    pub max: [f32; INPUTS],
    /// How far beyond [min, max] each input still counts as inside (the input's
    /// unit, finite and ≥ 0).
    pub tolerance: [f32; INPUTS],
}

/// Where an input left the envelope: [`Envelope::excursion`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Excursion {
    /// Index of the input in the residual's input vector (for the 1D examples 0 = δ,
    /// 1 = δ̇, 2 = δ̇0).
    pub input: usize,
    /// How far the input lies beyond its tolerated bound, min − tolerance or
    /// max + tolerance (the input's unit, > 0; +∞ for an infinite input, NaN for NaN).
    pub distance: f32,
}

impl<const INPUTS: usize> Envelope<INPUTS> {
    /// Every finite input is inside.
    pub const fn unbounded() -> Self {
        Envelope {
            min: [-f32::MAX; INPUTS],
            max: [f32::MAX; INPUTS],
            tolerance: [0.0; INPUTS],
        }
    }

    /// min_i − tolerance_i ≤ x_i ≤ max_i + tolerance_i for every input; false if any
    /// input is NaN.
    #[inline]
    pub fn contains(&self, input: &[f32; INPUTS]) -> bool {
        let mut inside = true;
        // No early exit: a fixed sequence of compares, which the compiler vectorises.
        for (x, (lower, upper)) in input.iter().zip(self.bounds()) {
            inside &= lower <= *x && *x <= upper;
        }
        inside
    }

    /// How far each input lies outside its tolerated bound (the input's unit): 0
    /// inside, > 0 outside, NaN for a NaN input.
    pub fn distances(&self, input: &[f32; INPUTS]) -> [f32; INPUTS] {
        let mut distance = [0.0; INPUTS];
        for ((d, x), (lower, upper)) in distance.iter_mut().zip(input).zip(self.bounds()) {
            *d = if x.is_nan() {
                f32::NAN
            } else if *x < lower {
                lower - x
            } else if *x > upper {
                x - upper
            } else {
                0.0
            };
        }
        distance
    }

    /// The first input (lowest index) outside the envelope and its distance, or `None`
    /// if every input is inside.
    pub fn excursion(&self, input: &[f32; INPUTS]) -> Option<Excursion> {
        self.distances(input)
            .into_iter()
            .enumerate()
            .find(|(_, distance)| *distance != 0.0)
            .map(|(input, distance)| Excursion { input, distance })
    }

    /// (min − tolerance, max + tolerance) of each input.
    #[inline]
    fn bounds(&self) -> impl Iterator<Item = (f32, f32)> + '_ {
        self.min
            .iter()
            .zip(&self.max)
            .zip(&self.tolerance)
            .map(|((min, max), tolerance)| (min - tolerance, max + tolerance))
    }
}
