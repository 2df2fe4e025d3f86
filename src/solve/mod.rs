//! General integrators behind one small trait. Scene-specific schemes (the paper's two-phase
//! step, the exact bristle update) live with their scene.
//!
//! Integrators keep their scratch space inline (systems have at most [`MAX_DIM`] states), so a
//! doStep never allocates.

pub mod dense;
pub mod dopri;
pub mod expm;
pub mod radau;
pub mod rk4;

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
/// step may take: about a second of CPU for the costliest solver here. Past it the scene stops
/// with a message and the FMU returns fmi2Discard, instead of running for minutes when the
/// parameters (a microgram mass, a terahertz vibration) or a very long step ask for millions.
pub const MAX_STEPS_PER_DO_STEP: u64 = 2_000_000;

/// Errs once `work` has taken more than [`MAX_STEPS_PER_DO_STEP`] steps since it counted
/// `steps_at_start`; `t` is where the step stopped.
pub fn within_step_budget(work: &Work, steps_at_start: u64, t: f64) -> Result<(), String> {
    if work.steps.saturating_sub(steps_at_start) > MAX_STEPS_PER_DO_STEP {
        Err(format!(
            "more than {MAX_STEPS_PER_DO_STEP} integration steps in one communication step (stopped at t = {t}): use a shorter communication step, or a tolerance or parameters that make the problem less stiff"
        ))
    } else {
        Ok(())
    }
}
