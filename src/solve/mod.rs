//! General integrators behind one small trait. Scene-specific schemes (the paper's two-phase
//! step, the exact bristle update) live with their scene.
//!
//! Integrators keep their scratch space inline (systems have at most [`MAX_DIM`] states), so a
//! doStep never allocates.

pub mod dense;
pub mod dopri;
pub mod expm;
pub mod narrow;
pub mod phase;
pub mod radau;
pub mod rk4;
pub mod root;
pub mod stiffness;

/// The largest state vector any scene integrates (including quadrature states such as the
/// running integral of a force or of its power).
pub const MAX_DIM: usize = 9;

/// A system of ODEs `y' = f(t, y)`.
pub trait Ode {
    fn dim(&self) -> usize;
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]);
}

/// What an integration cost, for the error-against-run-time report.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Work {
    pub steps: u64,
    pub rejected: u64,
    pub rhs_evaluations: u64,
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
    ) -> Result<(), String>;
}

/// The most steps (sub-steps of every kind, as counted in [`Work::steps`]) one communication
/// step may take. Past it the scene stops with a message and the FMU returns fmi2Discard,
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
pub fn within_step_budget(work: &Work, at_start: &Work, t: f64) -> Result<(), String> {
    let steps = work.steps.saturating_sub(at_start.steps);
    let evaluations = work
        .rhs_evaluations
        .saturating_sub(at_start.rhs_evaluations);
    if steps > MAX_STEPS_PER_DO_STEP || evaluations > MAX_RHS_EVALUATIONS_PER_DO_STEP {
        Err(format!(
            "more than {MAX_STEPS_PER_DO_STEP} integration steps or {MAX_RHS_EVALUATIONS_PER_DO_STEP} right-hand-side evaluations in one communication step (stopped at t = {t}): use a shorter communication step, or a tolerance or parameters that make the problem less stiff"
        ))
    } else {
        Ok(())
    }
}
