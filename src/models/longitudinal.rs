//! Scene L: a rigid body sliding on a base at `vr(t) = vc + va cos(wt)` (Leus & Gutowski 2008,
//! eq. 2.1-2.4), or at a velocity given as an input; the friction force and its mean over the
//! last vibration period.
//!
//! One state (the bristle deflection z; none for Coulomb). Sub-steps end where vr changes sign
//! (|vr| has a kink there, and Coulomb friction jumps) and at period boundaries. The default
//! `exponential` solver also cuts them at 1/n of a period and freezes the velocity at each
//! sub-step's midpoint: a second-order scheme whose bristle update is exact and stable at any
//! stiffness. The general solvers (`ode`) integrate z with the force integral and the work as
//! further states, which a trimmed model drops when their outputs are hidden
//! ([`Longitudinal::ode_dim`]). A Dahl bristle with alpha < 1 saturates after a finite sliding
//! distance, where its rate is not Lipschitz: they stop there and hold it, in closed form
//! (`Longitudinal::saturation`).
//!
//! As a part of a drive system the velocity and the normal force can be inputs, each held over a
//! communication step or moving linearly at the derivative the master sets for it
//! ([`Ramp`]). The normal force scales the law's force levels: FC = mu FN, and LuGre's FS with
//! FN / (m g).

mod closed_form;
mod equations;
mod solver;
#[cfg(feature = "tools")]
pub mod stability;
mod start;
mod substeps;
pub mod switches;
pub mod table;

use super::input_scheme::{self, Extrapolator, InputScheme};
use super::period_mean::PeriodMean;
use super::ramp::Ramp;
use super::{require_passive, resolved_energy, Scope, Simulation};
use crate::error::{Error, Failure};
use crate::friction::{coulomb, dahl::Dahl, lugre::LuGre};
use crate::models::longitudinal::table::vr;
use crate::solve::phase::{cos_turns, turns};
use crate::solve::stepping::Stepping;
use crate::solve::{within_step_budget, Work};
use crate::variables::values::ValueSet;
use solver::Solver;
use std::f64::consts::TAU;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Law {
    Coulomb,
    Dahl(Dahl),
    LuGre(LuGre),
}

impl Law {
    /// The law under a normal force `scale` times the weight's: its force levels scale with it.
    fn loaded(self, scale: f64) -> Law {
        match self {
            Law::Coulomb => Law::Coulomb,
            Law::Dahl(d) => Law::Dahl(Dahl {
                fc: d.fc * scale,
                ..d
            }),
            Law::LuGre(l) => Law::LuGre(LuGre {
                fc: l.fc * scale,
                fs: l.fs * scale,
                ..l
            }),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Velocity {
    /// vr = vc + va cos(2 pi f t)
    Prescribed { vc: f64, va: f64 },
    /// vr = vr_in over each step ([`Ramp`])
    Input,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Longitudinal {
    pub law: Law,
    pub velocity: Velocity,
    /// Coulomb force mu*m*g, the reference of S.
    pub fc: f64,
    pub f: f64,
    pub steps_per_period: u32,
    pub solver: Solver,
    t: f64,
    /// The vibration's phase, in turns, at `t`. Within a step the equations run on the time
    /// since the step's start, so that neither the phase nor the solvers' steps lose digits to
    /// a large t.
    phase0: f64,
    z: f64,
    /// The input velocity over the current step.
    v_in: Ramp,
    /// How vr_in and FN_in move over a step: their past values and the master's derivatives.
    inputs: [Extrapolator; 2],
    input_scheme: InputScheme,
    /// The weight m g, the normal force's reference.
    weight: f64,
    /// The normal force over the current step when it is an input (None: the weight).
    load: Option<Ramp>,
    /// The mean Coulomb force mu FN over the last period, the reference of S, when the normal
    /// force is an input.
    fc_mean: Option<PeriodMean>,
    mean: PeriodMean,
    /// The work of the friction force on the sliding since the start, the integral of FT vr.
    friction_work: f64,
    pub work: Work,
    /// Coulomb's closed form runs on the 1/n grid, for the midpoint rule of its work W_diss under
    /// a moving normal force (under a held one the work is exact on any grid; the force integral
    /// needs only the sign changes of vr): false when W_diss is hidden.
    pub coulomb_grid: bool,
    /// States the general solvers integrate: z, then the force integral q while FT_mean or S is
    /// read, then the work w while W_diss is read or the solver takes fixed steps (w feeds the
    /// passivity check that stops an unstable fixed step; an adaptive one rejects such steps).
    pub ode_dim: usize,
    /// FT_mean or S is read: sub-steps end on period boundaries.
    pub tracks_mean: bool,
    /// Where the prescribed vr turns to 0 within a period, the phase p in turns at which
    /// cos(2 pi p) = -vc/va (and 1 - p); None where vr keeps its sign. Fixed with vc and va, so
    /// taken once rather than on every call.
    reversal_phase: Option<f64>,
    /// Why the periodic start fell back to the transient, for the first
    /// [`Simulation::take_warning`].
    notice: Option<String>,
    /// closed_form's sub-step under way across calls ([`Pending`]).
    pending: Option<Pending>,
}

/// Where closed_form's sub-step under way began, when it spans several calls: with the velocity
/// prescribed and a period complete (FT_mean is then the last period's, not the running mean),
/// calls that end between a sub-step's cuts (vr's sign changes, the period's boundary) take z
/// and the work in closed form from its start, and the force integral waits for the cut.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pending {
    /// Absolute time.
    t: f64,
    z: f64,
    friction_work: f64,
}

/// The vibration as the equations see it: frequency `f` and phase `phase0` (turns) at their
/// time 0.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Clock {
    f: f64,
    phase0: f64,
}

impl Clock {
    fn phase(self, t: f64) -> f64 {
        self.phase0 + t * self.f
    }
}

/// vr(t) for a velocity source, clock and input.
fn velocity_at(source: Velocity, clock: Clock, input: Ramp, t: f64) -> f64 {
    match source {
        // cos_turns: libm's cos and the reduction were a third of the right-hand side.
        Velocity::Prescribed { vc, va } => vc + va * cos_turns(clock.phase(t)),
        Velocity::Input => input.at(t),
    }
}

/// The sliding displacement, the integral of vr from `t0` to `t`.
fn displacement(source: Velocity, clock: Clock, input: Ramp, t0: f64, t: f64) -> f64 {
    slid_from(source, clock, input, t0)(t - t0)
}

/// The distance slid from `t0` to `t0 + tau`, as a function of tau (the prescribed velocity's sine
/// in turns, as the velocity's cosine).
fn slid_from(source: Velocity, clock: Clock, input: Ramp, t0: f64) -> impl Fn(f64) -> f64 {
    let sin = move |t: f64| cos_turns(clock.phase(t) - 0.25);
    let sin0 = sin(t0);
    move |tau: f64| match source {
        Velocity::Prescribed { vc, va } => vc * tau + va / (TAU * clock.f) * (sin(t0 + tau) - sin0),
        Velocity::Input => input.integral(t0, t0 + tau),
    }
}

pub fn build(
    values: &ValueSet,
    start_time: f64,
    scope: &Scope,
) -> Result<Box<dyn Simulation>, Error> {
    Ok(Box::new(Longitudinal::with_scope(
        values, start_time, scope,
    )?))
}

impl Longitudinal {
    /// The equations' clock: their time 0 is the simulation's time.
    fn clock(&self) -> Clock {
        Clock {
            f: self.f,
            phase0: self.phase0,
        }
    }

    /// The sliding velocity `t` after the simulation's time.
    pub fn velocity_at(&self, t: f64) -> f64 {
        velocity_at(self.velocity, self.clock(), self.v_in, t)
    }

    /// The normal force over the weight `t` after the simulation's time.
    fn load_scale(&self, t: f64) -> f64 {
        self.load.map_or(1.0, |load| load.at(t) / self.weight)
    }

    /// The law under the normal force `t` after the simulation's time.
    fn law_at(&self, t: f64) -> Law {
        match self.load {
            Some(_) => self.law.loaded(self.load_scale(t)),
            None => self.law,
        }
    }

    pub fn friction_force(&self) -> f64 {
        self.friction_force_at(0.0, self.z)
    }

    /// FT `t` after the simulation's time with the deflection `z`.
    fn friction_force_at(&self, t: f64, z: f64) -> f64 {
        let v = self.velocity_at(t);
        match self.law_at(t) {
            Law::Coulomb => coulomb::force(self.fc * self.load_scale(t), v),
            Law::Dahl(law) => law.force(z),
            Law::LuGre(law) => law.force(z, v),
        }
    }

    /// The bristle's rate z' `t` after the simulation's time with the deflection `z`.
    fn bristle_rate_at(&self, t: f64, z: f64) -> f64 {
        let v = self.velocity_at(t);
        match self.law_at(t) {
            Law::Coulomb => 0.0,
            Law::Dahl(law) => law.rate(z, v),
            Law::LuGre(law) => law.rate(z, v),
        }
    }

    pub fn z(&self) -> f64 {
        self.z
    }

    pub fn mean_force(&self) -> f64 {
        self.mean.value(self.t, self.friction_force())
    }

    /// The Coulomb force S is taken against: FC, or with the normal force an input, its mean
    /// over the same period as FT_mean.
    fn reference_force(&self) -> f64 {
        let fc_now = self.fc * self.load_scale(0.0);
        self.fc_mean
            .as_ref()
            .map_or(self.fc, |mean| mean.value(self.t, fc_now))
    }

    /// The energy the contact has dissipated since the start: the friction work minus the
    /// energy stored in the deflection (Coulomb stores none).
    pub fn dissipated_energy(&self) -> f64 {
        self.friction_work - self.stored_energy()
    }

    /// The contact's stiffness (Coulomb's is infinite: it stores nothing).
    fn stiffness(&self) -> f64 {
        match self.law {
            Law::Coulomb => f64::INFINITY,
            Law::Dahl(law) => law.kt,
            Law::LuGre(law) => law.sigma0,
        }
    }

    fn stored_energy(&self) -> f64 {
        match self.law {
            Law::Coulomb => 0.0,
            Law::Dahl(law) => 0.5 * law.kt * self.z * self.z,
            Law::LuGre(law) => 0.5 * law.sigma0 * self.z * self.z,
        }
    }
}

impl Simulation for Longitudinal {
    fn do_step(&mut self, h: f64, values: &ValueSet) -> Result<(), Error> {
        self.read_inputs(values);
        let [velocity, load] = &mut self.inputs;
        if self.velocity == Velocity::Input {
            self.v_in = velocity.ramp(self.input_scheme, self.t, self.v_in.value, h);
        } else {
            velocity.lapse();
        }
        match self.load.as_mut() {
            // Where the scheme's line would leave FN_in > 0 the step holds it instead.
            Some(force) => {
                *force = load.ramp_where(self.input_scheme, self.t, force.value, h, |r| {
                    r.value > 0.0 && r.at(h) > 0.0
                })
            }
            None => load.lapse(),
        }
        if self.velocity == Velocity::Input {
            self.v_in = Ramp::checked("vr_in", self.v_in.value, self.v_in.rate)?;
        }
        if let Some(load) = self.load {
            let load = Ramp::checked("FN_in", load.value, load.rate)?;
            if !(load.value > 0.0 && load.at(h) > 0.0) {
                return Err(Error::value_found(
                    "FN_in",
                    format!(
                        "the normal force FN_in moves from {} N to {} N over the step from t = {}",
                        load.value,
                        load.at(h),
                        self.t
                    ),
                    "FN_in > 0 throughout (set a smaller derivative or a shorter step)",
                ));
            }
        }
        let t_end = self.t + h;
        let mut t = self.t;
        let at_start = self.work;
        while t < t_end {
            // The sub-step's next cut, and where this one ends: the same as the cut up to t_end.
            let cut = self.substep_end(t, f64::INFINITY);
            let next = cut.min(t_end);
            // The call ends inside a sub-step: its next cut lies beyond (past round-off).
            let open =
                next == t_end && self.pending_allowed() && cut > t_end + self.mean.slack(t_end);
            self.substep(t, next, open)
                .map_err(|e| e.counted_from(self.t))?;
            within_step_budget(self.solver.name(), &self.work, &at_start, next)?;
            t = next;
        }
        self.t = t_end;
        self.phase0 = turns(t_end, self.f);
        // A derivative applies to the step it was set for (fmi2DoStep restores it with the rest
        // of the state when the step fails).
        self.v_in.rate = 0.0;
        if let Some(load) = self.load.as_mut() {
            load.rate = 0.0;
        }
        if !self.z.is_finite() {
            return Err(Error::step(
                self.solver.name(),
                Failure::NotFinite,
                format!("the bristle deflection became {} at t = {t_end}", self.z),
                "a finite deflection: a tighter tolerance or more steps_per_period",
            ));
        }
        let integrates_work = self.ode_dim == 3
            || self.law == Law::Coulomb
            || matches!(self.solver, Solver::Exponential | Solver::ClosedForm(_));
        match self.law {
            // LuGre's bristle damping sigma1 can return energy (the law is passive only for
            // small sigma1), so only the other laws are held to it.
            Law::LuGre(law) if law.sigma1 > 0.0 => Ok(()),
            // Without the work (W_diss hidden, adaptive solver) there is nothing to check.
            _ if !integrates_work => Ok(()),
            _ => require_passive(
                self.solver.name(),
                (self.dissipated_energy(), self.stored_energy()),
                1e-6,
                self.solver
                    .ode_tolerance()
                    .map_or(0.0, |rtol| resolved_energy(rtol, self.fc, self.stiffness())),
                (t_end, match self.solver {
                    Solver::Exponential | Solver::ClosedForm(_) => {
                        "the scheme is passive at any step, so this is its round-off: use a tolerance or steps_per_period that resolves the bristle"
                    }
                    _ => "use more steps_per_period, or the exponential solver (stable at any step)",
                }),
            ),
        }
    }

    fn write_outputs(&self, values: &mut ValueSet) {
        // Direct feedthrough: the outputs at t follow the inputs set at t.
        let mut now = self.clone();
        now.read_inputs(values);
        let ft_mean = now.mean_force();
        values.set(vr::FT, now.friction_force());
        values.set(vr::Z, now.z);
        values.set(vr::VR, now.velocity_at(0.0));
        values.set(vr::FT_MEAN, ft_mean);
        values.set(vr::S, (1.0 - ft_mean / now.reference_force()) * 100.0);
        values.set(vr::W_DISS, now.dissipated_energy());
    }

    fn time(&self) -> f64 {
        self.t
    }

    fn take_warning(&mut self) -> Option<String> {
        if let Some(notice) = self.notice.take() {
            return Some(notice);
        }
        let [velocity, load] = &mut self.inputs;
        let unstable = velocity.instability("vr_in", self.input_scheme);
        if let Some(unstable) = unstable.or_else(|| load.instability("FN_in", self.input_scheme)) {
            return Some(unstable);
        }
        let solver = self.solver.general_mut()?;
        let t = solver.stiff_since()?;
        Some(super::stiff_warning(
            t,
            solver.name(),
            "radau5 or exponential",
        ))
    }

    fn reading_period(&self) -> Option<(f64, f64)> {
        Some((
            1.0 / self.f,
            self.solver
                .tolerance()
                .unwrap_or(super::FIXED_STEP_ACCURACY),
        ))
    }

    fn next_internal_step(&self) -> Option<f64> {
        Some(self.solver.step_hint()).filter(|&h| h > 0.0)
    }

    /// The inputs' values and the derivatives set for the coming step (FMI 2.0, 2.1.8: they
    /// are state), then, with the normal force an input, its value, rate and mean.
    fn save_into(&self, out: &mut Vec<f64>) {
        out.clear();
        out.extend_from_slice(&[self.t, self.z, self.v_in.value, self.v_in.rate]);
        out.extend_from_slice(&self.mean.save());
        out.extend_from_slice(&[self.solver.step_hint(), self.friction_work]);
        let pending = self
            .pending
            .map_or([0.0; 4], |p| [1.0, p.t, p.z, p.friction_work]);
        out.extend_from_slice(&pending);
        for input in &self.inputs {
            input.save(out);
        }
        if let (Some(load), Some(mean)) = (self.load, &self.fc_mean) {
            out.extend_from_slice(&[load.value, load.rate]);
            out.extend_from_slice(&mean.save());
        }
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), Error> {
        let base = 13 + 2 * input_scheme::SAVED;
        let expected = if self.load.is_some() { base + 5 } else { base };
        super::check_saved(
            "LongitudinalFriction (with this normal force source)",
            state,
            expected,
        )?;
        let mut inputs = self.inputs;
        for (input, saved) in inputs
            .iter_mut()
            .zip(state[13..base].chunks_exact(input_scheme::SAVED))
        {
            input.restore(saved)?;
        }
        self.inputs = inputs;
        self.t = state[0];
        self.phase0 = turns(self.t, self.f);
        self.z = state[1];
        self.v_in = Ramp {
            value: state[2],
            rate: state[3],
        };
        self.mean.restore(&state[4..7]);
        self.solver.set_step_hint(state[7]);
        self.friction_work = state[8];
        self.pending = match state[9] {
            0.0 => None,
            1.0 if matches!(self.solver, Solver::ClosedForm(_)) => Some(Pending {
                t: state[10],
                z: state[11],
                friction_work: state[12],
            }),
            flag => {
                return Err(Error::state(
                    format!("a LongitudinalFriction state's pending sub-step flag of {flag}"),
                    "0, or 1 with solver closed_form",
                ))
            }
        };
        if let (Some(load), Some(mean)) = (self.load.as_mut(), self.fc_mean.as_mut()) {
            *load = Ramp {
                value: state[base],
                rate: state[base + 1],
            };
            mean.restore(&state[base + 2..base + 5]);
        }
        Ok(())
    }

    fn set_input_derivative(&mut self, value_reference: u32, derivative: f64) -> Result<(), Error> {
        // Kept when the input is not read too, and ignored there like the input itself. The
        // ramps' rates are what the outputs' derivatives read until the step.
        match (value_reference, self.load.as_mut()) {
            (vr::VR_IN, _) => {
                self.v_in.rate = derivative;
                self.inputs[0].set_derivative(derivative);
            }
            (vr::FN_IN, Some(load)) => {
                load.rate = derivative;
                self.inputs[1].set_derivative(derivative);
            }
            (vr::FN_IN, None) => {}
            _ => return Err(super::not_an_input(value_reference)),
        }
        Ok(())
    }

    fn drop_input_derivative(&mut self, value_reference: u32) {
        match (value_reference, self.load.as_mut()) {
            (vr::VR_IN, _) => {
                self.v_in.rate = 0.0;
                self.inputs[0].lapse();
            }
            (vr::FN_IN, Some(load)) => {
                load.rate = 0.0;
                self.inputs[1].lapse();
            }
            _ => {}
        }
    }

    /// Every output's first derivative at the current state: vr', z' and W_diss' = FT vr -
    /// kt z z' exactly; FT' exactly for Coulomb (away from a sign change) and Dahl (kt z'), and
    /// for LuGre, whose damping term needs z'', as a centred difference along the solution;
    /// FT_mean's and S's as [`PeriodMean::rate`].
    fn output_derivative(&self, value_reference: u32, values: &ValueSet) -> Result<f64, Error> {
        let mut now = self.clone();
        now.read_inputs(values);
        let z_rate = now.bristle_rate_at(0.0, now.z);
        let ft = now.friction_force();
        let ft_rate = now.friction_force_rate(z_rate);
        Ok(match value_reference {
            vr::FT => ft_rate,
            vr::Z => z_rate,
            vr::VR => now.velocity_rate(),
            vr::W_DISS => ft * now.velocity_at(0.0) - now.stiffness_or_zero() * now.z * z_rate,
            vr::FT_MEAN => now.mean.rate(now.t, ft, ft_rate),
            vr::S => {
                let (mean, mean_rate) = (now.mean_force(), now.mean.rate(now.t, ft, ft_rate));
                let fc_now = now.fc * now.load_scale(0.0);
                let fc_rate = now.fc * now.load.map_or(0.0, |l| l.rate) / now.weight;
                let (reference, reference_rate) = match &now.fc_mean {
                    Some(m) => (now.reference_force(), m.rate(now.t, fc_now, fc_rate)),
                    None => (now.fc, 0.0),
                };
                -100.0 * (mean_rate * reference - mean * reference_rate) / (reference * reference)
            }
            _ => return Err(super::no_output_derivative(value_reference)),
        })
    }
}

impl Longitudinal {
    /// Takes the inputs' current values from `values` (their rates are set for the step).
    fn read_inputs(&mut self, values: &ValueSet) {
        if self.velocity == Velocity::Input {
            self.v_in.value = values.real(vr::VR_IN);
        }
        if let Some(load) = self.load.as_mut() {
            load.value = values.real(vr::FN_IN);
        }
    }

    /// vr' now.
    fn velocity_rate(&self) -> f64 {
        match self.velocity {
            Velocity::Prescribed { va, .. } => {
                -va * TAU * self.f * (TAU * self.clock().phase(0.0).fract()).sin()
            }
            Velocity::Input => self.v_in.rate,
        }
    }

    /// kt, or 0 for Coulomb (which stores nothing).
    fn stiffness_or_zero(&self) -> f64 {
        match self.law {
            Law::Coulomb => 0.0,
            _ => self.stiffness(),
        }
    }

    /// FT' now, given z'. LuGre's as the centred difference of FT at +-eps along the tangent
    /// z + tau z': its second-order terms cancel, so the error is of order (eps / T)^2 for the
    /// fastest time scale T met; eps is a millionth of 1/(2 pi f), at most 1 ns.
    fn friction_force_rate(&self, z_rate: f64) -> f64 {
        match self.law {
            Law::Coulomb => {
                let v = self.velocity_at(0.0);
                coulomb::force(self.fc * self.load.map_or(0.0, |l| l.rate) / self.weight, v)
            }
            Law::Dahl(law) => law.kt * z_rate,
            Law::LuGre(_) => {
                let eps = (1e-6 / (TAU * self.f)).min(1e-9);
                let at = |tau: f64| self.friction_force_at(tau, self.z + tau * z_rate);
                (at(eps) - at(-eps)) / (2.0 * eps)
            }
        }
    }
}

/// Runs the prescribed-velocity model for `periods` vibration periods and returns the mean force
/// over the last one: the quantity of the paper's Tables 1-3.
pub fn steady_mean_force(values: &ValueSet, periods: u32) -> Result<f64, Error> {
    let mut sim = Longitudinal::new(values, 0.0)?;
    let period = 1.0 / sim.f;
    for _ in 0..periods {
        sim.do_step(period, values)?;
    }
    Ok(sim.mean_force())
}

#[cfg(test)]
mod input_tests;

#[cfg(test)]
mod tests;
