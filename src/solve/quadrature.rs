//! Adaptive Gauss-Kronrod quadrature of a smooth function: the 15-point Kronrod rule on panels
//! whose length follows QUADPACK's estimate of its error (from the difference from the 7-point
//! Gauss rule it contains), as a solver's step follows its error estimate. For an integral whose integrand is known in closed form
//! (scene L's Dahl bristle), where an ODE solver would integrate it as a quadrature state.

use super::Work;
use crate::error::{Error, Failure};

/// The 15-point Kronrod nodes on [0, 1] (the rule is symmetric); the 7-point Gauss nodes are
/// those at odd indices (and 0).
const NODES: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// The 15-point Kronrod weights, in the order of [`NODES`].
const KRONROD: [f64; 8] = [
    0.022_935_322_010_529_225,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];
/// The 7-point Gauss weights at the nodes of odd index, then at 0.
const GAUSS: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// Evaluations per panel.
pub const PANEL_EVALUATIONS: u64 = 15;

/// A panel over `[a, a + h]`: the Kronrod and the Gauss estimate of the integral of `f`, and
/// the Kronrod integral of |f - K/h|, the integrand's spread about its mean (QUADPACK's
/// `resasc`).
fn panel(f: &impl Fn(f64) -> f64, a: f64, h: f64) -> (f64, f64, f64) {
    let half = 0.5 * h;
    let mid = a + half;
    let centre = f(mid);
    let mut kronrod = KRONROD[7] * centre;
    let mut gauss = GAUSS[3] * centre;
    let mut pairs = [(0.0, 0.0); 7];
    for i in 0..7 {
        let d = half * NODES[i];
        let (left, right) = (f(mid - d), f(mid + d));
        pairs[i] = (left, right);
        kronrod += KRONROD[i] * (left + right);
        if i % 2 == 1 {
            gauss += GAUSS[i / 2] * (left + right);
        }
    }
    // The mean of f over the panel (the weights sum to 2).
    let mean = 0.5 * kronrod;
    let mut spread = KRONROD[7] * (centre - mean).abs();
    for (i, (left, right)) in pairs.iter().enumerate() {
        spread += KRONROD[i] * ((left - mean).abs() + (right - mean).abs());
    }
    (half * kronrod, half * gauss, half * spread)
}

/// The error of a panel's Kronrod estimate, QUADPACK's (its `qk15`):
/// `resasc min(1, (200 |K - G| / resasc)^1.5)`. The Gauss-Kronrod difference measures the
/// Gauss rule's error; the Kronrod rule's own is far smaller, about that difference to the
/// power 1.5 on the integrand's scale, which the formula encodes.
fn kronrod_error(kronrod: f64, gauss: f64, resasc: f64) -> f64 {
    let difference = (kronrod - gauss).abs();
    if resasc > 0.0 && difference > 0.0 {
        resasc * (200.0 * difference / resasc).powf(1.5).min(1.0)
    } else {
        difference
    }
}

/// The panel length carries over from one integral to the next, like a solver's next step: the
/// one proposed after the last integral's first panel. Successive integrals (sub-steps between
/// the sign changes of a periodic forcing) start alike more than one starts like the last one
/// ended: a smooth end proposes a long panel that the next start, right after a reversal, rejects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussKronrod {
    /// The error allowed per unit length of the interval.
    pub tol_per_length: f64,
    /// The panel to try first in the next integral (0: the whole interval).
    pub h_next: f64,
}

impl GaussKronrod {
    pub fn new(tol_per_length: f64) -> Self {
        GaussKronrod {
            tol_per_length,
            h_next: 0.0,
        }
    }

    /// The integral of `f` over `[a, b]`, each panel's error estimate (`kronrod_error`)
    /// within the tolerance for its length.
    pub fn integrate(
        &mut self,
        f: impl Fn(f64) -> f64,
        a: f64,
        b: f64,
        work: &mut Work,
    ) -> Result<f64, Error> {
        let mut t = a;
        let mut sum = 0.0;
        let mut h = if self.h_next > 0.0 {
            self.h_next
        } else {
            b - a
        };
        let mut first_proposal = None;
        while t < b {
            let last = t + h >= b;
            let step = if last { b - t } else { h };
            let (kronrod, gauss, resasc) = panel(&f, t, step);
            let error = kronrod_error(kronrod, gauss, resasc);
            work.rhs_evaluations += PANEL_EVALUATIONS;
            let allowed = self.tol_per_length * step;
            if !error.is_finite() {
                return Err(Error::step(
                    "Gauss-Kronrod quadrature",
                    Failure::NotFinite,
                    format!("the integrand became non-finite on [{t}, {}]", t + step),
                    "a finite integrand",
                ));
            }
            // The Gauss-Kronrod difference goes as the panel to the 15th power, the estimate
            // as its 22.5th: the allowed error per length, as its 21.5th. No floor under the error:
            // on panels so short that the allowed error is below any floor, one would shrink
            // every panel that follows.
            let factor = if error > 0.0 {
                (0.9 * (allowed / error).powf(1.0 / 21.5)).clamp(0.2, 5.0)
            } else {
                5.0
            };
            if error <= allowed {
                work.steps += 1;
                sum += kronrod;
                t += step;
                // A panel cut short by the interval's end keeps the longer proposal.
                h = if last {
                    h.max(step * factor)
                } else {
                    step * factor
                };
                first_proposal.get_or_insert(h);
            } else {
                work.rejected += 1;
                h = step * factor;
            }
            if t + h <= t && t < b {
                return Err(Error::step(
                    "Gauss-Kronrod quadrature",
                    Failure::StepTooShort,
                    format!("the panel became too short at t = {t}"),
                    "an integrand the tolerance can follow: a looser tolerance",
                ));
            }
        }
        self.h_next = first_proposal.unwrap_or(h);
        Ok(sum)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kronrod integrates polynomials to degree 23 exactly on [-1, 1], Gauss to degree 13.
    #[test]
    fn rules_are_exact_to_their_degrees() {
        for k in 0..=23 {
            let exact = if k % 2 == 1 {
                0.0
            } else {
                2.0 / f64::from(k + 1)
            };
            let (kronrod, gauss, _) = panel(&|x: f64| x.powi(k), -1.0, 2.0);
            assert!((kronrod - exact).abs() < 1e-15, "degree {k}: {kronrod}");
            if k <= 13 {
                assert!((gauss - exact).abs() < 1e-15, "degree {k}: {gauss}");
            }
        }
        let (kronrod, gauss, _) = panel(&|x: f64| x.powi(24), -1.0, 2.0);
        assert!((kronrod - 2.0 / 25.0).abs() > 1e-9);
        let (_, gauss_14, _) = panel(&|x: f64| x.powi(14), -1.0, 2.0);
        assert!((gauss_14 - 2.0 / 15.0).abs() > 1e-6 && gauss != kronrod);
    }

    /// The adaptive integral meets its tolerance over a function with a sharp, moving layer,
    /// and a tighter tolerance costs more panels (none fewer at each step down).
    #[test]
    fn adaptive_integral_meets_its_tolerance() {
        let f = |t: f64| (-30.0 * t).exp() * (1.0 + (5.0 * t).cos());
        let exact = |t: f64| {
            let (a, w) = (-30.0_f64, 5.0_f64);
            (a * t).exp() / a
                + (a * t).exp() * (a * (w * t).cos() + w * (w * t).sin()) / (a * a + w * w)
        };
        let (a, b) = (0.0, 2.0);
        let mut work_loose = Work::default();
        let mut previous = 0;
        for tol in [1e-4, 1e-8, 1e-14] {
            let mut quad = GaussKronrod::new(tol);
            let mut work = Work::default();
            let value = quad.integrate(f, a, b, &mut work).unwrap();
            let error = (value - (exact(b) - exact(a))).abs();
            assert!(error <= tol * (b - a), "tol {tol}: error {error}");
            assert!(work.rhs_evaluations >= previous, "tol {tol}: {work:?}");
            previous = work.rhs_evaluations;
            if tol == 1e-4 {
                work_loose = work;
            }
        }
        assert!(
            work_loose.rhs_evaluations <= 8 * PANEL_EVALUATIONS
                && previous > work_loose.rhs_evaluations,
            "{work_loose:?}, {previous}"
        );
    }

    /// A vanishing interval (a communication step of 1e-300 s) leaves a proposal from which the
    /// next interval's panels grow: they must never shrink where the integrand is smooth, which
    /// once left panels too short to move t, and the call never returned.
    #[test]
    fn a_vanishing_interval_does_not_stall_the_next() {
        let f = |t: f64| (2.0 * t).cos();
        let mut quad = GaussKronrod::new(1e-9);
        let mut work = Work::default();
        quad.integrate(f, 0.0, 1e-300, &mut work).unwrap();
        let value = quad.integrate(f, 1e-300, 1e-6, &mut work).unwrap();
        assert!((value - 0.5 * (2e-6_f64).sin()).abs() < 1e-15, "{value}");
        assert!(work.steps < 500, "{work:?}");
    }

    /// Integrating in pieces (communication steps) keeps the panel proposal, and the result is
    /// the whole integral to the tolerance.
    #[test]
    fn pieces_keep_the_panel() {
        let f = |t: f64| (2.0 * t).sin() + 1.5;
        let mut quad = GaussKronrod::new(1e-10);
        let mut work = Work::default();
        let mut sum = 0.0;
        for i in 0..1000 {
            let t = f64::from(i) * 1e-3;
            sum += quad.integrate(f, t, t + 1e-3, &mut work).unwrap();
        }
        let exact = 1.5 + (1.0 - (2.0_f64).cos()) / 2.0;
        assert!((sum - exact).abs() < 1e-10, "{sum} vs {exact}");
        assert_eq!(work.steps, 1000, "{work:?}");
        assert_eq!(work.rejected, 0, "{work:?}");
    }
}
