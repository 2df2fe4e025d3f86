//! Scene L's bristle ODE, `z' = rate(z, vr(t))` with the force integral `q' = FT(z, vr(t))` and
//! the friction work `w' = FT vr` as quadrature states ([`Bristle`]), which the general solvers
//! integrate; the exponential and closed-form schemes take the bristle in closed form instead.

use super::Law;
use crate::solve::Ode;

/// The law as a function of time, under a moving normal force.
pub type LoadedLaw<'a> = &'a dyn Fn(f64) -> Law;

/// `(z, q, w)` with the velocity (and the law, under a moving normal force) as a function of
/// time; the first `dim` of them.
pub(super) struct Bristle<'a> {
    pub(super) law: &'a Law,
    pub(super) velocity: &'a dyn Fn(f64) -> f64,
    pub(super) loaded: Option<LoadedLaw<'a>>,
    pub(super) dim: usize,
}

impl Ode for Bristle<'_> {
    fn dim(&self) -> usize {
        self.dim
    }
    /// q and w are quadratures: the right-hand side reads z alone.
    fn coupled(&self) -> usize {
        self.dim.min(1)
    }
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let v = (self.velocity)(t);
        let law = self.loaded.map(|loaded| loaded(t));
        let (rate, force) = match law.as_ref().unwrap_or(self.law) {
            // Coulomb has no state; the simulation integrates its force in closed form instead.
            Law::Coulomb => (0.0, 0.0),
            Law::Dahl(d) => (d.rate(y[0], v), d.force(y[0])),
            Law::LuGre(l) => (l.rate(y[0], v), l.force(y[0], v)),
        };
        dydt[0] = rate;
        if self.dim > 1 {
            dydt[1] = force;
        }
        if self.dim > 2 {
            dydt[2] = force * v;
        }
    }
}
