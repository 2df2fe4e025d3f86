//! Steps taken past the communication point: a call takes the step the solver proposes whole,
//! past its end, and reads the state at its end from the step; the calls that follow inside the
//! step read it too.

use super::solver::Solver;
use super::{turning_point, Core, Oscillator, AHEAD_SAVED, DIM};
use crate::error::Error;
use crate::solve::stepping::{CallEnd, StepAhead, Stepping};
use crate::solve::MAX_DIM;

/// A solver's step taken past the communication point: the calls that end inside it read the
/// state from it instead of each taking a step of its own, which at communication steps far
/// shorter than the solver's is nearly every call. Only while the force is prescribed: an input
/// may change at every call, and the step would no longer be the motion's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Ahead {
    pub(super) step: StepAhead,
    /// (t, u, u', W) at the step's end, where the integration goes on from.
    pub(super) end: [f64; 4],
    /// The largest |u| from where the step was taken to its end, for the amplitude once the
    /// communication points reach the end.
    pub(super) largest: f64,
}

/// The states `step` holds at `t`.
fn read(step: &StepAhead, t: f64) -> [f64; MAX_DIM] {
    let mut y = [0.0; MAX_DIM];
    step.at(t, &mut y);
    y
}

impl Oscillator {
    /// Answers a step ending at `t_end` from the step taken ahead, if there is one: inside it,
    /// from its polynomial (true); at or past its end, by going on from there (true if `t_end`
    /// is its end, to round-off; false if the loop must go on).
    pub(super) fn read_step_ahead(&mut self, t_end: f64) -> bool {
        let Some(ahead) = self.ahead else {
            return false;
        };
        let call = CallEnd::of(t_end, ahead.end[0], self.amplitude.slack(t_end));
        if call == CallEnd::Inside {
            self.read_step(&ahead.step, t_end);
            return true;
        }
        self.ahead = None;
        self.set_motion(ahead.end[0], &ahead.end[1..]);
        self.amplitude
            .add(ahead.largest, ahead.end[0], self.state.u.abs());
        if call == CallEnd::AtEnd {
            self.state.t = t_end;
            true
        } else {
            false
        }
    }

    /// Moves the motion to `t_end` along `step`, which holds it from the motion's time on, and
    /// counts the largest |u| on the way in the period's amplitude: before the first period
    /// ends u_amplitude is max |u| so far, which the step's end ([`Ahead::largest`]) is not.
    pub(super) fn read_step(&mut self, step: &StepAhead, t_end: f64) {
        let (t0, u0, v0) = (self.state.t, self.state.u, self.state.v);
        let y = read(step, t_end);
        let mut largest = u0.abs().max(y[0].abs());
        // |u| peaks inside only where u' changes sign: there, by bisection on the polynomial
        // (sign changes of u' on it are far apart against a call's span).
        if v0 * y[1] < 0.0 {
            let (mut a, mut b) = (t0, t_end);
            for _ in 0..60 {
                let middle = 0.5 * (a + b);
                if middle <= a || middle >= b {
                    break;
                }
                if read(step, middle)[1] * v0 > 0.0 {
                    a = middle;
                } else {
                    b = middle;
                }
            }
            largest = largest.max(read(step, 0.5 * (a + b))[0].abs());
        }
        self.set_motion(t_end, &y);
        self.amplitude.running = self.amplitude.running.max(largest);
    }

    /// How many numbers the steps taken ahead add to a saved state: [`AHEAD_SAVED`] and, where
    /// it takes them, the solver's step.
    pub(super) fn ahead_saved(&self) -> usize {
        AHEAD_SAVED
            + match &self.core {
                Core::Regularized(_, Solver::General(method)) if self.takes_steps_ahead => {
                    method.step_ahead_saved(DIM)
                }
                _ => 0,
            }
    }

    /// (t, u, u', W) from `y` = (u, u', W); W only where it is integrated.
    fn set_motion(&mut self, t: f64, y: &[f64]) {
        self.state.t = t;
        self.state.u = y[0];
        self.state.v = y[1];
        if let Core::Regularized(equations, _) = &self.core {
            if equations.with_work {
                self.state.dissipated = y[2];
            }
        }
    }

    /// Where steps may be taken ahead and the solver takes one from the motion's time that
    /// holds `t_end` (not reaching past the period's `boundary`), reads the state at `t_end`
    /// from it (true). False, with nothing changed but the work and what the solver carries
    /// towards its next step ahead, where it may not, or takes none.
    pub(super) fn take_step_ahead(&mut self, t_end: f64, boundary: f64) -> Result<bool, Error> {
        let tracks = self.tracks_amplitude;
        let Core::Regularized(equations, solver) = &mut self.core else {
            return Ok(false);
        };
        let Solver::General(method) = solver else {
            return Ok(false);
        };
        if !self.takes_steps_ahead {
            return Ok(false);
        }
        let before = self.state;
        let t = before.t;
        let mut y = [before.u, before.v, before.dissipated];
        // The step holds the way to t_end too: from the call's start, or from where u' has not
        // changed sign since (so |u| peaks only at the ends), for the amplitude so far.
        let readable =
            |step: &StepAhead| step.start() <= t || before.v * read(step, step.start())[1] >= 0.0;
        let span = (t, t_end, boundary);
        let taken = method.step_ahead(&*equations, span, &mut y, &mut self.work, None, readable)?;
        let Some((end, step)) = taken else {
            return Ok(false);
        };
        let mut largest = before.u.abs();
        if tracks && before.v * y[1] < 0.0 {
            // u' changed sign inside the step: where |u| peaks, searched from its start.
            let mut probe = solver.clone();
            probe.set_step_hint(end - t);
            let from = (t, [before.u, before.v, before.dissipated]);
            let extreme = turning_point(equations, probe, from, (end, y), &mut self.work)?;
            largest = largest.max(extreme.abs());
        }
        largest = largest.max(y[0].abs());
        self.ahead = Some(Ahead {
            step,
            end: [end, y[0], y[1], y[2]],
            largest,
        });
        // From the step's start: before it, if there is a before, |u| grew or shrank monotonically.
        if step.start() > t {
            let y = read(&step, step.start());
            self.amplitude.running = self.amplitude.running.max(y[0].abs());
            self.set_motion(step.start(), &y);
        }
        self.read_step(&step, t_end);
        Ok(true)
    }
}
