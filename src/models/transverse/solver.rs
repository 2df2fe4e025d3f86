//! The solver menu of scene T: a general solver on the continuous-time equations (dopri5,
//! radau5, dop853, rk4), the paper's own two-phase step, or the exact bristle update
//! (`exponential`); and where in the Stribeck band the adaptive ones end their steps.

use super::switches::TransverseSolver;
use super::{exponential, tolerance_scales, two_phase, Clocked, VY, ZY};
use crate::solve::dop853::Dop853;
use crate::solve::dopri::Dopri5;
use crate::solve::method::Method;
use crate::solve::radau::Radau5;
use crate::solve::rk4::Rk4;
use crate::solve::stepping::{self, Stepping};
use crate::solve::MAX_DIM;

/// Where else, in multiples of vs, steps end inside the Stribeck band of a rate whose absolute
/// value has a kink (v1 and v2 for the split law, v1 + v2 for the total law), when the
/// tolerance asks for it ([`band_points`]). Inside the band g(v) rises to FS over a time of
/// about vs / |v'| (a tenth of a microsecond at the paper's values), and the slip |v|/g(v) has
/// a bump there that steps ending only on v = 0 span: the stages miss the bump and so does the
/// error estimate, which leaves the split law an error floor in FFx_mean whatever the
/// tolerance. Ends at 3 vs lower the floor, ends at vs and 3 vs let the error follow the
/// tolerance, ends at 2 vs do not help (measured with benches/transverse.py: see
/// docs/performance.md, "Benchmarks" and "Measurements behind the code").
pub(super) const BAND_POINTS_COARSE: [f64; 1] = [3.0];
/// The band's step ends for the tightest tolerances: at vs too.
pub(super) const BAND_POINTS_FINE: [f64; 2] = [1.0, 3.0];

/// The tolerance at and below which dopri5 ends steps at [`BAND_POINTS_COARSE`]. Above it the
/// unresolved bump is within the tolerance and the step ends would only cost right-hand sides;
/// at it they are what meets the tolerance (split law, the benchmark's case: errors and
/// costs with and without them in docs/performance.md, "Measurements behind the code").
const DOPRI5_COARSE_BAND_RTOL: f64 = 3e-7;

/// The tolerance at and below which dopri5 ends steps at [`BAND_POINTS_FINE`] instead: there
/// the coarse ends' error floor is no longer well inside the tolerance. Above it the coarse
/// ends cost fewer right-hand sides and fewer kinks to foresee for about the fine ends' error,
/// at the paper's larger amplitudes too (docs/performance.md, "Measurements behind the code").
const DOPRI5_FINE_BAND_RTOL: f64 = 1e-7;

/// radau5 ends steps at [`BAND_POINTS_FINE`] from this tolerance down: above it radau5 meets
/// the tolerance without them, and they would only cost it right-hand sides
/// (docs/performance.md, "Measurements behind the code").
const RADAU5_FINE_BAND_RTOL: f64 = 1e-7;

/// The points inside the Stribeck band where the solver `name` ends steps at the tolerance
/// `rtol`: set by the tolerance for the adaptive solvers, none for the others.
pub(super) fn band_points(name: TransverseSolver, rtol: f64) -> &'static [f64] {
    use TransverseSolver::{Dop853, Dopri5, Radau5};
    match name {
        Dopri5 | Dop853 if rtol <= DOPRI5_FINE_BAND_RTOL => &BAND_POINTS_FINE,
        Dopri5 | Dop853 if rtol <= DOPRI5_COARSE_BAND_RTOL => &BAND_POINTS_COARSE,
        Radau5 if rtol <= RADAU5_FINE_BAND_RTOL => &BAND_POINTS_FINE,
        _ => &[],
    }
}

/// A general solver on the equations, or one of the scene's own schemes.
#[derive(Clone, Debug, PartialEq)]
pub enum Solver {
    General(Method),
    TwoPhase(two_phase::TwoPhase),
    Exponential(exponential::Exponential),
}

impl Solver {
    /// The solver's name, as the switch spells it (in its errors).
    pub(super) fn name(&self) -> &'static str {
        match self {
            Solver::General(m) => m.name(),
            Solver::TwoPhase(_) => "two_phase",
            Solver::Exponential(_) => "exponential",
        }
    }

    /// The relative tolerance of an adaptive solver.
    pub(super) fn rtol(&self) -> Option<f64> {
        match self {
            Solver::General(m) => m.tolerance(),
            Solver::TwoPhase(_) | Solver::Exponential(_) => None,
        }
    }

    /// How many numbers [`Solver::save_into`] writes.
    pub(super) fn saved_len(&self) -> usize {
        match self {
            Solver::General(_) => stepping::SAVED,
            Solver::Exponential(_) => 1,
            Solver::TwoPhase(_) => two_phase::SAVED,
        }
    }

    /// Appends what the solver carries from one call to the next to a saved state: a general
    /// solver's, the two-phase step's forces, a 0 for the exponential scheme (which carries
    /// nothing: its place keeps the states' layout).
    pub(super) fn save_into(&self, out: &mut Vec<f64>) {
        match self {
            Solver::General(m) => m.save_into(out),
            Solver::Exponential(_) => out.push(0.0),
            Solver::TwoPhase(tp) => out.extend_from_slice(&tp.save()),
        }
    }

    /// Restores what [`Solver::save_into`] wrote.
    pub(super) fn restore(&mut self, saved: &[f64]) {
        match self {
            Solver::General(m) => m.restore(saved),
            Solver::Exponential(_) => {}
            Solver::TwoPhase(tp) => tp.restore(saved),
        }
    }

    /// The solver `name` picks, at the tolerance `rtol`, with `steps` per period for the fixed
    /// steps; `start` is the start time and state (the two-phase step starts from it), `vd` the
    /// drive's nominal velocity, and `axial` says the 1D equations run.
    pub(super) fn new(
        name: TransverseSolver,
        p: &Clocked,
        (start_time, y): (f64, &[f64; MAX_DIM]),
        steps: u32,
        (rtol, vd): (f64, f64),
        axial: bool,
    ) -> Self {
        let f = p.f;
        match name {
            TransverseSolver::Rk4 => Solver::General(Method::Rk4(Rk4 {
                h_max: 1.0 / (f * f64::from(steps)),
            })),
            TransverseSolver::TwoPhase => {
                Solver::TwoPhase(two_phase::TwoPhase::new(p, start_time, y, steps))
            }
            TransverseSolver::Exponential => Solver::Exponential(exponential::Exponential {
                steps_per_period: steps,
            }),
            TransverseSolver::Dopri5 | TransverseSolver::Radau5 | TransverseSolver::Dop853 => {
                // The parameter vd, the drive's nominal velocity, with an input drive too, not
                // vd_in's value at the build: fmi2SetFMUstate builds again with the value then,
                // and a restored run must take the steps the first one took.
                let mut scale = tolerance_scales(p, vd);
                if axial {
                    // The 1D equations leave the y axis at rest: out of the error control, so
                    // that its zeros do not dilute the others' errors.
                    scale[VY] = f64::INFINITY;
                    scale[ZY] = f64::INFINITY;
                }
                Solver::General(if name == TransverseSolver::Radau5 {
                    let mut radau = Radau5::new(rtol, rtol, 0.05 / f);
                    radau.atol_scale = scale;
                    Method::Radau5(radau)
                } else if name == TransverseSolver::Dop853 {
                    Method::Dop853(Dop853::new(rtol, scale.map(|s| rtol * s), 0.05 / f))
                } else {
                    let mut dopri5 = Dopri5::new(rtol, scale.map(|s| rtol * s), 0.05 / f);
                    // Its steps are long against a master's short communication steps, and
                    // read inside to their own order.
                    dopri5.steps_ahead = true;
                    Method::Dopri5(dopri5)
                })
            }
        }
    }
}
