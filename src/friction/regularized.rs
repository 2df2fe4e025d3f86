//! Regularised dry friction (paper O, eq. 4-9): the force `H(v)` and its slope `C(v) = dH/dv`
//! for the four approximations of `h*sgn(v)` with a transition region of width `D` around v = 0.
//!
//! The stiction variants add a bump of width `Da` in which the force rises to `h + ha`,
//! `ha = h*Da/D` (eq. 6-7), before it falls back to `h`. Every function returns `(H, C)`.

use super::sgn;

/// Which approximation, with its parameters (h >= 0, D > 0, Da >= 0 are the simulation's to check).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Regularized {
    Linear { h: f64, d: f64 },
    Trigonometric { h: f64, d: f64 },
    LinearStiction { h: f64, d: f64, da: f64 },
    TrigonometricStiction { h: f64, d: f64, da: f64 },
}

impl Regularized {
    /// `(H(v), C(v))`.
    pub fn eval(&self, v: f64) -> (f64, f64) {
        match *self {
            Regularized::Linear { h, d } => linear(h, d, v),
            Regularized::Trigonometric { h, d } => trigonometric(h, d, v),
            Regularized::LinearStiction { h, d, da } => linear_stiction(h, d, da, v),
            Regularized::TrigonometricStiction { h, d, da } => trigonometric_stiction(h, d, da, v),
        }
    }

    /// The largest |H| the law reaches: h, or h + ha with stiction.
    pub fn peak(&self) -> f64 {
        match *self {
            Regularized::Linear { h, .. } | Regularized::Trigonometric { h, .. } => h,
            Regularized::LinearStiction { h, d, da }
            | Regularized::TrigonometricStiction { h, d, da } => h + stiction_excess(h, d, da),
        }
    }
}

/// `ha = h*Da/D` (eq. 7): the bump keeps the slope h/D of the core (eq. 6).
pub fn stiction_excess(h: f64, d: f64, da: f64) -> f64 {
    h * da / d
}

/// Eq. 4: `C = h/D` for |v| < D, else 0; so `H = h*clamp(v/D, -1, 1)`.
pub fn linear(h: f64, d: f64, v: f64) -> (f64, f64) {
    if v.abs() < d {
        (h * v / d, h / d)
    } else {
        (h * sgn(v), 0.0)
    }
}

/// Eq. 5: `H = h*sin(pi/2 * v/D)` for |v| < D, else `h*sgn(v)`.
pub fn trigonometric(h: f64, d: f64, v: f64) -> (f64, f64) {
    if v.abs() < d {
        let x = std::f64::consts::FRAC_PI_2 * v / d;
        (h * x.sin(), h * std::f64::consts::FRAC_PI_2 / d * x.cos())
    } else {
        (h * sgn(v), 0.0)
    }
}

/// Eq. 8: slope h/D up to |v| = D + Da (H reaches h + ha), slope -h/D up to D + 2*Da (back to h).
pub fn linear_stiction(h: f64, d: f64, da: f64, v: f64) -> (f64, f64) {
    let ha = stiction_excess(h, d, da);
    let a = v.abs();
    if a < d + da {
        (h * v / d, h / d)
    } else if a < d + 2.0 * da {
        (sgn(v) * (h + ha - h / d * (a - d - da)), -h / d)
    } else {
        (h * sgn(v), 0.0)
    }
}

/// Eq. 9: `(h + ha)*sin(pi/2 * v/(D + Da))` up to D + Da, then a half sine wave of width Da down
/// to h (continuous, with zero slope at both ends of the bump), then `h*sgn(v)`.
pub fn trigonometric_stiction(h: f64, d: f64, da: f64, v: f64) -> (f64, f64) {
    use std::f64::consts::FRAC_PI_2;
    let ha = stiction_excess(h, d, da);
    let a = v.abs();
    if a < d + da {
        let x = FRAC_PI_2 * v / (d + da);
        (
            (h + ha) * x.sin(),
            (h + ha) * FRAC_PI_2 / (d + da) * x.cos(),
        )
    } else if a < d + 2.0 * da {
        // This branch is empty when Da = 0, so 0.5*Da never divides by zero here.
        let x = FRAC_PI_2 * (a - (d + 1.5 * da)) / (0.5 * da);
        (
            sgn(v) * (h + 0.5 * ha - 0.5 * ha * x.sin()),
            -0.5 * ha * FRAC_PI_2 / (0.5 * da) * x.cos(),
        )
    } else {
        (h * sgn(v), 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const H: f64 = 1.6;
    const D: f64 = 0.8;
    const DA: f64 = 0.8;

    fn laws() -> [Regularized; 4] {
        [
            Regularized::Linear { h: H, d: D },
            Regularized::Trigonometric { h: H, d: D },
            Regularized::LinearStiction { h: H, d: D, da: DA },
            Regularized::TrigonometricStiction { h: H, d: D, da: DA },
        ]
    }

    /// Oracle: the definitions. H is continuous at every breakpoint (the largest jump over a
    /// 1e-9 neighbourhood is of the order of slope * 1e-9), odd, and bounded by its peak.
    #[test]
    fn continuous_odd_and_bounded() {
        for law in laws() {
            for point in [0.0, D, D + DA, D + 2.0 * DA] {
                for side in [1.0, -1.0] {
                    let x = side * point;
                    let jump = (law.eval(x + 1e-9).0 - law.eval(x - 1e-9).0).abs();
                    assert!(jump < 1e-8 * (1.0 + H / D), "{law:?} jumps {jump} at {x}");
                }
            }
            for i in -400..=400 {
                let v = f64::from(i) * 0.01;
                let (hv, _) = law.eval(v);
                assert_eq!(hv, -law.eval(-v).0, "{law:?} not odd at {v}");
                assert!(hv.abs() <= law.peak() * (1.0 + 1e-15), "{law:?} at {v}");
            }
        }
    }

    /// Oracle: central differences of H. C is its derivative wherever H is smooth.
    #[test]
    fn slope_is_the_derivative() {
        let eps = 1e-6;
        for law in laws() {
            for i in -390..=390 {
                let v = f64::from(i) * 0.01 + 0.003;
                let fd = (law.eval(v + eps).0 - law.eval(v - eps).0) / (2.0 * eps);
                let c = law.eval(v).1;
                assert!((fd - c).abs() < 1e-6, "{law:?} at {v}: C {c}, dH/dv {fd}");
            }
        }
    }

    /// Oracle: the paper's figures of H(v): plateau h beyond the region, peak h + ha = 2h at
    /// |v| = D + Da for Da = D, slope h/D at 0 (linear) and pi/2 * h/D (trigonometric forms).
    #[test]
    fn published_shape() {
        for law in laws() {
            assert_eq!(law.eval(10.0).0, H);
            assert_eq!(law.eval(-10.0).0, -H);
            assert_eq!(law.eval(10.0).1, 0.0);
        }
        assert!((linear_stiction(H, D, DA, D + DA).0 - 2.0 * H).abs() < 1e-12);
        assert!((trigonometric_stiction(H, D, DA, D + DA).0 - 2.0 * H).abs() < 1e-12);
        assert!((linear(H, D, 0.0).1 - H / D).abs() < 1e-15);
        let trig_slope = std::f64::consts::FRAC_PI_2 * H / D;
        assert!((trigonometric(H, D, 0.0).1 - trig_slope).abs() < 1e-12);
        assert!((trigonometric_stiction(H, D, DA, 0.0).1 - trig_slope).abs() < 1e-12);
        // Da = 0: the stiction forms reduce to the plain ones.
        for v in [-2.0, -0.5, 0.1, 0.79, 0.8, 3.0] {
            assert_eq!(linear_stiction(H, D, 0.0, v), linear(H, D, v));
            assert_eq!(trigonometric_stiction(H, D, 0.0, v), trigonometric(H, D, v));
        }
    }
}
