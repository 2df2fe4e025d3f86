//! Scene O: a forced oscillator with dry friction, `m u'' + c u' + H(u') + k u = F(t)` (paper O,
//! eq. 1), `F = P sin(w t)` or an input held over each communication step.
//!
//! Two cores share the parameters and the outputs:
//! - the regularised laws (eq. 4-9) are a smooth-but-stiff ODE in `(u, u')` (slope h/D near
//!   u' = 0), integrated by the L-stable Radau IIA method in sub-steps of at most one
//!   `steps_per_period`-th of the forcing period;
//! - the exact laws ([`exact`]) are the non-smooth switch model, solved in closed form phase by
//!   phase with every stick/slip event located inside the communication step.
//!
//! `u_amplitude` is max |u| over the last complete forcing period `2 pi/w`, counted from the
//! start time. The exact core meets every extreme of u as an event; the regularised core finds
//! an extreme inside a sub-step by re-integrating to where u' = 0 (`turning_point`), or, with
//! `piecewise` (the linear motion outside H's band in closed form, `linear_phase`), reads it
//! off the dense output of dopri5's step (smooth inside the band, whose edges end steps).
//!
//! With the force prescribed and radau5, a communication step of at most a quarter of the step
//! the solver proposes takes that step past the communication point and reads the state there
//! from the step's polynomial; the calls that follow inside the step read it too (`Ahead`).

mod ahead;
mod equations;
pub mod exact;
mod linear_phase;
mod solver;
#[cfg(feature = "tools")]
pub mod stability;
mod start;
pub mod switches;
pub mod table;

pub use equations::{Equations, Forced};

use super::{Scope, Simulation};
use crate::error::{Error, Failure};
use crate::friction::regularized::Regularized;
use crate::friction::sgn;
use crate::models::oscillator::table::{vr, TABLE};
use crate::solve::dopri::Dopri5;
use crate::solve::stepping::{CallEnd, Stepping, AHEAD_HINTS};
use crate::solve::{within_step_budget, Ode, Work};
use crate::variables::values::ValueSet;
use ahead::Ahead;
use exact::{Event, Mode, State, Switch};
use linear_phase::LinearPhase;
use solver::Solver;

/// One per instance, built once: the sizes of the variants do not matter, and the regularised
/// core, which every right-hand side evaluation reads, stays unboxed.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
enum Core {
    Exact(Box<Switch>),
    Regularized(Equations, Solver),
}

/// max |u| over the last complete period; periods counted from the start with an integer index,
/// as [`super::period_mean::PeriodMean`] does.
#[derive(Clone, Debug, PartialEq)]
struct PeriodMax {
    start_time: f64,
    period: f64,
    completed: u64,
    running: f64,
    last: f64,
}

impl PeriodMax {
    fn next_boundary(&self) -> f64 {
        self.start_time + (self.completed + 1) as f64 * self.period
    }

    fn slack(&self, t: f64) -> f64 {
        super::period_mean::slack(self.period, t)
    }

    /// Adds the largest |u| of a sub-interval ending at t_end (where |u| = `at_end`).
    fn add(&mut self, largest: f64, t_end: f64, at_end: f64) {
        self.running = self.running.max(largest);
        if t_end >= self.next_boundary() - self.slack(t_end) {
            self.last = self.running;
            self.running = at_end;
            self.completed += 1;
        }
    }

    fn value(&self) -> f64 {
        if self.completed > 0 {
            self.last
        } else {
            self.running
        }
    }
}

/// What the steps taken ahead take in a saved state besides the step itself (of at most
/// [`DIM`] states): what the solver carries towards them, a flag, the end and the largest |u|.
const AHEAD_SAVED: usize = AHEAD_HINTS + 1 + 4 + 1;

/// The most states the regularised core integrates: u, u' and the friction work.
const DIM: usize = 3;

/// The numbers of a saved state without the step ahead.
const STATE_SAVED: usize = 10;

#[derive(Clone, Debug, PartialEq)]
pub struct Oscillator {
    core: Core,
    /// Steps may be taken past the communication point ([`Ahead`]): the solver takes them, and
    /// the force is prescribed.
    takes_steps_ahead: bool,
    ahead: Option<Ahead>,
    state: State,
    /// The input force held over the current step.
    held: f64,
    /// Longest sub-step of the regularised core.
    max_substep: f64,
    amplitude: PeriodMax,
    /// u_amplitude is read: extremes of u located inside sub-steps, sub-steps cut at the
    /// forcing period's boundaries.
    pub tracks_amplitude: bool,
    /// rtol: the accuracy the amplitude is asked to (see [`super::clock_warning`]).
    reading_tolerance: f64,
    /// For the first [`Simulation::take_warning`]: a law whose band is too narrow for any solver
    /// here, or why the periodic start fell back to the transient.
    unresolved: Option<String>,
    pub work: Work,
}

/// The narrowest band (D or Da, m/s) where linear_stiction's amplitude still meets rtol in the
/// paper's case (3.5e-7 of it off at 1e-9, whatever rtol; see the documentation page).
const NARROWEST_LINEAR_STICTION: f64 = 1e-8;

pub fn build(
    values: &ValueSet,
    start_time: f64,
    scope: &Scope,
) -> Result<Box<dyn Simulation>, Error> {
    Ok(Box::new(Oscillator::with_scope(values, start_time, scope)?))
}

impl Oscillator {
    /// The solver's name, as the switch spells it (in its errors).
    fn solver_name(&self) -> &'static str {
        match &self.core {
            Core::Exact(_) => "exact",
            Core::Regularized(_, solver) => solver.name(),
        }
    }

    pub fn state(&self) -> State {
        self.state
    }

    /// `(H, C, u'')` now, with the input force `held`.
    pub fn friction(&self, held: f64) -> (f64, f64, f64) {
        match &self.core {
            Core::Exact(switch) => {
                let (h, a) = switch.friction_and_acceleration(&self.state, held);
                (h, 0.0, a)
            }
            Core::Regularized(equations, _) => {
                let equations = Equations { held, ..*equations };
                equations.evaluate(self.state.t, self.state.u, self.state.v)
            }
        }
    }

    pub fn amplitude(&self) -> f64 {
        self.amplitude.value()
    }

    /// Advances to t_end (not past the next period boundary); returns the largest |u| met.
    fn advance(
        &mut self,
        t_end: f64,
        log: Option<&mut Vec<Event>>,
        at_start: &Work,
    ) -> Result<f64, Error> {
        let held = self.held;
        match &mut self.core {
            Core::Exact(switch) => switch.advance(
                &mut self.state,
                t_end,
                held,
                log,
                (&mut self.work, at_start),
            ),
            Core::Regularized(equations, solver) => {
                equations.held = held;
                let tracks = self.tracks_amplitude;
                let mut largest = self.state.u.abs();
                while self.state.t < t_end {
                    within_step_budget(solver.name(), &self.work, at_start, self.state.t)?;
                    let t0 = self.state.t;
                    // Far from t = 0 a sub-step can be lost to round-off (t0 + max == t0):
                    // then the solver takes the rest at once rather than the loop stalling.
                    let t1 = if t_end - t0 <= self.max_substep * (1.0 + 1e-9)
                        || t0 + self.max_substep <= t0
                    {
                        t_end
                    } else {
                        t0 + self.max_substep
                    };
                    if let Some(bound) = solver.stability_bound() {
                        equations.require_stable(solver.name(), t1 - t0, bound)?;
                    }
                    let piecewise = matches!(solver, Solver::Piecewise(_));
                    if let Solver::Piecewise(dopri5) = solver {
                        close_to_edge(equations, dopri5, &mut self.state, t_end, &mut self.work);
                    }
                    if piecewise && linear_phase(equations, &mut self.state, t_end, &mut self.work)
                    {
                        largest = largest.max(self.state.u.abs());
                        continue;
                    }
                    let start = [self.state.u, self.state.v, self.state.dissipated];
                    // piecewise reads extremes off dopri5's dense output: no search.
                    let probe = (tracks && !piecewise).then(|| solver.clone());
                    let mut y = start;
                    let t1 = match solver {
                        // Inside the band, up to where u' leaves it.
                        Solver::Piecewise(dopri5) => dopri5.integrate_to_kink(
                            &*equations,
                            (t0, t1),
                            &mut y,
                            &mut self.work,
                            &mut largest,
                        )?,
                        _ => {
                            solver.integrate(equations, (t0, t1), &mut y, &mut self.work)?;
                            t1
                        }
                    };
                    if let Some(probe) = probe.filter(|_| start[1] * y[1] < 0.0) {
                        let extreme =
                            turning_point(equations, probe, (t0, start), (t1, y), &mut self.work)?;
                        largest = largest.max(extreme.abs());
                    }
                    self.state.t = t1;
                    self.state.u = y[0];
                    self.state.v = y[1];
                    self.state.dissipated = y[2];
                    largest = largest.max(y[0].abs());
                }
                Ok(largest)
            }
        }
    }

    /// Like [`Simulation::do_step`], recording every stick/slip event of the exact core in `log`.
    pub fn step_logged(
        &mut self,
        h: f64,
        held: f64,
        mut log: Option<&mut Vec<Event>>,
    ) -> Result<(), Error> {
        super::require_step(h)?;
        self.held = held;
        let t_end = self.state.t + h;
        let at_start = self.work;
        let done = self.read_step_ahead(t_end);
        while !done && self.state.t < t_end {
            within_step_budget(self.solver_name(), &self.work, &at_start, self.state.t)?;
            let boundary = if self.tracks_amplitude {
                self.amplitude.next_boundary()
            } else {
                f64::INFINITY
            };
            // A boundary within round-off of t_end closes its period at t_end (PeriodMax::add).
            // A boundary at or before t (lost to round-off far from the start time) must not
            // stall the loop.
            let segment_end =
                if boundary < t_end - self.amplitude.slack(t_end) && boundary > self.state.t {
                    boundary
                } else {
                    t_end
                };
            if segment_end == t_end && self.take_step_ahead(t_end, boundary)? {
                break;
            }
            let largest = self.advance(segment_end, log.as_deref_mut(), &at_start)?;
            self.state.t = segment_end;
            self.amplitude.add(largest, segment_end, self.state.u.abs());
        }
        self.state.t = t_end;
        let (friction, _, a) = self.friction(self.held);
        if [
            self.state.u,
            self.state.v,
            friction,
            a,
            self.amplitude.value(),
        ]
        .iter()
        .all(|x| x.is_finite())
        {
            Ok(())
        } else {
            Err(Error::step(
                self.solver_name(),
                Failure::NotFinite,
                format!(
                    "the motion became non-finite at t = {t_end} (u = {}, u' = {})",
                    self.state.u, self.state.v
                ),
                "a finite motion: a tighter tolerance, more steps_per_period or the radau5 solver",
            ))
        }
    }
}

/// Where dopri5 stopped short of the band's edge, u' leaving the band (its steps end on a kink
/// to within a thousandth of a step, and a step retaken to a kink located on a trial's dense
/// output can land a little shorter), closes the gap with one Heun step to where u' reaches
/// the edge (true), if Euler's error over it, which bounds Heun's, is within the tolerance.
/// False otherwise: then dopri5 goes on, a step of the gap's length and a restart dearer.
fn close_to_edge(
    equations: &Equations,
    dopri5: &Dopri5,
    state: &mut State,
    t_end: f64,
    work: &mut Work,
) -> bool {
    let (edge, _) = equations.band();
    // The gap must not reach back past a kink inside the band (with stiction, Da below).
    let room = match equations.law {
        Regularized::LinearStiction { da, .. } | Regularized::TrigonometricStiction { da, .. } => {
            da
        }
        _ => edge,
    };
    let s = sgn(state.v);
    let gap = edge - s * state.v;
    if !(gap > 0.0 && gap < 0.05 * edge && gap < room) {
        return false;
    }
    let n = equations.dim();
    let y = [state.u, state.v, state.dissipated];
    let mut k1 = [0.0; 3];
    equations.rhs(state.t, &y[..n], &mut k1[..n]);
    work.rhs_evaluations += 1;
    let rate = s * k1[1];
    let dt = gap / rate;
    if !(rate > 0.0 && state.t + dt < t_end) {
        return false;
    }
    let mut euler = y;
    for j in 0..n {
        euler[j] = y[j] + dt * k1[j];
    }
    let mut k2 = [0.0; 3];
    equations.rhs(state.t + dt, &euler[..n], &mut k2[..n]);
    work.rhs_evaluations += 1;
    let within = (0..2)
        .all(|j| 0.5 * dt * (k2[j] - k1[j]).abs() <= dopri5.atol[j] + dopri5.rtol * y[j].abs());
    if !within {
        return false;
    }
    work.steps += 1;
    state.t += dt;
    state.u += 0.5 * dt * (k1[0] + k2[0]);
    state.v += 0.5 * dt * (k1[1] + k2[1]);
    if n > 2 {
        state.dissipated += 0.5 * dt * (k1[2] + k2[2]);
    }
    true
}

/// Where the state is outside H's band (or within a millionth of its edge, leaving it: there
/// H differs from h sgn(u') by a millionth at most, for a time that vanishes with it), takes the
/// linear motion in closed form ([`LinearPhase`]) to where u' comes back to the edge, or to
/// `t_end` (true). False, with nothing changed, inside the band or where the closed form does
/// not apply.
fn linear_phase(equations: &Equations, state: &mut State, t_end: f64, work: &mut Work) -> bool {
    let (edge, h) = equations.band();
    let s = sgn(state.v);
    let beyond = s * state.v - edge;
    let phase = LinearPhase::new(
        &equations.plant,
        (equations.held, s * h),
        (state.t, state.u, state.v),
    );
    let Some(phase) = phase.filter(|p| {
        s != 0.0
            && (beyond > 0.0
                || (beyond > -1e-6 * edge && s * p.acceleration(state.t, state.u, state.v) > 0.0))
    }) else {
        return false;
    };
    let mut evaluations = 0;
    let entry = phase.entry(s, edge, t_end, &mut evaluations);
    work.rhs_evaluations += evaluations;
    let t1 = entry.unwrap_or(t_end);
    if t1 <= state.t {
        return false;
    }
    work.steps += 1;
    let (u, v) = phase.at(t1);
    // On the edge, where the band's switching functions start from 0.
    let v = if entry.is_some() { s * edge } else { v };
    if equations.with_work {
        state.dissipated += h * s * (u - state.u);
    }
    (state.t, state.u, state.v) = (t1, u, v);
    true
}

/// u where u' changes sign inside the sub-step from `a` to `b`: u' is located by re-integrating
/// (Illinois false position, each probe starting from the latest point before the sign change).
/// An interpolant would not do: u'' jumps by 2h/m right there when D is small. u is flat at its
/// extreme, so an error dv in u' there moves u by only about dv^2/(2|u''|).
fn turning_point(
    equations: &Equations,
    solver: Solver,
    (t0, y0): (f64, [f64; 3]),
    (t1, y1): (f64, [f64; 3]),
    work: &mut Work,
) -> Result<f64, Error> {
    let atol = solver.atol();
    let (mut lo, mut y_lo, mut solver_lo) = (t0, y0, solver);
    let (mut hi, mut v_hi) = (t1, y1[1]);
    let mut v_lo = y0[1];
    let mut best = if y0[1].abs() < y1[1].abs() {
        y0[0]
    } else {
        y1[0]
    };
    let mut side = 0;
    for _ in 0..40 {
        let t = (lo * v_hi - hi * v_lo) / (v_hi - v_lo);
        if !(t > lo && t < hi) {
            break;
        }
        let mut probe = solver_lo.clone();
        let mut y = y_lo;
        probe.integrate(equations, (lo, t), &mut y, work)?;
        best = y[0];
        let slope = (v_hi - v_lo) / (hi - lo);
        if y[1] * y[1] <= 0.2 * atol * slope.abs() || hi - lo <= 4.0 * f64::EPSILON * t.abs() {
            break;
        }
        if (y[1] > 0.0) == (y_lo[1] > 0.0) {
            (lo, y_lo, solver_lo) = (t, y, probe);
            v_lo = y[1];
            if side == -1 {
                v_hi *= 0.5;
            }
            side = -1;
        } else {
            hi = t;
            v_hi = y[1];
            if side == 1 {
                v_lo *= 0.5;
            }
            side = 1;
        }
    }
    Ok(best)
}

impl Simulation for Oscillator {
    fn do_step(&mut self, h: f64, values: &ValueSet) -> Result<(), Error> {
        let held = values.real(vr::P_IN);
        self.step_logged(h, held, None)
    }

    /// Answers a call of `h` that ends inside the step taken ahead, short of its end, as
    /// [`Oscillator::step_logged`] would (true): it reads the step's polynomial and cannot fail.
    /// Steps are taken ahead only under a prescribed force, so the input force is not read.
    fn read_inside(&mut self, h: f64) -> bool {
        let t_end = self.state.t + h;
        match self.ahead {
            Some(ahead)
                if h > 0.0
                    && CallEnd::of(t_end, ahead.end[0], self.amplitude.slack(t_end))
                        == CallEnd::Inside =>
            {
                self.read_step(&ahead.step, t_end);
                true
            }
            _ => false,
        }
    }

    fn write_outputs(&self, values: &mut ValueSet) {
        // Direct feedthrough: a and H at t follow the input force set at t.
        let held = values.real(vr::P_IN);
        let (friction, slope, a) = self.friction(held);
        values.set(vr::U, self.state.u);
        values.set(vr::V, self.state.v);
        values.set(vr::A, a);
        values.set(vr::H_OUT, friction);
        values.set(vr::C_OUT, slope);
        values.set(vr::U_AMPLITUDE, self.amplitude.value());
        values.set(vr::W_DISS, self.state.dissipated);
    }

    fn time(&self) -> f64 {
        self.state.t
    }

    fn take_warning(&mut self) -> Option<String> {
        if let Some(message) = self.unresolved.take() {
            return Some(message);
        }
        let Core::Regularized(_, solver) = &mut self.core else {
            return None;
        };
        let name = match solver {
            Solver::Piecewise(_) => "piecewise (its dopri5 inside the band)",
            Solver::General(m) => m.name(),
        };
        let t = solver.stiff_since()?;
        Some(super::stiff_warning(t, name, "radau5"))
    }

    fn reading_period(&self) -> Option<(f64, f64)> {
        self.tracks_amplitude
            .then_some((self.amplitude.period, self.reading_tolerance))
    }

    fn next_internal_step(&self) -> Option<f64> {
        match &self.core {
            Core::Regularized(_, solver) => Some(solver.step_hint()).filter(|&h| h > 0.0),
            Core::Exact(_) => None,
        }
    }

    fn save_into(&self, out: &mut Vec<f64>) {
        let step_hint = match &self.core {
            Core::Regularized(_, solver) => solver.step_hint(),
            Core::Exact(_) => 0.0,
        };
        out.clear();
        out.extend_from_slice(&[
            self.state.t,
            self.state.u,
            self.state.v,
            self.state.mode.code(),
            self.held,
            self.amplitude.completed as f64,
            self.amplitude.running,
            self.amplitude.last,
            step_hint,
            self.state.dissipated,
        ]);
        match &self.core {
            Core::Regularized(_, Solver::General(method)) => method.save_ahead_hints(out),
            _ => out.extend_from_slice(&[0.0; AHEAD_HINTS]),
        }
        match &self.ahead {
            Some(ahead) => {
                out.push(1.0);
                ahead.step.write(DIM, out);
                out.extend_from_slice(&ahead.end);
                out.push(ahead.largest);
            }
            None => out.resize(STATE_SAVED + self.ahead_saved(), 0.0),
        }
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), Error> {
        super::check_saved(
            TABLE.model_identifier,
            state,
            STATE_SAVED + self.ahead_saved(),
        )?;
        let (hints, ahead) = state[STATE_SAVED..].split_at(AHEAD_HINTS);
        let ahead = match ahead[0] {
            0.0 => None,
            _ => {
                let method = match &self.core {
                    Core::Regularized(_, Solver::General(method)) if self.takes_steps_ahead => {
                        Some(method)
                    }
                    _ => None,
                };
                let (step, rest) = ahead[1..].split_at(self.ahead_saved() - AHEAD_SAVED);
                let step = method.and_then(|m| m.restore_step_ahead(DIM, step));
                let Some(step) = step else {
                    return Err(Error::state(
                        format!(
                            "a {} state holding a step taken ahead that this simulation cannot take",
                            TABLE.model_identifier
                        ),
                        "a step taken ahead by this simulation's solver, or none",
                    ));
                };
                Some(Ahead {
                    step,
                    end: [rest[0], rest[1], rest[2], rest[3]],
                    largest: rest[4],
                })
            }
        };
        match Mode::from_code(state[3]) {
            Some(mode) => {
                self.state = State {
                    t: state[0],
                    u: state[1],
                    v: state[2],
                    mode,
                    dissipated: state[9],
                };
                self.held = state[4];
                self.amplitude.completed = state[5] as u64;
                self.amplitude.running = state[6];
                self.amplitude.last = state[7];
                if let Core::Regularized(_, solver) = &mut self.core {
                    solver.set_step_hint(state[8]);
                    if let Solver::General(method) = solver {
                        method.restore_ahead_hints(hints);
                    }
                }
                self.ahead = ahead;
                Ok(())
            }
            None => Err(Error::state(
                format!("a DryFrictionOscillator state with the mode {}", state[3]),
                "a mode of 0 or +-1",
            )),
        }
    }
}

/// Runs a simulation from rest for `periods` forcing periods in steps of 1/50 period and returns
/// `u_amplitude` at the end: the steady amplitude once the free response has died out.
pub fn steady_amplitude(values: &ValueSet, periods: u32) -> Result<f64, Error> {
    let mut sim = Oscillator::new(values, 0.0)?;
    let step = sim.amplitude.period / 50.0;
    for _ in 0..periods * 50 {
        sim.do_step(step, values)?;
    }
    Ok(sim.amplitude())
}

/// `(t, u, u', H, C)` sampled `per_period` times a period over the last `shown` of `periods`.
pub fn trajectory(
    values: &ValueSet,
    periods: u32,
    shown: u32,
    per_period: u32,
) -> Result<Vec<[f64; 5]>, Error> {
    let mut sim = Oscillator::new(values, 0.0)?;
    let step = sim.amplitude.period / f64::from(per_period);
    let mut samples = Vec::new();
    for i in 0..periods * per_period {
        sim.do_step(step, values)?;
        if i + 1 >= (periods - shown) * per_period {
            let (friction, slope, _) = sim.friction(values.real(vr::P_IN));
            let st = sim.state();
            samples.push([st.t, st.u, st.v, friction, slope]);
        }
    }
    Ok(samples)
}

#[cfg(test)]
mod tests;
