//! General integrators behind one small trait. Model-specific schemes (the paper's two-phase
//! step, the exact bristle update) live with their model.
//!
//! Integrators keep their scratch space inline (systems have at most [`MAX_DIM`] states), so a
//! doStep never allocates.

pub mod dense;
pub mod dop853;
pub mod dopri;
pub mod expm;
pub mod failures;
pub mod method;
pub mod narrow;
pub mod phase;
pub mod quadrature;
pub mod radau;
pub mod rk4;
pub mod root;
pub mod shooting;
mod starting_step;
pub mod step_ahead;
pub mod stepping;
pub mod stiffness;
pub mod switching;
#[cfg(test)]
mod test_odes;

use crate::error::{Error, Failure};

/// The largest state vector any simulation integrates (including quadrature states such as the
/// running integral of a force or of its power).
pub const MAX_DIM: usize = 9;

/// A system of ODEs `y' = f(t, y)`.
pub trait Ode {
    fn dim(&self) -> usize;
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]);

    /// How many of the leading states the right-hand side reads. The states after them, up to
    /// `dim`, are quadratures (the running integral of a force, of a power, of a velocity): the
    /// right-hand side gives their rates but never reads them, so a method need not carry them
    /// through its stages, nor an implicit one through its Newton iteration. All of them unless
    /// an ODE says otherwise.
    fn coupled(&self) -> usize {
        self.dim()
    }
}

/// What an integration cost, for the error-against-run-time report.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Work {
    pub steps: u64,
    pub rejected: u64,
    pub rhs_evaluations: u64,
}

impl Work {
    /// The work of both.
    pub fn plus(&self, other: &Work) -> Work {
        Work {
            steps: self.steps + other.steps,
            rejected: self.rejected + other.rejected,
            rhs_evaluations: self.rhs_evaluations + other.rhs_evaluations,
        }
    }
}

/// Advances `y` from `t0` to `t1`; an error says why the step could not be completed (the FMI
/// layer turns it into fmi2Discard with the message logged).
pub trait Integrator {
    fn integrate(
        &mut self,
        ode: &dyn Ode,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error>;
}

/// The most steps (sub-steps of every kind, as counted in [`Work::steps`]) one communication
/// step may take. Past it the simulation stops with a message and the FMU returns fmi2Discard,
/// instead of running for minutes when the parameters (a microgram mass, a terahertz vibration)
/// or a very long step ask for millions.
pub const MAX_STEPS_PER_DO_STEP: u64 = 2_000_000;

/// The most right-hand-side evaluations one communication step may take: the unit of work all
/// solvers share, so an implicit step (many evaluations for its Jacobian and Newton iterations)
/// counts for more than an explicit one. With the step limit, this keeps a refused doStep to
/// about a second for the explicit solvers and a few seconds for radau5.
pub const MAX_RHS_EVALUATIONS_PER_DO_STEP: u64 = 10_000_000;

/// Errs once `work` has gone past either limit since it stood at `at_start`; `t` is where the
/// step stopped.
pub fn within_step_budget(
    solver: &'static str,
    work: &Work,
    at_start: &Work,
    t: f64,
) -> Result<(), Error> {
    let steps = work.steps.saturating_sub(at_start.steps);
    let evaluations = work
        .rhs_evaluations
        .saturating_sub(at_start.rhs_evaluations);
    if steps > MAX_STEPS_PER_DO_STEP || evaluations > MAX_RHS_EVALUATIONS_PER_DO_STEP {
        Err(Error::step(
            solver,
            Failure::TooManySteps,
            format!("more than {MAX_STEPS_PER_DO_STEP} integration steps or {MAX_RHS_EVALUATIONS_PER_DO_STEP} right-hand-side evaluations in one communication step (stopped at t = {t})"),
            "fewer: a shorter communication step, or a tolerance or parameters that make the problem less stiff",
        ))
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::dopri::Dopri5;
    use super::radau::Radau5;
    use super::{Integrator, Ode, Work, MAX_DIM};

    /// A forced, damped oscillator and two quadratures of it (its energy input and the integral
    /// of its position), declared as such or not.
    struct Forced {
        declared: bool,
    }

    impl Ode for Forced {
        fn dim(&self) -> usize {
            4
        }
        fn coupled(&self) -> usize {
            if self.declared {
                2
            } else {
                4
            }
        }
        fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
            let force = (3.0 * t).cos();
            dydt[0] = y[1];
            dydt[1] = force - 0.3 * y[1] - 4.0 * y[0];
            dydt[2] = force * y[1];
            dydt[3] = y[0];
        }
    }

    fn run(solver: &mut dyn Integrator, declared: bool) -> ([f64; 4], Work) {
        let mut y = [1.0, 0.0, 0.0, 0.0];
        let mut work = Work::default();
        solver
            .integrate(&Forced { declared }, 0.0, 5.0, &mut y, &mut work)
            .unwrap();
        (y, work)
    }

    /// Declaring the quadratures changes nothing but the work: dopri5 takes the same steps to
    /// the same bits (its last stage, the new state, still carries every state); radau5 the same
    /// steps to round-off, with 2 fewer right-hand sides per Jacobian. In a debug build dopri5
    /// hands the right-hand side NaN for the quadratures in the other stages, so one that read
    /// them would fail here.
    #[test]
    fn declared_quadratures_change_only_the_work() {
        let dopri = || Dopri5::new(1e-8, [1e-10; MAX_DIM], 1.0);
        let (plain, plain_work) = run(&mut dopri(), false);
        let (declared, declared_work) = run(&mut dopri(), true);
        assert_eq!(plain, declared);
        assert_eq!(plain_work, declared_work);

        let radau = || Radau5::new(1e-8, 1e-10, 1.0);
        let (plain, plain_work) = run(&mut radau(), false);
        let (declared, declared_work) = run(&mut radau(), true);
        for (a, b) in plain.iter().zip(&declared) {
            assert!(
                (a - b).abs() <= 1e-12 * a.abs().max(1.0),
                "{plain:?} {declared:?}"
            );
        }
        assert_eq!(plain_work.steps, declared_work.steps);
        assert_eq!(plain_work.rejected, declared_work.rejected);
        assert!(
            declared_work.rhs_evaluations < plain_work.rhs_evaluations,
            "{plain_work:?} {declared_work:?}"
        );
        // The quadratures are integrated, not left at their start.
        assert!(
            declared[2].abs() > 1e-3 && declared[3].abs() > 1e-3,
            "{declared:?}"
        );
    }
}
