//! Scene L's sub-steps: where each ends (vr's sign changes, the period's boundary, the grid of
//! the fixed-step solvers), and each taken by the solver, in closed form, or held at a Dahl
//! bristle's saturation.

use super::closed_form::Sliding;
use super::solver::Solver;
use super::{displacement, slid_from, velocity_at, Law, Longitudinal, Pending, Velocity};
use crate::error::{Error, Failure};
use crate::friction::{coulomb, dahl::Dahl, sgn};
use crate::solve::method::Method;

impl Longitudinal {
    /// The end of the sub-step starting at `t`: the next grid point (1/n period, fixed-step
    /// solvers only), sign change of vr, or period boundary, whichever comes first, but not past
    /// `t_end`. Times are absolute; the phase counts from the simulation's time.
    pub(super) fn substep_end(&self, t: f64, t_end: f64) -> f64 {
        let mut next = if self.tracks_mean {
            t_end.min(self.mean.next_boundary())
        } else {
            t_end
        };
        let n = f64::from(self.steps_per_period);
        let phase = self.clock().phase(t - self.t);
        // The absolute time of a phase (in turns).
        let at = |phase: f64| self.t + (phase - self.phase0) / self.f;
        // Over a moving velocity or normal force the fixed-step solvers freeze them at each
        // sub-step's midpoint, so they take the grid; a held input they meet exactly.
        let moving = match self.velocity {
            Velocity::Prescribed { .. } => true,
            Velocity::Input => self.v_in.rate != 0.0 || self.load.is_some_and(|l| l.rate != 0.0),
        };
        // Coulomb is always integrated in closed form on the grid: its sign at each sub-step's
        // midpoint must be the sign over the sub-step, which a whole period would not give
        // where vr only touches zero (vc = va).
        if moving && (self.solver.fixed_step() || (self.law == Law::Coulomb && self.coulomb_grid)) {
            // The grid point after t; phase*n can round just below an integer we reached.
            let mut j = (phase * n).floor() + 1.0;
            if at(j / n) <= t {
                j += 1.0;
            }
            next = next.min(at(j / n));
        }
        if let Some(zero) = self
            .v_in
            .zero()
            .filter(|_| self.velocity == Velocity::Input)
        {
            let tc = self.t + zero;
            if tc > t {
                next = next.min(tc);
            }
        }
        if let Some(p) = self.reversal_phase {
            // vr = 0 at phase fractions p and 1 - p.
            let k = phase.floor();
            for crossing in [k + p, k + 1.0 - p, k + 1.0 + p, k + 2.0 - p] {
                let tc = at(crossing);
                if tc > t {
                    next = next.min(tc);
                }
            }
        }
        // Round-off must never stall the loop.
        if next <= t {
            let fallback = t + 1.0 / (self.f * f64::from(self.steps_per_period));
            if fallback > t {
                t_end.min(fallback)
            } else {
                t_end
            }
        } else {
            next
        }
    }

    /// Whether a closed_form sub-step may stay open across calls ([`Pending`]).
    pub(super) fn pending_allowed(&self) -> bool {
        matches!(self.solver, Solver::ClosedForm(_))
            && matches!(self.law, Law::Dahl(_))
            && self.tracks_mean
            && self.mean.has_completed()
            && matches!(self.velocity, Velocity::Prescribed { .. })
    }

    /// A velocity with the sign of vr over a sub-step whose midpoint velocity is `v_mid`: when
    /// |vc| >= va vr keeps the sign of vc (it only touches 0, maybe at a whole period's
    /// midpoint), otherwise the sub-steps end on its sign changes.
    fn sliding_direction(&self, v_mid: f64) -> f64 {
        match self.velocity {
            Velocity::Prescribed { vc, va } if vc.abs() >= va => vc,
            _ => v_mid,
        }
    }

    /// Where in the sub-step `[t0, t1]` a Dahl bristle with alpha < 1 saturates, if it does:
    /// the time, and the deflection it then keeps until vr changes sign (which ends the
    /// sub-step). An adaptive solver stops where the bristle is within its tolerance of
    /// saturation, `rtol FC/kt` in z, where the rate's slope is still bounded.
    fn saturation(&self, law: &Dahl, t0: f64, t1: f64) -> Option<(f64, f64)> {
        let s = sgn(self.sliding_direction(self.velocity_at(0.5 * (t0 + t1))));
        let slack = self.solver.ode_tolerance().unwrap_or(0.0);
        let distance = law.distance_to_saturation(self.z, s, slack);
        if !distance.is_finite() || s == 0.0 {
            return None;
        }
        // Within the slack already: saturated from the start, where no solver can step (the
        // rate's slope is unbounded there; dopri5 spent its whole budget on 5e-324 s).
        if distance <= 0.0 {
            return Some((t0, law.saturated(s)));
        }
        // vr keeps the sign s over the sub-step, so the distance slid grows with t.
        let slid = |t: f64| s * displacement(self.velocity, self.clock(), self.v_in, t0, t);
        if slid(t1) <= distance {
            return None;
        }
        let (mut before, mut after) = (t0, t1);
        loop {
            let mid = 0.5 * (before + after);
            if mid <= before || mid >= after {
                break;
            }
            if slid(mid) < distance {
                before = mid;
            } else {
                after = mid;
            }
        }
        Some((after, law.saturated(s)))
    }

    /// The general solvers over a sub-step; returns the integrals of the force and its power.
    fn advance_ode(&mut self, t0: f64, t1: f64) -> Result<(f64, f64), Error> {
        let saturation = match self.law {
            // Only below alpha 1 is saturation reached in finite time.
            Law::Dahl(law) if law.alpha < 1.0 => self
                .saturation(&law, t0, t1)
                .map(|(t, z)| (t, z, law.force(z))),
            _ => None,
        };
        let t_ode = saturation.map_or(t1, |(t_sat, _, _)| t_sat);
        let (source, clock, input) = (self.velocity, self.clock(), self.v_in);
        let velocity = move |t: f64| velocity_at(source, clock, input, t);
        let (law, weight) = (self.law, self.weight);
        let loaded = self
            .load
            .map(|load| move |t: f64| law.loaded(load.at(t) / weight));
        // Sub-step ends that met in the round-off of the absolute time (a kink a few ulps after
        // a period's boundary, say): one explicit step, as the adaptive solvers took there when
        // they counted absolute time (counted from the step's start, they would take the
        // interval for a real one and refine it).
        let mut round_off = Solver::General(Method::across_round_off());
        let solver = if crate::models::within_round_off(self.t + t0, self.t + t_ode) {
            &mut round_off
        } else {
            &mut self.solver
        };
        let (mut integral, mut power_integral) = solver.advance(
            (&self.law, self.ode_dim),
            (&velocity, loaded.as_ref().map(|l| l as &dyn Fn(f64) -> Law)),
            t0,
            t_ode,
            &mut self.z,
            &mut self.work,
        )?;
        if let Some((t_sat, z_sat, force)) = saturation {
            // Saturated, the bristle holds: the rest is closed form, and no solver has to
            // resolve the corner where the rate's slope is unbounded.
            self.z = z_sat;
            if self.ode_dim > 1 {
                integral += force * (t1 - t_sat);
            }
            if self.ode_dim > 2 {
                power_integral += force * displacement(source, clock, input, t_sat, t1);
            }
        }
        Ok((integral, power_integral))
    }

    /// closed_form over `[start, end]` (absolute times within the step under way), from the
    /// start of the pending sub-step if there is one; `defer`: `end` is no cut of the sub-step,
    /// and the force integral waits for the cut ([`Pending`]).
    fn closed_form_substep(
        &mut self,
        law: &Dahl,
        (start, end): (f64, f64),
        defer: bool,
    ) -> Result<(), Error> {
        let from = self.pending.unwrap_or(Pending {
            t: start,
            z: self.z,
            friction_work: self.friction_work,
        });
        // The equations' time counts from the step's start (before it, for a pending start).
        let (t0, t1) = (from.t - self.t, end - self.t);
        let s = sgn(self.sliding_direction(self.velocity_at(0.5 * (t0 + t1))));
        let slid = slid_from(self.velocity, self.clock(), self.v_in, t0);
        let Solver::ClosedForm(solver) = &mut self.solver else {
            return Err(Error::step(
                "closed_form",
                Failure::Misuse,
                "a closed-form sub-step with another solver",
                "solver closed_form",
            ));
        };
        let done = solver.advance(
            law,
            Sliding { s, slid },
            (from.z, t1 - t0),
            self.tracks_mean && !defer,
            &mut self.work,
        )?;
        self.z = done.z;
        self.friction_work = from.friction_work + done.power_integral;
        if defer {
            self.pending = Some(from);
        } else {
            self.pending = None;
            self.mean.add(done.force_integral, end);
        }
        Ok(())
    }

    /// Advances over `[start, end]` (absolute times within the step under way); `open`: `end`
    /// ends the call but is no cut of the sub-step (only closed_form reads it).
    pub(super) fn substep(&mut self, start: f64, end: f64, open: bool) -> Result<(), Error> {
        // The equations' time counts from the simulation's time, the step's start.
        let (t0, t1) = (start - self.t, end - self.t);
        if let (Some(mean), Some(load)) = (self.fc_mean.as_mut(), self.load) {
            if self.tracks_mean {
                mean.add(self.fc / self.weight * load.integral(t0, t1), end);
            }
        }
        if let (Solver::ClosedForm(_), Law::Dahl(law)) = (&self.solver, self.law) {
            return self.closed_form_substep(&law, (start, end), open);
        }
        if !matches!(self.solver, Solver::Exponential) && self.law != Law::Coulomb {
            let (integral, power_integral) = self.advance_ode(t0, t1)?;
            self.friction_work += power_integral;
            self.mean.add(integral, end);
            return Ok(());
        }
        let h = t1 - t0;
        let mid = 0.5 * (t0 + t1);
        let v = self.velocity_at(mid);
        self.work.steps += 1;
        self.work.rhs_evaluations += 1;
        // A normal force that moves linearly: its midpoint value times h is its integral.
        let fc = self.fc * self.load_scale(mid);
        let integral = match self.law_at(mid) {
            Law::Coulomb if !self.coulomb_grid => coulomb::force(fc, self.sliding_direction(v)) * h,
            Law::Coulomb => coulomb::force(fc, v) * h,
            Law::Dahl(law) => {
                let (z1, z_integral) = law.advance(self.z, v, h);
                self.z = z1;
                law.kt * z_integral
            }
            Law::LuGre(law) => {
                let (z1, force_integral) = law.advance(self.z, v, h);
                self.z = z1;
                force_integral
            }
        };
        self.friction_work += match self.law {
            // Coulomb's force keeps its sign (sub-steps end where vr changes it) and, under a
            // held normal force, its level: its work is that force times the distance slid,
            // exactly, where the frozen velocity would leave it second order in the grid.
            Law::Coulomb if self.load.is_none_or(|load| load.rate == 0.0) => {
                integral / h * displacement(self.velocity, self.clock(), self.v_in, t0, t1)
            }
            // The velocity is frozen over the sub-step, so this is the exact work of the
            // scheme's force: with the exact bristle update the scheme is as passive as the
            // contact.
            _ => v * integral,
        };
        self.mean.add(integral, end);
        Ok(())
    }
}
