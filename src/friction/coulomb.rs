//! Coulomb friction: `FT = FC sgn(vr)` (Leus & Gutowski, eq. 2.5), a rigid contact.

use super::sgn;

pub fn force(fc: f64, v: f64) -> f64 {
    fc * sgn(v)
}

/// Mean of `FC sgn(vc + va cos(wt))` over one period: the fraction of the period with vr > 0
/// minus the fraction with vr < 0. This is the exact oracle for the Coulomb column of Table 1.
pub fn mean_under_vibration(fc: f64, vc: f64, va: f64) -> f64 {
    if vc.abs() >= va {
        force(fc, vc)
    } else {
        fc * std::f64::consts::FRAC_2_PI * (vc / va).asin()
    }
}
