//! The general solvers a model picks from, as one value behind the stepping interface
//! ([`Stepping`]): dopri5, radau5, dop853 and rk4. A model builds the one its `solver` switch
//! names, with its own tolerances, and from then on asks only the interface. A new general
//! solver is a module of `solve/` that implements [`Stepping`], and a variant here.

use super::dop853::Dop853;
use super::dopri::Dopri5;
use super::radau::Radau5;
use super::rk4::Rk4;
use super::stepping::{StepAhead, Stepping};
use super::switching::Switching;
use super::{Integrator, Ode, Work};
use crate::error::Error;

#[derive(Clone, Debug, PartialEq)]
pub enum Method {
    Dopri5(Dopri5),
    Radau5(Radau5),
    Dop853(Dop853),
    Rk4(Rk4),
}

impl Method {
    /// One explicit step across an interval within the round-off of the absolute time, where
    /// an adaptive solver would take the interval for a real one and refine it.
    pub fn across_round_off() -> Method {
        Method::Rk4(Rk4 {
            h_max: f64::INFINITY,
        })
    }
}

/// `$body` with `$s` bound to the solver inside `$method`, whichever it is.
macro_rules! each {
    ($method:expr, $s:ident => $body:expr) => {
        match $method {
            Method::Dopri5($s) => $body,
            Method::Radau5($s) => $body,
            Method::Dop853($s) => $body,
            Method::Rk4($s) => $body,
        }
    };
}

impl Stepping for Method {
    fn name(&self) -> &'static str {
        each!(self, s => s.name())
    }

    fn tolerance(&self) -> Option<f64> {
        each!(self, s => s.tolerance())
    }

    fn step_hint(&self) -> f64 {
        each!(self, s => s.step_hint())
    }

    fn set_step_hint(&mut self, h: f64) {
        each!(self, s => s.set_step_hint(h))
    }

    fn stiff_since(&mut self) -> Option<f64> {
        each!(self, s => s.stiff_since())
    }

    fn advance<S: Switching>(
        &mut self,
        ode: &S,
        span: (f64, f64),
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        each!(self, s => s.advance(ode, span, y, work))
    }

    fn takes_steps_ahead(&self) -> bool {
        each!(self, s => s.takes_steps_ahead())
    }

    fn step_ahead<S: Switching>(
        &mut self,
        ode: &S,
        span: (f64, f64, f64),
        y: &mut [f64],
        work: &mut Work,
        behind: Option<&StepAhead>,
        readable: impl Fn(&StepAhead) -> bool,
    ) -> Result<Option<(f64, StepAhead)>, Error> {
        each!(self, s => s.step_ahead(ode, span, y, work, behind, readable))
    }

    fn step_ahead_saved(&self, dim: usize) -> usize {
        each!(self, s => s.step_ahead_saved(dim))
    }

    fn restore_step_ahead(&self, dim: usize, saved: &[f64]) -> Option<StepAhead> {
        each!(self, s => s.restore_step_ahead(dim, saved))
    }

    fn save_ahead_hints(&self, out: &mut Vec<f64>) {
        each!(self, s => s.save_ahead_hints(out))
    }

    fn restore_ahead_hints(&mut self, saved: &[f64]) {
        each!(self, s => s.restore_ahead_hints(saved))
    }

    fn stability_bound(&self) -> Option<f64> {
        each!(self, s => s.stability_bound())
    }
}

impl Integrator for Method {
    fn integrate(
        &mut self,
        ode: &dyn Ode,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        each!(self, s => s.integrate(ode, t0, t1, y, work))
    }
}
