//! cos(2 pi x) for a phase `x` in turns, for periodic forcing that a right-hand side evaluates
//! at every stage. libm's cos plus the reduction `fract` cost about as much as the rest of scene
//! T's right-hand side; reducing in turns is exact, which leaves two short polynomials.

use std::f64::consts::FRAC_PI_2;

/// sin(a) for |a| <= pi/4 by its Taylor series to a^15 (next term < 5e-17).
#[inline]
fn sin_quarter(a: f64) -> f64 {
    let a2 = a * a;
    let mut p = -1.0 / 1_307_674_368_000.0;
    p = p * a2 + 1.0 / 6_227_020_800.0;
    p = p * a2 - 1.0 / 39_916_800.0;
    p = p * a2 + 1.0 / 362_880.0;
    p = p * a2 - 1.0 / 5040.0;
    p = p * a2 + 1.0 / 120.0;
    p = p * a2 - 1.0 / 6.0;
    a + a * a2 * p
}

/// cos(a) for |a| <= pi/4 by its Taylor series to a^16 (next term < 3e-18).
#[inline]
fn cos_quarter(a: f64) -> f64 {
    let a2 = a * a;
    let mut p = 1.0 / 20_922_789_888_000.0;
    p = p * a2 - 1.0 / 87_178_291_200.0;
    p = p * a2 + 1.0 / 479_001_600.0;
    p = p * a2 - 1.0 / 3_628_800.0;
    p = p * a2 + 1.0 / 40_320.0;
    p = p * a2 - 1.0 / 720.0;
    p = p * a2 + 1.0 / 24.0;
    p = p * a2 - 0.5;
    1.0 + a2 * p
}

/// cos(2 pi x), to about 2e-16 absolute. Always inlined: a call and its register spills cost
/// as much as the reduction.
#[inline(always)]
pub fn cos_turns(x: f64) -> f64 {
    // Below 2^52 the integer part is exact in an i64 and x minus it is exact: the whole error is
    // that of the short polynomial.
    if x.is_nan() || x.abs() >= 4.5e15 {
        return (std::f64::consts::TAU * x.fract()).cos();
    }
    let r = x - (x as i64) as f64;
    // Quarter turns, and the nearest whole quarter q (u + 4.5 > 0, so truncation is floor).
    let u = 4.0 * r;
    let q = (u + 4.5) as i64 - 4;
    let a = (u - q as f64) * FRAC_PI_2;
    match q.rem_euclid(4) {
        0 => cos_quarter(a),
        1 => -sin_quarter(a),
        2 => -cos_quarter(a),
        _ => sin_quarter(a),
    }
}

#[cfg(test)]
mod tests {
    use super::cos_turns;

    /// Oracle: libm's cos on the same phase, over a grid of phases (negative ones and many
    /// turns included).
    #[test]
    fn agrees_with_libm() {
        let mut worst: f64 = 0.0;
        for i in -20_000..20_000 {
            let x = f64::from(i) * 0.000_731_3 + 1e-3;
            let exact = (std::f64::consts::TAU * x.fract()).cos();
            worst = worst.max((cos_turns(x) - exact).abs());
        }
        for x in [
            0.0,
            0.25,
            0.5,
            0.75,
            1.0,
            3000.125,
            1e9 + 0.3,
            -7.75,
            1e17,
            f64::NAN,
        ] {
            let exact = (std::f64::consts::TAU * x.fract()).cos();
            let got = cos_turns(x);
            assert!(
                (got - exact).abs() < 1e-15 || (got.is_nan() && exact.is_nan()),
                "{x}: {got}"
            );
        }
        assert!(worst < 1e-15, "{worst}");
    }
}
