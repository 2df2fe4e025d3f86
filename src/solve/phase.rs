//! The phase of a periodic forcing in turns ([`turns`]), and cos(2 pi x) and sin(2 pi x) for a
//! phase `x` in turns, for periodic forcing that a right-hand side evaluates at every stage, and
//! for closed forms evaluated as often. libm's cos plus the reduction `fract` cost a large part of
//! scene T's right-hand side (docs/performance.md, "Measurements behind the code"); reducing in
//! turns is exact, which leaves two short polynomials.
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

/// Below this |x| the integer part of x is exact in an i64 and x minus it is exact: the whole
/// error of [`cos_turns`] and [`sin_cos_turns`] is that of the short polynomials.
const EXACT_REDUCTION: f64 = 4.5e15;

/// A phase `x` in turns (|x| below [`EXACT_REDUCTION`]) as the nearest whole quarter turn q and
/// the angle a left over, |a| <= pi/4: 2 pi x = q pi/2 + a. Returns (q, a, a^2).
#[inline(always)]
fn quarters(x: f64) -> (i64, f64, f64) {
    let r = x - (x as i64) as f64;
    // u + 4.5 > 0, so truncation is floor.
    let u = 4.0 * r;
    let q = (u + 4.5) as i64 - 4;
    let a = (u - q as f64) * FRAC_PI_2;
    (q, a, a * a)
}

/// `v` with its sign flipped where bit 1 (the value 2) of `q` is set.
#[inline(always)]
fn flipped(v: f64, q: i64) -> f64 {
    f64::from_bits(v.to_bits() ^ (((q & 2) as u64) << 62))
}

/// cos(2 pi x), to about 2e-16 absolute. Always inlined: a call and its register spills cost
/// as much as the reduction.
#[inline(always)]
pub fn cos_turns(x: f64) -> f64 {
    if x.is_nan() || x.abs() >= EXACT_REDUCTION {
        return (std::f64::consts::TAU * x.fract()).cos();
    }
    let (q, a, a2) = quarters(x);
    let (c, s) = (cos_quarter(a2), sin_quarter(a, a2));
    // Quadrants 0..3 of q mod 4: cos, -sin, -cos, sin; the sign flips for quadrants 1 and 2,
    // where (q + 1) & 2 is set.
    flipped(if q & 1 == 0 { c } else { s }, q + 1)
}

/// (sin(2 pi x), cos(2 pi x)) from one reduction, each to about 2e-16 absolute (sin near 0 to
/// about an ulp of itself).
#[inline(always)]
pub fn sin_cos_turns(x: f64) -> (f64, f64) {
    if x.is_nan() || x.abs() >= EXACT_REDUCTION {
        return (std::f64::consts::TAU * x.fract()).sin_cos();
    }
    let (q, a, a2) = quarters(x);
    let (c, s) = (cos_quarter(a2), sin_quarter(a, a2));
    // Quadrants 0..3 of q mod 4: sin is sin, cos, -sin, -cos (flipped where q & 2 is set), cos
    // as in `cos_turns`.
    let (sin, cos) = if q & 1 == 0 { (s, c) } else { (c, s) };
    (flipped(sin, q), flipped(cos, q + 1))
}

/// The fraction of a turn of `t f` in [0, 1), to the rounding of one sum: the product is split
/// exactly into its rounded value and its error (fma), and only their fractions are added. A
/// forcing evaluated as phase0 + tau f over a step (tau from the step's start) then keeps its
/// phase however large t is, where t f itself has lost its fraction's digits.
pub fn turns(t: f64, f: f64) -> f64 {
    let product = t * f;
    let error = t.mul_add(f, -product);
    let r = fraction(fraction(product) + fraction(error));
    // rem_euclid(1.0) for a sum within (-2, 2), whose fraction is exact: without fmod.
    if r < 0.0 {
        r + 1.0
    } else {
        r
    }
}

/// `x.fract()` to the bit, by a conversion to an integer instead of a call to libm's trunc
/// (which a baseline x86-64 build makes): every call of a model at short communication steps
/// takes its phase.
#[inline]
fn fraction(x: f64) -> f64 {
    // 2^52 and above, every double is a whole number (and the cast would saturate).
    if x.abs() < 4_503_599_627_370_496.0 {
        x - (x as i64) as f64
    } else if x.is_finite() {
        0.0
    } else {
        f64::NAN
    }
}

#[cfg(test)]
mod tests {
    use super::{cos_turns, sin_cos_turns, turns};

    /// Oracle: the standard library's fract and rem_euclid, to the bit, over the magnitudes a
    /// phase meets.
    #[test]
    fn turns_is_fract_and_rem_euclid_to_the_bit() {
        let reference = |t: f64, f: f64| {
            let product = t * f;
            let error = t.mul_add(f, -product);
            (product.fract() + error.fract()).rem_euclid(1.0)
        };
        for &f in &[1.0, 3000.0, 6e4, 0.1591549430918953, 1.7e7] {
            for k in 0..2000 {
                let t = (k as f64 * 0.737).powi(3) * 1e-3 - 0.5;
                assert_eq!(
                    turns(t, f).to_bits(),
                    reference(t, f).to_bits(),
                    "t {t} f {f}"
                );
            }
        }
        assert_eq!(super::fraction(-2.5), -0.5);
        assert_eq!(super::fraction(1e300), 0.0);
        assert!(super::fraction(f64::INFINITY).is_nan());
    }

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

    /// Oracle: libm's sin and cos on the same phase: a grid over many turns, both signs, every
    /// quadrant's edges, tiny phases (sin to a relative 1e-15 there) and NaN.
    #[test]
    fn sin_cos_agrees_with_libm() {
        let phases = (-20_000..20_000)
            .map(|i| f64::from(i) * 0.000_731_3 + 1e-3)
            .chain((-8..=8).map(|i| f64::from(i) * 0.125))
            .chain([3000.125, 1e9 + 0.3, -7.75, 1e17]);
        for x in phases {
            let (sin, cos) = sin_cos_turns(x);
            let (s, c) = (std::f64::consts::TAU * x.fract()).sin_cos();
            assert!(
                (sin - s).abs() < 1e-15 && (cos - c).abs() < 1e-15,
                "{x}: {sin} {cos}"
            );
            assert_eq!(cos.to_bits(), cos_turns(x).to_bits(), "{x}");
        }
        for x in [1e-300, 3e-12, -2e-9] {
            let (sin, _) = sin_cos_turns(x);
            let s = (std::f64::consts::TAU * x).sin();
            assert!((sin / s - 1.0).abs() < 1e-15, "{x}: {sin} {s}");
        }
        let (sin, cos) = sin_cos_turns(f64::NAN);
        assert!(sin.is_nan() && cos.is_nan());
    }
}
