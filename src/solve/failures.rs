//! The failures every general solver can meet, said the same way by each: a solver names
//! itself, what it found and what would have worked.

use crate::error::{Error, Failure};

/// More states than the solvers' fixed-size work arrays hold.
pub fn states_do_not_fit(solver: &'static str, n: usize, max: usize) -> Error {
    Error::step(
        solver,
        Failure::Misuse,
        format!("{n} states"),
        format!("at most {max}"),
    )
}

/// An interval or settings an adaptive solver cannot integrate with.
pub fn bad_settings(solver: &'static str, (t0, t1): (f64, f64), rtol: f64, h_max: f64) -> Error {
    Error::step(
        solver,
        Failure::Misuse,
        format!("the interval [{t0}, {t1}] with rtol {rtol} and h_max {h_max}"),
        "t1 >= t0, rtol > 0 and h_max > 0",
    )
}

/// More than `max` steps between `t0` and `t1`, stopped at `t`.
pub fn too_many_steps(solver: &'static str, max: u64, (t0, t1): (f64, f64), t: f64) -> Error {
    Error::step(
        solver,
        Failure::TooManySteps,
        format!("more than {max} steps between t = {t0} and t = {t1} (stopped at t = {t})"),
        "fewer: a looser tolerance, a shorter communication step, or a solver made for stiff problems",
    )
}

/// The step `h` fell at `t` below `h_tiny`, the least step the clock resolves there.
pub fn step_fell(solver: &'static str, (h, t, h_tiny): (f64, f64, f64), rtol: f64) -> Error {
    Error::step(
        solver,
        Failure::StepTooShort,
        format!("the step fell to {h:e} s at t = {t:e}, below the {h_tiny:e} s that t resolves"),
        format!("a solution smooth enough there for rtol {rtol:e} (a looser tolerance), or t nearer 0 for its time scales"),
    )
}

/// The state left the finite numbers at `t`.
pub fn not_finite(solver: &'static str, t: f64) -> Error {
    Error::step(
        solver,
        Failure::NotFinite,
        format!("the state became non-finite at t = {t}"),
        "a finite state: a tighter tolerance, or parameters of moderate size",
    )
}

/// A fixed-step scheme asked for `steps` steps of `h` to reach `t1` in one call.
pub fn too_many_fixed_steps(solver: &'static str, steps: f64, h: f64, t1: f64) -> Error {
    Error::step(
        solver,
        Failure::TooManySteps,
        format!("{steps:.3e} steps of {h:e} s to reach t = {t1}"),
        format!("at most {} in one communication step: a shorter communication step or fewer steps_per_period", super::MAX_STEPS_PER_DO_STEP),
    )
}

/// A fixed-step scheme whose state left the finite numbers by `t1`.
pub fn fixed_step_not_finite(solver: &'static str, t1: f64) -> Error {
    Error::step(
        solver,
        Failure::NotFinite,
        format!("the state became non-finite by t = {t1}"),
        "a finite state: more steps_per_period",
    )
}
