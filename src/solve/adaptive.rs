//! The adaptive solvers every model offers, dopri5 and radau5, as one value: what the models ask
//! of either (its tolerance, the step it would try next, a stiffness warning, an integration)
//! is answered here once, so that a model's own solver enum adds only its own methods.

use super::dopri::Dopri5;
use super::radau::Radau5;
use super::switching::Switching;
use super::{Integrator, Ode, Work};

#[derive(Clone, Debug, PartialEq)]
pub enum Adaptive {
    Dopri5(Dopri5),
    Radau5(Radau5),
}

impl Adaptive {
    /// The relative tolerance.
    pub fn rtol(&self) -> f64 {
        match self {
            Adaptive::Dopri5(d) => d.rtol,
            Adaptive::Radau5(r) => r.rtol,
        }
    }

    /// Where dopri5 found the problem stiff, once ([`Dopri5::stiff_since`]); radau5 never says.
    pub fn stiff_since(&mut self) -> Option<f64> {
        match self {
            Adaptive::Dopri5(d) => d.stiff_since(),
            Adaptive::Radau5(_) => None,
        }
    }

    /// The step the solver would try next (part of a saved FMU state).
    pub fn step_hint(&self) -> f64 {
        match self {
            Adaptive::Dopri5(d) => d.h,
            Adaptive::Radau5(r) => r.h_next,
        }
    }

    pub fn set_step_hint(&mut self, h: f64) {
        match self {
            Adaptive::Dopri5(d) => d.h = h,
            Adaptive::Radau5(r) => r.h_next = h,
        }
    }

    /// Advances `y` from `t0` to `t1`, ending steps on the sign changes `ode` reports.
    pub fn integrate_switched<S: Switching>(
        &mut self,
        ode: &S,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), String> {
        match self {
            Adaptive::Dopri5(d) => d.integrate_switched(ode, t0, t1, y, work),
            Adaptive::Radau5(r) => r.integrate_switched(ode, t0, t1, y, work),
        }
    }
}

impl Integrator for Adaptive {
    fn integrate(
        &mut self,
        ode: &dyn Ode,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), String> {
        match self {
            Adaptive::Dopri5(d) => d.integrate(ode, t0, t1, y, work),
            Adaptive::Radau5(r) => r.integrate(ode, t0, t1, y, work),
        }
    }
}
