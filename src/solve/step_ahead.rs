//! A step taken ahead: a solver's step taken whole past the end of a call, which the calls
//! that end inside it read instead of each taking a step of its own, cut to its span
//! ([`Stepping::step_ahead`]). Each solver that takes them reads its step inside to its own
//! order: dopri5 from a quintic of the step's order ([`Quintic`]), radau5 from its collocation
//! polynomial ([`StepPolynomial`]).

use super::dopri::{Carry, Quintic, CARRY_SAVED, QUINTIC_SAVED};
use super::radau::StepPolynomial;
#[cfg(doc)]
use super::stepping::Stepping;
use super::MAX_DIM;

/// One step taken ahead, in the time of the equations it was taken on. Held inline, so that
/// a call never allocates.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepAhead {
    /// dopri5's step, and what the next step taken from its end goes on with.
    Dopri5(Quintic, Carry),
    Radau5(StepPolynomial),
}

impl StepAhead {
    /// The step's start.
    pub fn start(&self) -> f64 {
        match self {
            StepAhead::Dopri5(step, _) => step.t,
            StepAhead::Radau5(step) => step.t,
        }
    }

    /// The states at `t` (inside the step) into `y`; the states the step does not cover are
    /// left as they are.
    pub fn at(&self, t: f64, y: &mut [f64; MAX_DIM]) {
        match self {
            StepAhead::Dopri5(step, _) => step.at(t, y),
            StepAhead::Radau5(step) => {
                let n = step.n();
                y[..n].copy_from_slice(&step.at(t)[..n]);
            }
        }
    }

    /// Appends the step to a saved state: [`Stepping::step_ahead_saved`] numbers, `dim` the
    /// most states the model integrates.
    pub fn write(&self, dim: usize, out: &mut Vec<f64>) {
        match self {
            StepAhead::Dopri5(step, carry) => {
                step.write(out);
                carry.write(out);
            }
            StepAhead::Radau5(step) => step.write(dim, out),
        }
    }
}

/// How many numbers a saved dopri5 step takes.
pub(super) const DOPRI5_SAVED: usize = QUINTIC_SAVED + CARRY_SAVED;

/// The dopri5 step [`StepAhead::write`] wrote; None where the numbers cannot be one.
pub(super) fn read_dopri5(saved: &[f64]) -> Option<StepAhead> {
    if saved.len() != DOPRI5_SAVED {
        return None;
    }
    let (step, carry) = saved.split_at(QUINTIC_SAVED);
    Some(StepAhead::Dopri5(Quintic::read(step)?, Carry::read(carry)?))
}
