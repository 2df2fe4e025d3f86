//! The one stepping interface every general solver implements, so that a model picks a solver
//! and never needs to know which: it hands over its equations (an ODE with its switching
//! functions, [`Switching`]), and the solver advances them, ending its steps on the switching
//! functions' sign changes, answers what the model reads of it (its tolerance, a stiffness
//! found), and saves and restores what it carries from one call to the next.
//!
//! A step taken ahead is a solver's step taken whole past the communication point, its
//! interpolant read by the calls that end inside it ([`StepAhead`], [`CallEnd`]). Which solvers
//! take them, how far, and when a step can be read inside to the tolerance is the solvers'
//! ([`Stepping::step_ahead`]); when a model may take them at all (not while an input may change
//! at every call) and what it reads of them is the model's, said with one vocabulary
//! (`takes_steps_ahead`, `take_step_ahead`, `read_step_ahead`); and the FMI layer asks one
//! question of any model, `Simulation::read_inside`.

pub use super::step_ahead::StepAhead;
use super::switching::Switching;
use super::Work;
use crate::error::Error;

/// How many numbers [`Stepping::save_into`] writes.
pub const SAVED: usize = 1;

/// A solver behind the stepping interface.
pub trait Stepping {
    /// The solver's name, as the models' `solver` switches spell it (for the messages).
    fn name(&self) -> &'static str;

    /// The relative tolerance the solver integrates to; None for a fixed step, whose error is
    /// set by its step alone.
    fn tolerance(&self) -> Option<f64>;

    /// The step the solver would try next (0 for a fixed step): all it carries from one call
    /// to the next, so part of a saved state.
    fn step_hint(&self) -> f64;

    fn set_step_hint(&mut self, h: f64);

    /// Where the solver found the problem stiff ([`crate::solve::stiffness`]), the first time
    /// it is asked after that was found; None otherwise (always, for a solver that cannot
    /// tell).
    fn stiff_since(&mut self) -> Option<f64> {
        None
    }

    /// Advances `y` over `span`, from its start to its end, ending steps on the sign changes of
    /// `ode`'s switching functions; an error says why the interval could not be completed.
    fn advance<S: Switching>(
        &mut self,
        ode: &S,
        span: (f64, f64),
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error>;

    /// Appends what the solver carries between calls to a saved state: [`SAVED`] numbers.
    fn save_into(&self, out: &mut Vec<f64>) {
        out.push(self.step_hint());
    }

    /// Restores what [`Stepping::save_into`] wrote (`saved` holds [`SAVED`] numbers).
    fn restore(&mut self, saved: &[f64]) {
        self.set_step_hint(saved[0]);
    }

    /// Whether the solver takes steps ahead when a model asks ([`Stepping::step_ahead`]): a
    /// setting of the solvers that can, none by default.
    fn takes_steps_ahead(&self) -> bool {
        false
    }

    /// Where the solver takes steps ahead and the step it proposes from `t` holds enough calls
    /// ending at `t_end` to pay for its reading, takes that step whole, no further than `reach`
    /// (all in the equations' time), ending it on the switching functions' sign changes as
    /// [`Stepping::advance`] does: leaves `y` at its end and returns the end and the step, to
    /// be read inside. The step may end short of `t_end` (on a kink). `behind` is the last step
    /// taken ahead, where this one starts at its end; `readable`, the caller's own condition
    /// for reading the step. None, with nothing changed but `work` and what the solver learnt
    /// for its next step ahead, where it takes no such step, or the step cannot be read inside
    /// to the tolerance, or not as the caller asks.
    fn step_ahead<S: Switching>(
        &mut self,
        _ode: &S,
        _span: (f64, f64, f64),
        _y: &mut [f64],
        _work: &mut Work,
        _behind: Option<&StepAhead>,
        _readable: impl Fn(&StepAhead) -> bool,
    ) -> Result<Option<(f64, StepAhead)>, Error> {
        Ok(None)
    }

    /// How many numbers a step the solver takes ahead adds to a saved state
    /// ([`StepAhead::write`]), `dim` the most states the model integrates; 0 for a solver that
    /// cannot take them.
    fn step_ahead_saved(&self, _dim: usize) -> usize {
        0
    }

    /// The step ahead that [`StepAhead::write`] wrote for this solver; None where the numbers
    /// cannot be one.
    fn restore_step_ahead(&self, _dim: usize, _saved: &[f64]) -> Option<StepAhead> {
        None
    }

    /// Appends what the solver carries towards its next step ahead: [`AHEAD_HINTS`] numbers.
    fn save_ahead_hints(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(&[0.0, f64::MAX]);
    }

    /// Restores what [`Stepping::save_ahead_hints`] wrote.
    fn restore_ahead_hints(&mut self, _saved: &[f64]) {}

    /// The largest |h lambda|, lambda an eigenvalue of the equations' linear part, within which
    /// a step of a fixed-step solver stays stable; None for an adaptive solver, whose error
    /// control holds its steps.
    fn stability_bound(&self) -> Option<f64> {
        None
    }
}

/// How many numbers [`Stepping::save_ahead_hints`] writes.
pub const AHEAD_HINTS: usize = 2;

/// Where a call that ends at `t_end` ends against a step taken ahead to `end`, past the
/// communication point: `slack` is the clock's round-off, within which a call ends on the step's
/// end. A call inside the step is read from its interpolant; one at its end takes its end
/// state; one past it goes on from there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CallEnd {
    Inside,
    AtEnd,
    Past,
}

impl CallEnd {
    pub fn of(t_end: f64, end: f64, slack: f64) -> CallEnd {
        if t_end < end - slack {
            CallEnd::Inside
        } else if t_end <= end + slack {
            CallEnd::AtEnd
        } else {
            CallEnd::Past
        }
    }
}
