//! Hairer's starting step for the explicit pairs (dopri5, dop853), when a call has no step from
//! the last one to go on with.

/// A step over which an Euler step's error would be about the tolerance, scaled down with the
/// pair's `order` (its error estimate's, 5 or 8) and held to `span` and `h_max`: `y` and its
/// rate `k1` at the start, per-state `atol` and the common `rtol`.
pub(super) fn starting_step(
    (y, k1): (&[f64], &[f64]),
    (rtol, atol): (f64, &[f64]),
    (span, h_max): (f64, f64),
    order: u8,
) -> f64 {
    let (mut d0, mut d1) = (0.0, 0.0);
    for j in 0..y.len() {
        let scale = atol[j] + rtol * y[j].abs();
        d0 += (y[j] / scale).powi(2);
        d1 += (k1[j] / scale).powi(2);
    }
    let h = if d0 < 1e-10 || d1 < 1e-10 {
        1e-6 * span
    } else {
        0.01 * (d0 / d1).sqrt()
    };
    h.min(span).min(h_max) * rtol.powf(1.0 / f64::from(order)).max(1e-3)
}
