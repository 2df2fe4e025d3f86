//! Scene O's regularised equations of motion ([`Equations`]) with the switching functions at
//! the kinks of H, on the linear oscillator and its forcing that the exact core shares
//! ([`Forced`]).

use crate::error::{Error, Failure};
use crate::friction::regularized::Regularized;
#[cfg(doc)]
use crate::solve::stepping::Stepping;
use crate::solve::switching::{Switching, MAX_SWITCHES};
use crate::solve::Ode;

/// The linear oscillator `m u'' + c u' + k u = F(t)` and its forcing: what the regularised and
/// the exact cores share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forced {
    pub m: f64,
    pub c: f64,
    pub k: f64,
    pub w: f64,
    /// Sine amplitude; unused when `input`.
    pub p: f64,
    /// Whether the force is the input, held over each step.
    pub input: bool,
}

impl Forced {
    /// The excitation force at t (`held` is the input over the current step).
    pub fn force(&self, t: f64, held: f64) -> f64 {
        if self.input {
            held
        } else {
            self.p * (self.w * t).sin()
        }
    }
}

/// The regularised equations of motion, `y = (u, u', W)` with W the friction work, the integral
/// of H u' (a quadrature state, integrated to the solver's order; left out when W_diss is
/// hidden).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equations {
    pub plant: Forced,
    /// The input force held over the current step.
    pub held: f64,
    pub law: Regularized,
    /// W is integrated (W_diss is read).
    pub with_work: bool,
}

impl Equations {
    /// A fixed-step solver (rk4) blows up (through many steps of finite nonsense) where h times
    /// an eigenvalue of the linear part `m u'' + (c + C) u' + k u` leaves its stability region,
    /// which lies within |h lambda| < `bound` ([`Stepping::stability_bound`]). C is the friction
    /// law's steepest slope, at u' = 0: it acts only while |u'| < D, but a motion that sticks
    /// there, or crosses it in a step or two, then gains energy at every step (the regression
    /// test `rk4_refuses_a_step_the_friction_slope_makes_unstable` in `oscillator/tests.rs`
    /// holds such a case).
    pub fn require_stable(&self, solver: &'static str, h: f64, bound: f64) -> Result<(), Error> {
        let Forced { m, c, k, .. } = self.plant;
        let slope = self.law.eval(0.0).1.max(0.0);
        let damping = c + slope;
        let disc = damping * damping - 4.0 * m * k;
        let rate = if disc >= 0.0 {
            (damping + disc.sqrt()) / (2.0 * m)
        } else {
            (k / m).sqrt()
        };
        if h * rate <= bound {
            Ok(())
        } else {
            Err(Error::step(
                solver,
                Failure::BeyondStability,
                format!("the step {h:e} s is beyond its stability bound {bound}/{rate:e} s set by m, c, k and the friction slope {slope:e} N.s/m at u' = 0"),
                "a step within it: more steps_per_period (or the radau5 solver)",
            ))
        }
    }

    /// `(H, C, u'')` at (t, u, u').
    pub fn evaluate(&self, t: f64, u: f64, v: f64) -> (f64, f64, f64) {
        let (h, c) = self.law.eval(v);
        let pl = &self.plant;
        let a = (pl.force(t, self.held) - pl.c * v - h - pl.k * u) / pl.m;
        (h, c, a)
    }
}

impl Ode for Equations {
    fn dim(&self) -> usize {
        if self.with_work {
            3
        } else {
            2
        }
    }
    /// The work is a quadrature: the right-hand side reads (u, u') alone.
    fn coupled(&self) -> usize {
        2
    }
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let (h, _, a) = self.evaluate(t, y[0], y[1]);
        dydt[0] = y[1];
        dydt[1] = a;
        if self.with_work {
            dydt[2] = h * y[1];
        }
    }
}

impl Equations {
    /// The outer edge of H's band and h: beyond the edge H is the constant h sgn(u').
    pub fn band(&self) -> (f64, f64) {
        match self.law {
            Regularized::Linear { h, d } | Regularized::Trigonometric { h, d } => (d, h),
            Regularized::LinearStiction { h, d, da }
            | Regularized::TrigonometricStiction { h, d, da } => (d + 2.0 * da, h),
        }
    }
}

impl Switching for Equations {
    /// H has kinks in u' at +-D (+-(D + Da), +-(D + 2 Da) with stiction).
    fn switches(&self, _t: f64, y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> usize {
        let v = y[1];
        let edges = match self.law {
            Regularized::Linear { d, .. } | Regularized::Trigonometric { d, .. } => [d, d, d],
            Regularized::LinearStiction { d, da, .. }
            | Regularized::TrigonometricStiction { d, da, .. } => [d, d + da, d + 2.0 * da],
        };
        let count = if edges[0] == edges[2] { 1 } else { 3 };
        for (i, e) in edges[..count].iter().enumerate() {
            out[2 * i] = v - e;
            out[2 * i + 1] = v + e;
        }
        2 * count
    }

    /// The trigonometric law's H is C1 at +-D: its slope falls to 0 there.
    fn smooth_across(&self, _i: usize) -> bool {
        matches!(self.law, Regularized::Trigonometric { .. })
    }
}
