//! The solver menu of scene O's regularised core: Radau IIA (L-stable, the default),
//! Dormand-Prince 5(4) ending its steps on the kinks of H at |u'| = D (and D + Da, D + 2 Da with
//! stiction), fixed-step RK4, and `piecewise`: the linear motion outside H's band in closed form
//! ([`super::linear_phase`]), dopri5 inside it.

use super::switches::OscillatorSolver;
use super::Equations;
use crate::error::Error;
use crate::solve::dopri::Dopri5;
use crate::solve::method::Method;
use crate::solve::radau::Radau5;
use crate::solve::rk4::Rk4;
use crate::solve::stepping::Stepping;
use crate::solve::{Work, MAX_DIM};

#[derive(Clone, Debug, PartialEq)]
pub enum Solver {
    /// A general solver on the whole motion.
    General(Method),
    /// dopri5 inside the band, which the closed form outside it leaves to.
    Piecewise(Dopri5),
}

impl Solver {
    /// `name` is the `solver` item; `h_max` the longest step (the fixed step of rk4).
    /// The friction work, state 2, is left out of the error control (an infinite atol): the
    /// steps the motion needs integrate it to the same order.
    pub fn new(name: OscillatorSolver, rtol: f64, atol: f64, h_max: f64) -> Self {
        match name {
            OscillatorSolver::Dopri5 | OscillatorSolver::Piecewise => {
                let mut atols = [atol; MAX_DIM];
                atols[2] = f64::INFINITY;
                let dopri5 = Dopri5::new(rtol, atols, h_max);
                if name == OscillatorSolver::Piecewise {
                    Solver::Piecewise(dopri5)
                } else {
                    Solver::General(Method::Dopri5(dopri5))
                }
            }
            OscillatorSolver::Rk4 => Solver::General(Method::Rk4(Rk4 { h_max })),
            OscillatorSolver::Radau5 => {
                let mut radau = Radau5::new(rtol, atol, h_max);
                radau.atol_scale[2] = f64::INFINITY;
                // Its steps are long against short communication steps, and read inside to
                // the tolerance.
                radau.steps_ahead = true;
                Solver::General(Method::Radau5(radau))
            }
        }
    }

    /// The solver's name, as the switch spells it (in its errors).
    pub fn name(&self) -> &'static str {
        match self {
            Solver::General(m) => m.name(),
            Solver::Piecewise(_) => "piecewise",
        }
    }

    pub fn atol(&self) -> f64 {
        match self {
            Solver::General(Method::Radau5(r)) => r.atol,
            Solver::General(Method::Dopri5(d)) | Solver::Piecewise(d) => d.atol[0],
            // The turning-point search stops at this resolution of u' (a fixed step has no
            // tolerance).
            Solver::General(_) => 1e-12,
        }
    }

    /// The step an adaptive solver would try next (part of a saved FMU state); 0 for rk4.
    pub fn step_hint(&self) -> f64 {
        match self {
            Solver::General(m) => m.step_hint(),
            Solver::Piecewise(d) => d.h,
        }
    }

    pub fn set_step_hint(&mut self, h: f64) {
        match self {
            Solver::General(m) => m.set_step_hint(h),
            Solver::Piecewise(d) => d.h = h,
        }
    }

    /// The stability bound of a fixed-step solver ([`Stepping::stability_bound`]).
    pub fn stability_bound(&self) -> Option<f64> {
        match self {
            Solver::General(m) => m.stability_bound(),
            Solver::Piecewise(_) => None,
        }
    }

    /// Where dopri5 found the problem stiff, once; radau5 and rk4 never say.
    pub fn stiff_since(&mut self) -> Option<f64> {
        match self {
            Solver::General(m) => m.stiff_since(),
            Solver::Piecewise(d) => d.stiff_since(),
        }
    }

    /// Advances `y` from `t0` to `t1`.
    pub fn integrate(
        &mut self,
        equations: &Equations,
        (t0, t1): (f64, f64),
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        match self {
            Solver::General(m) => m.advance(equations, (t0, t1), y, work),
            Solver::Piecewise(d) => d.integrate_switched(equations, t0, t1, y, work),
        }
    }
}
