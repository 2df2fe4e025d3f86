//! The solver menu of scene L. `exponential` is the simulation's own scheme (in the parent module),
//! `closed_form` the exact bristle of Dahl at alpha = 1 ([`ClosedForm`]); the others integrate
//! the bristle ODE (`equations.rs`) together with the force integral `q' = FT(z, vr(t))`
//! and the friction work `w' = FT vr` as quadrature states (same order as the solver), over
//! sub-steps that never contain a sign change of vr.

use super::closed_form::ClosedForm;
use super::equations::{Bristle, LoadedLaw};
use super::switches::LongitudinalSolver;
use super::Law;
use crate::error::{Error, Failure};
use crate::models::longitudinal::table::vr;
use crate::models::require_tolerance;
use crate::models::switch::Switch;
use crate::solve::dopri::Dopri5;
use crate::solve::method::Method;
use crate::solve::radau::Radau5;
use crate::solve::rk4::Rk4;
use crate::solve::stepping::Stepping;
use crate::solve::{Integrator, Work, MAX_DIM};
use crate::variables::values::ValueSet;

#[derive(Clone, Debug, PartialEq)]
pub enum Solver {
    Exponential,
    /// A general solver on the bristle ODE (rk4's steps of at most 1/n period).
    General(Method),
    ClosedForm(ClosedForm),
}

impl Solver {
    pub fn new(
        values: &ValueSet,
        law: Law,
        fc: f64,
        (f, steps_per_period): (f64, u32),
        slip_per_period: f64,
        load_input: bool,
    ) -> Result<Self, Error> {
        let name = match LongitudinalSolver::read(values, vr::SOLVER)? {
            LongitudinalSolver::Auto => match law {
                Law::Coulomb => LongitudinalSolver::ClosedForm,
                Law::Dahl(d) if d.alpha == 1.0 && !load_input => LongitudinalSolver::ClosedForm,
                _ => LongitudinalSolver::Dopri5,
            },
            name => name,
        };
        match name {
            LongitudinalSolver::Exponential => return Ok(Solver::Exponential),
            LongitudinalSolver::Rk4 => {
                return Ok(Solver::General(Method::Rk4(Rk4 {
                    h_max: 1.0 / (f * f64::from(steps_per_period)),
                })))
            }
            // The adaptive solvers and closed_form (auto is resolved above).
            _ => {}
        }
        let rtol = require_tolerance(values, vr::TOLERANCE)?;
        // Absolute tolerances on the scale of each state: the deflection, FC/kt at saturation or
        // the distance slid in a period if that is less (a heavy body on a soft contact never
        // nears saturation, and FC/kt would loosen the control by FC over the forces met), and
        // the force integral over a period, the spring force of that deflection over 1/f.
        let kt = match law {
            Law::Dahl(d) => d.kt,
            Law::LuGre(l) => l.sigma0,
            Law::Coulomb => 1.0,
        };
        let z_scale = (fc / kt).min(slip_per_period);
        let q_scale = match law {
            Law::Coulomb => fc / f,
            _ => kt * z_scale / f,
        };
        if name == LongitudinalSolver::ClosedForm {
            return match law {
                Law::Dahl(d) if d.alpha == 1.0 => Ok(Solver::ClosedForm(ClosedForm::new(
                    rtol,
                    fc,
                    kt * z_scale,
                ))),
                Law::Coulomb => Ok(Solver::ClosedForm(ClosedForm::new(rtol, fc, fc))),
                Law::Dahl(d) => Err(Error::combination(
                    format!("solver closed_form with law dahl at alpha = {}", d.alpha),
                    "alpha = 1 (the bristle is in closed form only there), or solver dopri5 or radau5",
                )),
                Law::LuGre(_) => Err(Error::combination(
                    "solver closed_form with law lugre",
                    "law dahl (alpha = 1) or coulomb, or solver dopri5 or radau5 for LuGre",
                )),
            };
        }
        // LuGre's damping force sigma1 z' puts sigma1 (z(T) - z(0)) into a period's force
        // integral, so FT_mean takes the error in z times sigma1 f/sigma0 (of FC/sigma0): where
        // that gain is above 1, the solvers hold every state to the tolerance over it.
        let rtol = match law {
            Law::LuGre(l) => rtol / (l.sigma1 * f / l.sigma0).max(1.0),
            _ => rtol,
        };
        // The work w is left out of the error control (an infinite atol): the steps the
        // deflection needs integrate it to the same order.
        Ok(if name == LongitudinalSolver::Radau5 {
            let mut radau = Radau5::new(rtol, rtol * z_scale.min(q_scale), 1.0 / f);
            radau.atol_scale[2] = f64::INFINITY;
            Solver::General(Method::Radau5(radau))
        } else {
            let mut atol = [rtol * z_scale; MAX_DIM];
            atol[1] = rtol * q_scale;
            atol[2] = f64::INFINITY;
            Solver::General(Method::Dopri5(Dopri5::new(rtol, atol, 1.0 / f)))
        })
    }

    /// The solver's name, as the switch spells it (in its errors).
    pub fn name(&self) -> &'static str {
        match self {
            Solver::Exponential => "exponential",
            Solver::ClosedForm(_) => "closed_form",
            Solver::General(m) => m.name(),
        }
    }

    /// Sub-steps on a grid of 1/n period (the adaptive solvers choose their own steps).
    pub fn fixed_step(&self) -> bool {
        match self {
            Solver::Exponential => true,
            Solver::General(m) => m.tolerance().is_none(),
            Solver::ClosedForm(_) => false,
        }
    }

    /// The tolerance of a general solver on the bristle ODE (None for rk4 and the scene's own
    /// schemes).
    pub fn ode_tolerance(&self) -> Option<f64> {
        match self {
            Solver::General(m) => m.tolerance(),
            _ => None,
        }
    }

    /// The general solver, if it is one.
    pub fn general_mut(&mut self) -> Option<&mut Method> {
        match self {
            Solver::General(m) => Some(m),
            _ => None,
        }
    }

    /// The tolerance a solver integrates to (None for the fixed-step ones).
    pub fn tolerance(&self) -> Option<f64> {
        match self {
            Solver::General(m) => m.tolerance(),
            Solver::ClosedForm(c) => Some(c.rtol),
            Solver::Exponential => None,
        }
    }

    /// The step (or quadrature panel) to try next, part of a saved FMU state.
    pub fn step_hint(&self) -> f64 {
        match self {
            Solver::General(m) => m.step_hint(),
            Solver::ClosedForm(c) => c.quadrature.h_next,
            Solver::Exponential => 0.0,
        }
    }

    pub fn set_step_hint(&mut self, h: f64) {
        match self {
            Solver::General(m) => m.set_step_hint(h),
            Solver::ClosedForm(c) => c.quadrature.h_next = h,
            Solver::Exponential => {}
        }
    }

    /// Advances `z` over `[t0, t1]` (no sign change of vr inside); returns the integrals of the
    /// force and of its power FT vr (0 for those beyond the first `dim` states).
    pub fn advance(
        &mut self,
        (law, dim): (&Law, usize),
        (velocity, loaded): (&dyn Fn(f64) -> f64, Option<LoadedLaw>),
        t0: f64,
        t1: f64,
        z: &mut f64,
        work: &mut Work,
    ) -> Result<(f64, f64), Error> {
        let ode = Bristle {
            law,
            velocity,
            loaded,
            dim,
        };
        let mut y = [*z, 0.0, 0.0];
        match self {
            Solver::Exponential | Solver::ClosedForm(_) => {
                return Err(Error::step(
                    self.name(),
                    Failure::Misuse,
                    "an ODE to integrate",
                    "a general solver (exponential and closed_form are not ODE solvers)",
                ))
            }
            Solver::General(m) => m.integrate(&ode, t0, t1, &mut y, work)?,
        }
        *z = y[0];
        Ok((y[1], y[2]))
    }
}
