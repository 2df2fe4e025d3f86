//! Friction laws, one file each. Plain functions of state and velocity: no FMI, no solver.

pub mod coulomb;
pub mod dahl;
pub mod lugre;
pub mod lugre2d;
pub mod regularized;

/// Exact solution of `z' = a*(z_ss - z)` over `h` for constant `a >= 0`, `z_ss`:
/// returns `(z(h), integral of z over [0, h])`.
///
/// This is the zero-order-hold update of a bristle equation whose velocity is frozen over the
/// step: stable and exact however stiff `a*h` is (explicit Euler would need `h < 2/a`).
pub fn relax(z0: f64, z_ss: f64, a: f64, h: f64) -> (f64, f64) {
    let ah = a * h;
    if ah < 1e-300 {
        return (z0, z0 * h);
    }
    let decay = (-ah).exp();
    // (1 - e^{-ah})/a, written with exp_m1 so it stays accurate when a*h is tiny.
    let weight = -(-ah).exp_m1() / a;
    (z_ss + (z0 - z_ss) * decay, z_ss * h + (z0 - z_ss) * weight)
}

/// sgn with sgn(0) = 0, as the papers use it.
pub fn sgn(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::relax;

    #[test]
    fn relax_matches_closed_form_and_is_stable_when_stiff() {
        let (z, integral) = relax(1.0, 3.0, 2.0, 0.5);
        let exact = 3.0 - 2.0 * (-1.0f64).exp();
        assert!((z - exact).abs() < 1e-15);
        // integral of 3 - 2 e^{-2t} over [0, 0.5] = 1.5 - (1 - e^{-1})
        let exact_integral = 1.5 - (1.0 - (-1.0f64).exp());
        assert!((integral - exact_integral).abs() < 1e-15);
        let (z, integral) = relax(1.0, 3.0, 1e12, 1.0);
        assert_eq!(z, 3.0);
        assert!((integral - 3.0).abs() < 1e-11);
    }
}
