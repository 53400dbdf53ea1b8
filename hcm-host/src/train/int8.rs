//! The int8 storage of a weight row, shared by the quantisation-aware training (which
//! trains against it) and the export (which writes it).

/// One weight row in the int8 storage: levels q = round(w / s) in −127…127 and the
/// row's f32 scale s = max|w| / 127 (1 for an all-zero row); the core sums q times its
/// integer activations and scales the sum by s.
/// Finite weights expected (the encoder checks them first).
pub fn int8_row(row: &[f64]) -> (Vec<i8>, f32) {
    let largest = row.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
    // The f32 scale the core multiplies by; quantise against it, not its f64 twin.
    let scale = match (largest / 127.0) as f32 {
        s if s > 0.0 && s.is_finite() => s,
        _ => 1.0,
    };
    let levels = row
        .iter()
        .map(|w| (w / f64::from(scale)).round().clamp(-127.0, 127.0) as i8)
        .collect();
    (levels, scale)
}
