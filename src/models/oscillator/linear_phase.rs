//! Outside the regularised law's band (|u'| at or beyond its outer edge) the friction force is
//! the constant `s h`, s = sgn(u'), and the oscillator is linear:
//!
//! `m u'' + c u' + k u = P sin(w t) + q`, with q = (the held input force) - s h.
//!
//! Its solution is the particular one, `A sin(w t) + B cos(w t) + q/k`, plus the free motion
//! `x = e^(-a tau) (x0 C(tau) + y0 S(tau))`, a = c/(2m), y0 = x0' + a x0, with C, S the cosine
//! and sine over the frequency of `kappa = k/m - a^2` (hyperbolic where kappa < 0, 1 and tau at
//! 0). The `piecewise` solver takes these phases in closed form and ends each where u' comes
//! back to the edge ([`LinearPhase::entry`]); inside the band dopri5 integrates.

use super::Forced;
use crate::solve::phase::sin_cos_turns;
use std::f64::consts::TAU;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearPhase {
    t0: f64,
    /// The free motion's start and its y0.
    x0: f64,
    y0: f64,
    /// Damping rate a = c/(2m), kappa = k/m - a^2 and sqrt(|kappa|).
    a: f64,
    kappa: f64,
    root: f64,
    /// The particular solution's sine and cosine amplitudes and constant.
    sine: f64,
    cosine: f64,
    constant: f64,
    w: f64,
    /// The forcing's and the free motion's frequencies in turns per unit time (w and sqrt(kappa)
    /// over 2 pi): both sines and cosines from one reduction each, not libm's two.
    w_turns: f64,
    root_turns: f64,
    /// The forcing `P sin(w t) + q` and the plant, for the acceleration.
    p: f64,
    q: f64,
    plant: Forced,
}

impl LinearPhase {
    /// The phase from `(t0, u0, v0)` under the friction force `friction` (s h) and the input
    /// force `held`; None where the closed form does not apply (k = 0, or undamped resonance).
    pub fn new(
        plant: &Forced,
        (held, friction): (f64, f64),
        (t0, u0, v0): (f64, f64, f64),
    ) -> Option<Self> {
        let Forced { m, c, k, w, .. } = *plant;
        let (p, q) = if plant.input {
            (0.0, held - friction)
        } else {
            (plant.p, -friction)
        };
        let detuning = k - m * w * w;
        let det = detuning * detuning + (c * w) * (c * w);
        if k <= 0.0 || (p != 0.0 && det <= 0.0) {
            return None;
        }
        let (sine, cosine) = if p == 0.0 {
            (0.0, 0.0)
        } else {
            (p * detuning / det, -p * c * w / det)
        };
        let a = c / (2.0 * m);
        let kappa = k / m - a * a;
        let root = kappa.abs().sqrt();
        let mut phase = LinearPhase {
            t0,
            x0: 0.0,
            y0: 0.0,
            a,
            kappa,
            root,
            sine,
            cosine,
            constant: q / k,
            w,
            w_turns: w / TAU,
            root_turns: root / TAU,
            p,
            q,
            plant: *plant,
        };
        let (up, vp, _) = phase.particular(t0);
        phase.x0 = u0 - up;
        phase.y0 = (v0 - vp) + a * phase.x0;
        Some(phase)
    }

    /// The particular solution's (u, u') and the forcing's sine at t.
    fn particular(&self, t: f64) -> (f64, f64, f64) {
        let (sin, cos) = sin_cos_turns(self.w_turns * t);
        (
            self.sine * sin + self.cosine * cos + self.constant,
            self.w * (self.sine * cos - self.cosine * sin),
            sin,
        )
    }

    /// `e^(-a tau) C(tau)` and `e^(-a tau) S(tau)`.
    fn free(&self, tau: f64) -> (f64, f64) {
        let kappa = self.kappa;
        if kappa > 0.0 {
            let decay = (-self.a * tau).exp();
            let (sin, cos) = sin_cos_turns(self.root_turns * tau);
            (decay * cos, decay * sin / self.root)
        } else if kappa < 0.0 {
            // Written with the two exponentials, which neither overflow: beta < a when k > 0.
            let beta = self.root;
            let slow = ((beta - self.a) * tau).exp();
            let fast = (-(beta + self.a) * tau).exp();
            (0.5 * (slow + fast), 0.5 * (slow - fast) / beta)
        } else {
            let decay = (-self.a * tau).exp();
            (decay, decay * tau)
        }
    }

    /// (u, u') at time t.
    pub fn at(&self, t: f64) -> (f64, f64) {
        let (u, v, _) = self.motion(t);
        (u, v)
    }

    /// (u, u', u'') at time t.
    fn motion(&self, t: f64) -> (f64, f64, f64) {
        let (up, vp, sin) = self.particular(t);
        let (c, s) = self.free(t - self.t0);
        let (x0, y0) = (self.x0, self.y0);
        let u = up + c * x0 + s * y0;
        let v = vp + c * (y0 - self.a * x0) - s * (self.kappa * x0 + self.a * y0);
        let pl = &self.plant;
        (u, v, (self.p * sin + self.q - pl.c * v - pl.k * u) / pl.m)
    }

    /// u'' at (t, u, u').
    pub fn acceleration(&self, t: f64, u: f64, v: f64) -> f64 {
        let pl = &self.plant;
        (self.p * (pl.w * t).sin() + self.q - pl.c * v - pl.k * u) / pl.m
    }

    /// The first time in (t0, t_end] where s u' falls to `edge`, located to round-off, if it
    /// does; `evaluations` counts the closed form's evaluations. The search takes chunks of an
    /// eighth of the fastest period of the motion, and looks inside a chunk whose ends are both
    /// above the edge for a dip below it when s u'' turns from falling to rising there.
    pub fn entry(&self, s: f64, edge: f64, t_end: f64, evaluations: &mut u64) -> Option<f64> {
        let pl = &self.plant;
        let rate = self.w.max((pl.k / pl.m).sqrt()).max(self.a);
        let chunk = std::f64::consts::FRAC_PI_4 / rate;
        // g = s u' - edge and its rate s u''.
        let g = |t: f64, evaluations: &mut u64| {
            *evaluations += 1;
            let (_, v, a) = self.motion(t);
            (s * v - edge, s * a)
        };
        let mut lo = self.t0;
        let (mut g_lo, mut d_lo) = g(lo, evaluations);
        while lo < t_end {
            let hi = (lo + chunk).min(t_end);
            if hi <= lo {
                return None;
            }
            let (g_hi, d_hi) = g(hi, evaluations);
            if g_hi <= 0.0 && g_lo > 0.0 {
                return Some(self.root((lo, g_lo), (hi, g_hi), &g, evaluations));
            }
            if g_hi <= 0.0 || (d_lo < 0.0 && d_hi > 0.0) {
                // The lowest point between: where s u'' changes sign (bisection).
                let (mut a, mut b) = (lo, hi);
                let mut lowest = if g_hi <= 0.0 { (hi, g_hi) } else { (lo, g_lo) };
                if d_lo < 0.0 && d_hi > 0.0 {
                    for _ in 0..60 {
                        let mid = 0.5 * (a + b);
                        if mid <= a || mid >= b {
                            break;
                        }
                        let (_, d) = g(mid, evaluations);
                        if d < 0.0 {
                            a = mid;
                        } else {
                            b = mid;
                        }
                    }
                    let (g_min, _) = g(a, evaluations);
                    lowest = (a, g_min);
                }
                if lowest.1 <= 0.0 {
                    if g_lo > 0.0 {
                        return Some(self.root((lo, g_lo), lowest, &g, evaluations));
                    }
                    // Started on the edge and never rose above it: no phase to take here.
                    return Some(lo);
                }
            }
            (lo, g_lo, d_lo) = (hi, g_hi, d_hi);
        }
        None
    }

    /// The root of g between `lo` (g > 0) and `hi` (g <= 0): Newton's steps on g's rate, kept
    /// inside the bracket by false position, to round-off of t.
    fn root(
        &self,
        (mut lo, mut g_lo): (f64, f64),
        (mut hi, mut g_hi): (f64, f64),
        g: &dyn Fn(f64, &mut u64) -> (f64, f64),
        evaluations: &mut u64,
    ) -> f64 {
        let mut t = hi;
        for _ in 0..60 {
            let secant = lo - g_lo * (hi - lo) / (g_hi - g_lo);
            let (value, rate) = g(t, evaluations);
            if value == 0.0 {
                return t;
            }
            if value > 0.0 {
                (lo, g_lo) = (t, value);
            } else {
                (hi, g_hi) = (t, value);
            }
            if hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(1e-300) {
                break;
            }
            let newton = t - value / rate;
            // Newton's step converges from one side, so the bracket need not close: its step
            // falling to round-off of t is the end. Tested before the bracket: a step of less
            // than an ulp lands on t itself, the bracket's end, and false position from there
            // would only crawl.
            if (newton - t).abs() <= 2.0 * f64::EPSILON * t.abs() {
                return if newton > lo && newton < hi {
                    newton
                } else {
                    t
                };
            }
            if newton > lo && newton < hi {
                t = newton;
            } else {
                t = secant.clamp(lo, hi);
            }
            if t <= lo || t >= hi {
                t = 0.5 * (lo + hi);
            }
        }
        hi
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::dopri::Dopri5;
    use crate::solve::{Integrator, Ode, Work, MAX_DIM};

    fn plant(c: f64, k: f64) -> Forced {
        Forced {
            m: 1.0,
            c,
            k,
            w: 1.0,
            p: 4.0,
            input: false,
        }
    }

    struct Linear(Forced, f64);

    impl Ode for Linear {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
            let pl = &self.0;
            dydt[0] = y[1];
            dydt[1] = (pl.force(t, 0.0) - self.1 - pl.c * y[1] - pl.k * y[0]) / pl.m;
        }
    }

    /// Under-, over- and critically damped, the closed form is the ODE integrated tightly.
    #[test]
    fn closed_form_is_the_linear_motion() {
        for (c, k) in [(0.1, 1.0), (5.0, 1.0), (2.0, 1.0), (0.0, 2.0)] {
            let pl = plant(c, k);
            let (t0, u0, v0) = (3.0, 1.5, 7.0);
            let phase = LinearPhase::new(&pl, (0.0, 1.6), (t0, u0, v0)).unwrap();
            let mut y = [u0, v0];
            let t1 = t0 + 2.5;
            Dopri5::new(1e-13, [1e-13; MAX_DIM], 1.0)
                .integrate(&Linear(pl, 1.6), t0, t1, &mut y, &mut Work::default())
                .unwrap();
            let (u, v) = phase.at(t1);
            assert!(
                (u - y[0]).abs() < 1e-10 && (v - y[1]).abs() < 1e-10,
                "c {c}: {u} {v} {y:?}"
            );
            let (u_start, v_start) = phase.at(t0);
            assert!((u_start - u0).abs() < 1e-14 && (v_start - v0).abs() < 1e-14);
        }
    }

    /// The entry into the band is where u' first falls to the edge, to round-off, in a few
    /// evaluations also far from t = 0, where the last Newton step is below an ulp of t.
    #[test]
    fn entry_is_the_first_return_to_the_edge() {
        let pl = plant(0.1, 1.0);
        let mut most = 0;
        for t0 in (0..40).map(|i| 5.37 * f64::from(i)) {
            let phase = LinearPhase::new(&pl, (0.0, 1.6), (t0, 0.0, 10.0)).unwrap();
            let mut evaluations = 0;
            let t = phase.entry(1.0, 0.8, t0 + 20.0, &mut evaluations).unwrap();
            let (_, v) = phase.at(t);
            assert!((v - 0.8).abs() < 1e-12, "{t}: {v}");
            // No earlier return: u' stays above the edge on a fine grid before t.
            for i in 0..1000 {
                let (_, v) = phase.at(t0 + (t - t0) * f64::from(i) / 1000.0);
                assert!(v > 0.8, "{i}: {v}");
            }
            most = most.max(evaluations);
            let half = t0 + 0.5 * (t - t0);
            assert_eq!(phase.entry(1.0, 0.8, half, &mut evaluations), None);
        }
        assert!(most <= 12, "{most}");
    }

    /// No closed form without a spring or at an undamped resonance.
    #[test]
    fn refuses_what_it_cannot_write() {
        assert!(LinearPhase::new(&plant(0.1, 0.0), (0.0, 1.6), (0.0, 0.0, 1.0)).is_none());
        assert!(LinearPhase::new(&plant(0.0, 1.0), (0.0, 1.6), (0.0, 0.0, 1.0)).is_none());
    }
}
