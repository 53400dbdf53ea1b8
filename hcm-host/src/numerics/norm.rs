//! The Euclidean norm of a vector whose entries may be far from 1.

/// ‖x‖₂ without overflow or underflow for entries far from 1 (the largest |xᵢ| is
/// factored out before squaring).
pub fn euclidean_norm(x: &[f64]) -> f64 {
    let largest = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if largest == 0.0 || !largest.is_finite() {
        return largest;
    }
    largest * x.iter().map(|v| (v / largest).powi(2)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn norm_of_entries_beyond_the_square_root_of_the_range() {
        assert_eq!(euclidean_norm(&[3.0, 4.0]), 5.0);
        // Squaring these would overflow to ∞ or underflow to 0.
        assert!((euclidean_norm(&[3e200, 4e200]) / 5e200 - 1.0).abs() < 1e-15);
        assert!((euclidean_norm(&[3e-200, 4e-200]) / 5e-200 - 1.0).abs() < 1e-15);
        assert_eq!(euclidean_norm(&[]), 0.0);
    }
}
