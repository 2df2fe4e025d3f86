//! The phase of a periodic forcing in turns ([`turns`]), and cos(2 pi x) for a phase `x` in turns,
//! for periodic forcing that a right-hand side evaluates at every stage. libm's cos plus the
//! reduction `fract` cost a large part of scene T's right-hand side (docs/performance.md,
//! "Measurements behind the code"); reducing in turns is exact, which leaves two short polynomials.
//!
//! Both polynomials are evaluated every time, by Estrin's scheme, and the quadrant picks one
//! without a branch: Horner's chain of eight dependent products, and a quadrant branch that the
//! stages of a step (which fall in different quadrants) mispredict, made this a large share of
//! scene T's run time (docs/performance.md, "Benchmarks", Cost of a step).

use std::f64::consts::FRAC_PI_2;

/// c0 + c1 x + ... + c7 x^7 by Estrin's scheme: four independent pairs joined by x^2 and x^4,
/// a chain of four products where Horner's has eight.
#[inline(always)]
fn estrin(c: &[f64; 8], x: f64) -> f64 {
    let x2 = x * x;
    let x4 = x2 * x2;
    let p01 = c[0] + c[1] * x;
    let p23 = c[2] + c[3] * x;
    let p45 = c[4] + c[5] * x;
    let p67 = c[6] + c[7] * x;
    (p01 + x2 * p23) + x4 * (p45 + x2 * p67)
}

/// sin(a) for |a| <= pi/4 by its Taylor series to a^17 (next term < 3e-20), given a^2:
/// a + a^3 (s1 + s2 a^2 + ... + s8 a^14).
#[inline(always)]
fn sin_quarter(a: f64, a2: f64) -> f64 {
    const S: [f64; 8] = [
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
        -1.0 / 1_307_674_368_000.0,
        1.0 / 355_687_428_096_000.0,
    ];
    a + (a * a2) * estrin(&S, a2)
}

/// cos(a) for |a| <= pi/4 by its Taylor series to a^16 (next term < 3e-18), given a^2:
/// 1 + a^2 (c1 + c2 a^2 + ... + c8 a^14).
#[inline(always)]
fn cos_quarter(a2: f64) -> f64 {
    const C: [f64; 8] = [
        -0.5,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        -1.0 / 87_178_291_200.0,
        1.0 / 20_922_789_888_000.0,
    ];
    1.0 + a2 * estrin(&C, a2)
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
    let a2 = a * a;
    let (c, s) = (cos_quarter(a2), sin_quarter(a, a2));
    // Quadrants 0..3 of q mod 4: cos, -sin, -cos, sin.
    let v = if q & 1 == 0 { c } else { s };
    // The sign bit flips for quadrants 1 and 2, where (q + 1) & 2 is set.
    let flip = (((q + 1) & 2) as u64) << 62;
    f64::from_bits(v.to_bits() ^ flip)
}

/// The fraction of a turn of `t f` in [0, 1), to the rounding of one sum: the product is split
/// exactly into its rounded value and its error (fma), and only their fractions are added. A
/// forcing evaluated as phase0 + tau f over a step (tau from the step's start) then keeps its
/// phase however large t is, where t f itself has lost its fraction's digits.
pub fn turns(t: f64, f: f64) -> f64 {
    let product = t * f;
    let error = t.mul_add(f, -product);
    (product.fract() + error.fract()).rem_euclid(1.0)
}

#[cfg(test)]
mod tests {
    use super::{cos_turns, turns};

    /// Oracle: exact rational arithmetic. t = k/f + 1/8 period is an exact binary fraction
    /// whatever k, so its phase is 1/8 turn; t f rounded in one product loses it at large k.
    #[test]
    fn turns_keeps_the_phase_of_large_times() {
        let f = 4096.0;
        for k in [0.0, 1.0, 3e9, 1e12, 4.5e14] {
            let t = k / f + 0.125 / f;
            assert_eq!(turns(t, f), 0.125, "k = {k}");
        }
        // 3000 Hz is not a power of two: against the phase computed in i128 nanosecond units.
        let f = 3000.0;
        for seconds in [1e5_f64, 3e5, 1e6] {
            let t = seconds + 1.1e-4;
            let (mantissa, exponent) = {
                let bits = t.to_bits();
                let e = ((bits >> 52) & 0x7ff) as i32 - 1075;
                ((bits & ((1 << 52) - 1)) | (1 << 52), e)
            };
            // t f = mantissa 3000 2^exponent, exponent < 0: its fraction from integers.
            let scaled = i128::from(mantissa) * 3000;
            let denominator = 1i128 << (-exponent);
            let exact = (scaled % denominator) as f64 / denominator as f64;
            assert!(
                (turns(t, f) - exact).abs() < 1e-15,
                "{seconds}: {}",
                turns(t, f)
            );
        }
    }

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
