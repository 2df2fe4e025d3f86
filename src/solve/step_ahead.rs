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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::dop853::Dop853;
    use crate::solve::dopri::Dopri5;
    use crate::solve::method::Method;
    use crate::solve::radau::Radau5;
    use crate::solve::rk4::Rk4;
    use crate::solve::stepping::Stepping;
    use crate::solve::test_odes::Harmonic;
    use crate::solve::Work;

    const TOL: f64 = 1e-8;

    /// The solvers that can take steps ahead, with the setting on or off.
    fn takers(on: bool) -> [Method; 2] {
        let mut dopri5 = Dopri5::new(TOL, [TOL; MAX_DIM], 1.0);
        dopri5.steps_ahead = on;
        let mut radau5 = Radau5::new(TOL, TOL, 1.0);
        radau5.steps_ahead = on;
        [Method::Dopri5(dopri5), Method::Radau5(radau5)]
    }

    /// `solver` run on the harmonic oscillator from (1, 0) to t = 0.5, as calls before a step
    /// taken ahead leave it (with a step to propose): the state there.
    fn warmed(solver: &mut Method) -> [f64; MAX_DIM] {
        let mut y = [0.0; MAX_DIM];
        y[0] = 1.0;
        let mut work = Work::default();
        solver
            .advance(&Harmonic, (0.0, 0.5), &mut y[..2], &mut work)
            .unwrap();
        y
    }

    /// A call of 1e-4 from t = 0.5, a step ahead allowed up to t = 10.
    const SPAN: (f64, f64, f64) = (0.5, 0.5 + 1e-4, 10.0);

    /// Oracle: the closed form (cos t, -sin t). The step reaches well past the call, its end is
    /// the state the solver leaves, and it reads inside within a hundred times the tolerance
    /// (a reading of another step, or a lower order's, is off by 1e-3 and more).
    #[test]
    fn a_step_taken_ahead_reads_inside_to_the_tolerance() {
        for mut solver in takers(true) {
            let mut y = warmed(&mut solver);
            let mut work = Work::default();
            let (end, step) = solver
                .step_ahead(&Harmonic, SPAN, &mut y[..2], &mut work, None, |_| true)
                .unwrap()
                .unwrap_or_else(|| panic!("{} took no step ahead", solver.name()));
            assert!(end > SPAN.1 + 0.01 && step.start() == SPAN.0, "{end}");
            let mut at_end = [0.0; MAX_DIM];
            step.at(end, &mut at_end);
            for j in 0..2 {
                assert!((at_end[j] - y[j]).abs() < 1e-12, "{}", solver.name());
            }
            for theta in [0.1, 0.37, 0.5, 0.9] {
                let t = SPAN.0 + theta * (end - SPAN.0);
                let mut read = [0.0; MAX_DIM];
                step.at(t, &mut read);
                let error = (read[0] - t.cos()).abs().max((read[1] + t.sin()).abs());
                assert!(error < 100.0 * TOL, "{} at {t}: {error:e}", solver.name());
            }
        }
    }

    /// A step the caller refuses is undone: the state and the solver as they were, only the
    /// work it cost counted.
    #[test]
    fn a_refused_step_changes_nothing_but_the_work() {
        for mut solver in takers(true) {
            let y_before = warmed(&mut solver);
            let solver_before = solver.clone();
            let (mut y, mut work) = (y_before, Work::default());
            let taken = solver
                .step_ahead(&Harmonic, SPAN, &mut y[..2], &mut work, None, |_| false)
                .unwrap();
            assert_eq!(taken, None);
            assert_eq!(y, y_before, "{}", solver.name());
            assert_eq!(solver, solver_before);
            assert!(work.rhs_evaluations > 0);
        }
    }

    /// The solvers that take no steps ahead, and those whose setting is off, take none and
    /// touch nothing.
    #[test]
    fn a_solver_without_steps_ahead_takes_none() {
        let others = [
            Method::Dop853(Dop853::new(TOL, [TOL; MAX_DIM], 1.0)),
            Method::Rk4(Rk4 { h_max: 0.01 }),
        ];
        for mut solver in others.into_iter().chain(takers(false)) {
            let y_before = warmed(&mut solver);
            let solver_before = solver.clone();
            let (mut y, mut work) = (y_before, Work::default());
            let taken = solver
                .step_ahead(&Harmonic, SPAN, &mut y[..2], &mut work, None, |_| true)
                .unwrap();
            assert_eq!(taken, None, "{}", solver.name());
            assert!(!solver.takes_steps_ahead());
            assert_eq!(
                (y, work, &solver),
                (y_before, Work::default(), &solver_before)
            );
        }
    }

    /// What a step taken ahead writes into a saved state, its solver reads back to the same
    /// step; numbers that cannot be one are refused.
    #[test]
    fn a_saved_step_ahead_reads_back() {
        for mut solver in takers(true) {
            let mut y = warmed(&mut solver);
            let mut work = Work::default();
            let (_, step) = solver
                .step_ahead(&Harmonic, SPAN, &mut y[..2], &mut work, None, |_| true)
                .unwrap()
                .unwrap();
            let mut saved = Vec::new();
            step.write(2, &mut saved);
            assert_eq!(saved.len(), solver.step_ahead_saved(2), "{}", solver.name());
            assert_eq!(solver.restore_step_ahead(2, &saved), Some(step));
            assert_eq!(solver.restore_step_ahead(2, &saved[1..]), None);
        }
    }
}
