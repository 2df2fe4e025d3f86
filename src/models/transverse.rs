//! Scene T: a body pulled over a support vibrating across the sliding direction, with a 2D LuGre
//! contact (paper T).
//!
//! State `[x, x', z_x, lambda, w, q, y, y', z_y]`: body position and velocity, the bristle
//! `z = N - M`, the drive stretch `lambda = vd t - x` (a state of its own so Fd does not lose
//! digits to `vd t - x` in long runs), `q`, the integral of FFx since the last sub-step
//! boundary, which feeds [`PeriodMean`], and `w`, the work done on the contact since the start
//! (its power is FF e.(v_body - v_M) = FF (v1 + v2)), which gives the dissipated energy. The
//! planar part comes last so a simulation without vibration (`axial`) integrates only the first
//! five or six states, the others staying 0.
//! Sub-steps end on communication points and vibration period boundaries (those only when
//! FFx_mean is read, [`Trim`]); the continuous-time
//! solvers integrate the continuous-time ODE, `two_phase` runs the paper's own scheme on the same
//! state, `exponential` (its own module) the exact bristle update around a midpoint step of the
//! body, for stiff contacts.

mod ahead;
mod axial;
mod equations;
mod exponential;
mod solver;
#[cfg(feature = "tools")]
pub mod stability;
mod start;
pub mod switches;
pub mod table;
mod two_phase;

pub use equations::{tolerance_scales, Clocked, Equations, Params};
pub use solver::Solver;

use equations::{band_coordinate, kink_switches, BAND};

use super::input_scheme::{self, Extrapolator, InputScheme};
use super::period_mean::PeriodMean;
use super::ramp::Ramp;
use super::{require_passive, resolved_energy, Scope, Simulation};
use crate::error::{Error, Failure};
use crate::models::transverse::table::vr;
use crate::solve::method::Method;
use crate::solve::stepping::Stepping;
use crate::solve::switching::Switching;
use crate::solve::{within_step_budget, Integrator, Ode, Work, MAX_DIM};
use crate::variables::values::ValueSet;
use nalgebra::Vector2;
use std::f64::consts::TAU;
use switches::TransverseSolver;

// The state: first what the right-hand side reads (the body's velocity, the drive spring, the
// bristle), then the quadratures ([`Ode::coupled`]). The 1D equations ([`axial`]) use the same
// places, with the y axis at rest. Public for code that restates the equations (the solver
// comparison in benches/diffsol_compare).
pub const DIM: usize = 9;
pub const VX: usize = 0;
pub const ZX: usize = 1;
pub const LAMBDA: usize = 2;
pub const VY: usize = 3;
pub const ZY: usize = 4;
/// The states the planar right-hand side reads.
pub const COUPLED: usize = ZY + 1;
/// The states the 1D right-hand side ([`axial`]) reads.
const COUPLED_AXIAL: usize = LAMBDA + 1;
pub const X: usize = 5;
pub const W: usize = 6;
pub const Q: usize = 7;
pub const Y: usize = 8;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Drive {
    Prescribed(f64),
    Input,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Transverse {
    /// The parameters, on the clock of the simulation's current time.
    pub p: Clocked,
    pub drive: Drive,
    pub solver: Solver,
    /// The points inside the Stribeck band where the solver ends steps ([`solver::band_points`]).
    band_points: &'static [f64],
    /// Coulomb force FC = mu m g, the scale of the outputs.
    pub fc: f64,
    start_time: f64,
    t: f64,
    /// The state at t, except inside a step taken ahead, whose interpolant holds it there
    /// ([`Transverse::state`]).
    y: [f64; MAX_DIM],
    /// vd_in as set at the current step's start (input source).
    vd_held: f64,
    /// How vd_in moves over a step: its past values and the master's derivative.
    vd_input: Extrapolator,
    input_scheme: InputScheme,
    mean: PeriodMean,
    pub work: Work,
    /// What the scope lets the simulation skip.
    pub trim: Trim,
    /// Why the periodic start fell back to the transient, for the first
    /// [`Simulation::take_warning`].
    notice: Option<String>,
    /// A dopri5 step taken past the communication point, which the calls inside it read.
    ahead: Option<ahead::Ahead>,
}

/// The general model's parts a trimmed scope lets go (none for the full model, which keeps one
/// general path to check the trimmed ones against). The work w stays even with W_diss hidden:
/// it feeds the passivity check that stops unstable fixed steps, and leaving it out of dopri5's
/// 1D state gained nothing beyond the timing noise on the Fig. 4a case (docs/performance.md,
/// "Measurements behind the code").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trim {
    /// No vibration reaches the contact (va or eta fixed at 0): the 1D equations of `axial`.
    pub axial: bool,
    /// FFx_mean is read: the force integral q and sub-steps that end on period boundaries.
    pub mean: bool,
}

impl Trim {
    fn of(scope: &Scope, values: &ValueSet, solver: TransverseSolver) -> Self {
        let still = |vref: u32| scope.fixes(vref) && values.real(vref) == 0.0;
        Trim {
            // The paper's two-phase step is written in the plane; it stays as the paper has it.
            axial: (still(vr::VA) || still(vr::ETA)) && solver != TransverseSolver::TwoPhase,
            mean: scope.exposes(vr::FFX_MEAN),
        }
    }

    /// How many entries of the state the solver integrates.
    pub fn dim(&self) -> usize {
        match (self.axial, self.mean) {
            (false, _) => DIM,
            (true, true) => Q + 1,
            (true, false) => Q,
        }
    }
}

pub fn build(
    values: &ValueSet,
    start_time: f64,
    scope: &Scope,
) -> Result<Box<dyn Simulation>, Error> {
    Ok(Box::new(Transverse::with_scope(values, start_time, scope)?))
}

impl Transverse {
    fn vd(&self) -> f64 {
        match self.drive {
            Drive::Prescribed(v) => v,
            Drive::Input => self.vd_held,
        }
    }

    pub fn time(&self) -> f64 {
        self.t
    }

    /// FF, FFx, FFy, s, beta now.
    pub fn forces(&self) -> (f64, f64, f64, f64, f64) {
        self.forces_at(&self.state())
    }

    /// [`Transverse::forces`] with the state now, `y`, already at hand.
    fn forces_at(&self, y: &[f64; MAX_DIM]) -> (f64, f64, f64, f64, f64) {
        match &self.solver {
            Solver::TwoPhase(tp) => tp.forces(),
            _ => {
                let c = self.p.contact(0.0, y);
                (c.ff, c.ffx(), c.ffy(), c.s, c.beta())
            }
        }
    }

    /// FF, FFx and s now: [`Transverse::forces`] without the angle beta (an arctangent), which
    /// only its output needs, for the checks and readings that every step makes.
    fn ff_ffx_s(&self) -> (f64, f64, f64) {
        match &self.solver {
            Solver::TwoPhase(tp) => {
                let (ff, ffx, _, s, _) = tp.forces();
                (ff, ffx, s)
            }
            _ => {
                let c = self.p.contact(0.0, &self.state());
                (c.ff, c.ffx(), c.s)
            }
        }
    }

    pub fn mean_ffx(&self) -> f64 {
        self.mean_now(&self.state())
            .value(self.t, self.ff_ffx_s().1)
    }

    pub fn position(&self) -> (f64, f64) {
        let y = self.state();
        (y[X], y[Y])
    }

    pub fn drive_force(&self) -> f64 {
        self.p.drive_force(&self.state(), self.vd())
    }

    /// The energy the contact has dissipated since the start: the work done on it minus the
    /// energy kt s^2/2 stored in its deflection.
    pub fn dissipated_energy(&self) -> f64 {
        self.dissipated_with(&self.state(), self.ff_ffx_s().2)
    }

    /// [`Transverse::dissipated_energy`] with the state `y` and the deflection s at hand.
    fn dissipated_with(&self, y: &[f64; MAX_DIM], s: f64) -> f64 {
        y[W] - 0.5 * self.p.law.kt * s * s
    }

    /// Refuses the state `y` at `t`, with its contact force FF and deflection s, where it is
    /// not finite or the contact gave back more energy than the tolerance resolves.
    fn check_motion(&self, t: f64, y: &[f64; MAX_DIM], (ff, s): (f64, f64)) -> Result<(), Error> {
        if y.iter().all(|v| v.is_finite()) && ff.is_finite() {
            // The bristle damping ht (eq. 5) can return a little energy in transients, hence
            // the looser tolerance than scene L's.
            let kt = self.p.law.kt;
            require_passive(
                self.solver.name(),
                (y[W] - 0.5 * kt * s * s, 0.5 * kt * s * s),
                1e-3,
                self.solver
                    .rtol()
                    .map_or(0.0, |rtol| resolved_energy(rtol, self.fc, kt)),
                (
                    t,
                    "use more steps_per_period, or the dopri5 or radau5 solver",
                ),
            )
        } else {
            Err(Error::step(
                self.solver.name(),
                Failure::NotFinite,
                format!("the state became non-finite at t = {t}"),
                "a finite state: a smaller step or the dopri5 solver",
            ))
        }
    }

    /// Advances over one sub-step `[start, end]` that lies within one period; `origin` is the
    /// absolute time the equations' time counts from (the step's start).
    fn substep(&mut self, origin: f64, (start, end): (f64, f64), vd: Ramp) -> Result<(), Error> {
        let (t0, t1) = (start - origin, end - origin);
        // Sub-step ends that met in the round-off of the absolute time (a period's boundary a
        // few ulps from the master's point): one explicit step, as the adaptive solvers took
        // there when they counted absolute time (counted from the step's start, they would take
        // the interval for a real one and refine it).
        let round_off = super::within_round_off(start, end);
        self.y[Q] = 0.0;
        let band_points = self.band_points;
        let planar = Equations::new(&self.p, vd, band_points);
        let axial = axial::Axial {
            p: &self.p,
            vd,
            dim: self.trim.dim(),
            band_points,
        };
        let eq: &dyn Switching = if self.trim.axial { &axial } else { &planar };
        match &mut self.solver {
            Solver::General(_) if round_off => {
                let mut step = Method::across_round_off();
                step.integrate(eq, t0, t1, &mut self.y, &mut self.work)?;
            }
            // On the equations' own types rather than through `eq`: the contact then inlines
            // into the right-hand side, and the step takes fewer instructions
            // (docs/performance.md, "Measurements behind the code").
            Solver::General(m) if self.trim.axial => {
                m.advance(&axial, (t0, t1), &mut self.y, &mut self.work)?
            }
            Solver::General(m) => m.advance(&planar, (t0, t1), &mut self.y, &mut self.work)?,
            Solver::TwoPhase(tp) => {
                tp.advance(&self.p, vd, (origin, t0, t1), &mut self.y, &mut self.work)?;
            }
            Solver::Exponential(ex) => {
                let stepper = exponential::Stepper {
                    p: &self.p,
                    eq,
                    axial: self.trim.axial,
                };
                ex.advance(&stepper, t0, t1, &mut self.y, &mut self.work)?;
            }
        }
        if self.trim.mean {
            self.mean.add(self.y[Q], end);
        }
        Ok(())
    }
}

impl Simulation for Transverse {
    fn do_step(&mut self, h: f64, values: &ValueSet) -> Result<(), Error> {
        super::require_step(h)?;
        // A derivative applies to this step only (fmi2DoStep restores it with the rest of the
        // state when the step fails).
        let vd = if self.drive == Drive::Input {
            let v = values.real(vr::VD_IN);
            if !v.is_finite() {
                return Err(Error::value("vd_in", v, "a finite number"));
            }
            self.vd_held = v;
            self.vd_input.ramp(self.input_scheme, self.t, v, h)
        } else {
            self.vd_input.lapse();
            Ramp {
                value: self.vd(),
                rate: 0.0,
            }
        };
        let start = self.t;
        let t_end = start + h;
        let at_start = self.work;
        // The step taken ahead that the call read to its end, which the next goes on from.
        let mut behind = None;
        let mut done = self.read_step_ahead(t_end, &mut behind);
        if self.t != start && !done {
            // The call goes on from the end of the step taken ahead.
            self.p.set_time(self.t);
        }
        let mut origin = self.t;
        let mut t = self.t;
        while !done && t < t_end {
            within_step_budget(self.solver.name(), &self.work, &at_start, t)?;
            // Sub-steps end on period boundaries only for the mean (dopri5 and radau5 restart
            // there, a step or two each).
            let boundary = if self.trim.mean {
                self.mean.next_boundary()
            } else {
                f64::INFINITY
            };
            // A boundary within round-off of t_end is t_end (the master's clock drifts).
            let next = if boundary < t_end - self.mean.slack(t_end) {
                boundary
            } else {
                t_end
            };
            let next = if next > t { next } else { t_end };
            if next == t_end && self.take_step_ahead((t, t_end, boundary), behind.take())? {
                done = self.read_step_ahead(t_end, &mut behind);
                if !done {
                    // The step ended short of the call (on a kink): on from its end.
                    (origin, t) = (self.t, self.t);
                    self.p.set_time(origin);
                }
                continue;
            }
            behind = None;
            self.substep(origin, (t, next), vd)
                .map_err(|e| e.counted_from(origin))?;
            t = next;
        }
        self.t = t_end;
        self.p.set_time(t_end);
        if self.ahead.is_some() {
            // Read inside a step taken ahead, whose end was checked when it was taken.
            return Ok(());
        }
        let (ff, _, s) = self.ff_ffx_s();
        self.check_motion(t_end, &self.y, (ff, s))
    }

    fn read_inside(&mut self, h: f64) -> bool {
        self.read_inside_step_ahead(h)
    }

    fn write_outputs(&self, values: &mut ValueSet) {
        let y = self.state();
        let (ff, ffx, ffy, s, beta) = self.forces_at(&y);
        // Direct feedthrough of the hd term: Fd at t follows vd_in set at t.
        let vd = self.vd_now(values);
        values.set(vr::FF, ff);
        values.set(vr::FFX, ffx);
        values.set(vr::FFY, ffy);
        values.set(vr::FD, self.p.drive_force(&y, vd));
        values.set(vr::FFX_MEAN, self.mean_now(&y).value(self.t, ffx));
        values.set(vr::X, y[X]);
        values.set(vr::Y, y[Y]);
        values.set(vr::S, s);
        values.set(vr::BETA, beta);
        values.set(vr::W_DISS, self.dissipated_with(&y, s));
    }

    fn time(&self) -> f64 {
        self.t
    }

    fn take_warning(&mut self) -> Option<String> {
        if let Some(notice) = self.notice.take() {
            return Some(notice);
        }
        if let Some(unstable) = self.vd_input.instability("vd_in", self.input_scheme) {
            return Some(unstable);
        }
        let (t, name) = match &mut self.solver {
            Solver::General(m) => (m.stiff_since(), m.name()),
            Solver::TwoPhase(_) | Solver::Exponential(_) => (None, ""),
        };
        Some(super::stiff_warning(t?, name, "radau5 or exponential"))
    }

    fn reading_period(&self) -> Option<(f64, f64)> {
        Some((
            1.0 / self.p.f,
            self.solver.rtol().unwrap_or(super::FIXED_STEP_ACCURACY),
        ))
    }

    fn next_internal_step(&self) -> Option<f64> {
        match &self.solver {
            Solver::General(m) => Some(m.step_hint()).filter(|&h| h > 0.0),
            Solver::TwoPhase(_) | Solver::Exponential(_) => None,
        }
    }

    fn save_into(&self, out: &mut Vec<f64>) {
        // vd_in's past values and pending rate are state too (FMI 2.0, 2.1.8): see DriveTrain's.
        out.clear();
        out.extend_from_slice(&[self.t, self.vd_held]);
        self.vd_input.save(out);
        out.extend_from_slice(&self.y);
        out.extend_from_slice(&self.mean.save());
        self.solver.save_into(out);
        if self.saves_ahead() {
            self.save_ahead(out);
        }
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), Error> {
        let base = 2 + input_scheme::SAVED + MAX_DIM + 3;
        let solver = base + self.solver.saved_len();
        // The step taken ahead, if any (a flag first).
        let ahead = match state.get(solver) {
            _ if !self.saves_ahead() => 0,
            Some(1.0) => 1 + self.ahead_saved(),
            _ => 1,
        };
        super::check_saved(
            "TransverseFriction (with this solver)",
            state,
            solver + ahead,
        )?;
        if self.saves_ahead() {
            self.restore_ahead(&state[solver..])?;
        }
        self.t = state[0];
        self.p.set_time(self.t);
        self.vd_held = state[1];
        let y = 2 + input_scheme::SAVED;
        self.vd_input.restore(&state[2..y])?;
        self.y.copy_from_slice(&state[y..y + MAX_DIM]);
        self.mean.restore(&state[y + MAX_DIM..base]);
        self.solver.restore(&state[base..solver]);
        Ok(())
    }

    fn set_input_derivative(&mut self, value_reference: u32, derivative: f64) -> Result<(), Error> {
        if value_reference != vr::VD_IN {
            return Err(super::not_an_input(value_reference));
        }
        // Kept when vd is prescribed too, and ignored there like vd_in itself.
        self.vd_input.set_derivative(derivative);
        Ok(())
    }

    fn drop_input_derivative(&mut self, value_reference: u32) {
        if value_reference == vr::VD_IN {
            self.vd_input.lapse();
        }
    }

    /// Every output's first derivative, from the continuous-time equations at the current
    /// state (with the two-phase solver too): x', y' and Fd' = kd (vd - x') + hd (vd' - x'')
    /// exactly; s', beta' and W_diss' exactly from the bristle rate z'; FFx_mean's as
    /// [`PeriodMean::rate`]; FF, FFx and FFy, which need the bristle's second derivative, as a
    /// centred difference along the solution (`Transverse::force_rates`).
    fn output_derivative(&self, value_reference: u32, values: &ValueSet) -> Result<f64, Error> {
        let vd = self.drive_velocity_now(values);
        let y = self.state();
        let mut dydt = [0.0; MAX_DIM];
        Equations::new(&self.p, vd, &[]).rhs(0.0, &y, &mut dydt);
        let c = self.p.contact(0.0, &y);
        let z = Vector2::new(y[ZX], y[ZY]);
        // s' = e . z'; beta' from z = s (cos beta, -sin beta): beta' = -(z x z') / s^2 (0 on
        // an undeflected bristle, whose direction is that of the slip).
        let s_rate = c.e.dot(&c.zdot);
        let beta_rate = if c.s > 0.0 {
            -(z.x * c.zdot.y - z.y * c.zdot.x) / (c.s * c.s)
        } else {
            0.0
        };
        Ok(match value_reference {
            vr::FD => self.p.kd * (vd.value - dydt[X]) + self.p.hd * (vd.rate - dydt[VX]),
            vr::X => dydt[X],
            vr::Y => dydt[Y],
            vr::S => s_rate,
            vr::BETA => beta_rate,
            vr::W_DISS => dydt[W] - self.p.law.kt * c.s * s_rate,
            vr::FF => self.force_rates(&y, &dydt)[0],
            vr::FFX => self.force_rates(&y, &dydt)[1],
            vr::FFY => self.force_rates(&y, &dydt)[2],
            vr::FFX_MEAN => {
                let ffx = self.ff_ffx_s().1;
                let rate = self.force_rates(&y, &dydt)[1];
                self.mean_now(&y).rate(self.t, ffx, rate)
            }
            _ => return Err(super::no_output_derivative(value_reference)),
        })
    }
}

impl Transverse {
    /// The drive velocity over the coming step as the outputs see it: vd_in's current value
    /// and the rate set for the step when it is the source.
    fn drive_velocity_now(&self, values: &ValueSet) -> Ramp {
        Ramp {
            value: self.vd_now(values),
            rate: if self.drive == Drive::Input {
                self.vd_input.pending_rate()
            } else {
                0.0
            },
        }
    }

    /// (FF, FFx, FFy)' as the centred difference of the forces at t +- eps along the
    /// equations' tangent y +- eps y': the terms of second order in eps cancel, so the error
    /// is of order (eps / T)^2 for the fastest time scale T met. eps is a millionth of the
    /// vibration's 1/(2 pi f) and at most 1 ns (the equations' time counts from now, so any
    /// eps is resolved): at 3 kHz, 53 ps, so (eps / T)^2 is 1e-12 in steady sliding and 3e-7 in
    /// the Stribeck band, which the paper's values cross in about 100 ns.
    fn force_rates(&self, y_now: &[f64; MAX_DIM], dydt: &[f64; MAX_DIM]) -> [f64; 3] {
        let eps = (1e-6 / (TAU * self.p.f)).min(1e-9);
        let forces_at = |tau: f64| {
            let mut y = [0.0; MAX_DIM];
            for ((y, y0), d) in y.iter_mut().zip(y_now).zip(dydt) {
                *y = y0 + tau * d;
            }
            let c = self.p.contact(tau, &y);
            [c.ff, c.ffx(), c.ffy()]
        };
        let (plus, minus) = (forces_at(eps), forces_at(-eps));
        [0, 1, 2].map(|k| (plus[k] - minus[k]) / (2.0 * eps))
    }

    /// vd as the outputs see it: vd_in's current value when it is the source (Fd's hd term
    /// follows an input set after the last step).
    fn vd_now(&self, values: &ValueSet) -> f64 {
        match self.drive {
            Drive::Input if values.real(vr::VD_IN).is_finite() => values.real(vr::VD_IN),
            _ => self.vd(),
        }
    }

    /// The start time the simulation was built at.
    pub fn start_time(&self) -> f64 {
        self.start_time
    }
}

#[cfg(test)]
mod input_tests;

#[cfg(test)]
mod tests;
