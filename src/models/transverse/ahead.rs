//! Steps taken past the communication point. Where the master's steps are much shorter than
//! the solver's (a microsecond against dopri5's few at the default tolerance), a call takes the
//! step the solver proposes whole, past its end, and reads the state at the point from the
//! step ([`StepAhead`]); the calls that follow inside the step read it too, instead of each
//! taking a step of its own, cut to the call. Only while the drive is prescribed: an input may
//! change at every call, and the step would no longer be the motion's. A call that ends inside
//! the step only moves the clock: the state there, and the force integral the period's mean
//! adds, are read from the step when something asks for them ([`Transverse::state`],
//! [`Transverse::mean_now`]), and the mean takes the step's whole integral at its end.

use super::{axial, Drive, Equations, Solver, Transverse, Q};
use crate::error::Error;
use crate::models::period_mean::PeriodMean;
use crate::models::ramp::Ramp;
use crate::solve::stepping::{CallEnd, StepAhead, Stepping};
use crate::solve::MAX_DIM;

/// A solver's step taken past the communication point, with where the integration goes on
/// from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Ahead {
    step: StepAhead,
    /// The absolute time the step's equations count from (its start).
    origin: f64,
    /// The absolute time of its end, and the state there.
    end: f64,
    y_end: [f64; MAX_DIM],
}

impl Transverse {
    /// Whether calls may read steps taken ahead: the solver takes them, and the drive is
    /// prescribed.
    pub(super) fn takes_steps_ahead(&self) -> bool {
        matches!(&self.solver, Solver::General(m) if m.takes_steps_ahead())
            && matches!(self.drive, Drive::Prescribed(_))
    }

    /// How many numbers a step taken ahead adds to a saved state, after a flag.
    pub(super) fn ahead_saved(&self) -> usize {
        2 + MAX_DIM
            + match &self.solver {
                Solver::General(m) => m.step_ahead_saved(MAX_DIM),
                _ => 0,
            }
    }

    /// The step taken ahead whose interpolant holds the state now: the one `self.t` lies in,
    /// short of its end.
    fn inside(&self) -> Option<&Ahead> {
        self.ahead.as_ref().filter(|a| self.t < a.end)
    }

    /// The state now: `self.y`, or inside a step taken ahead its interpolant's.
    pub(super) fn state(&self) -> [f64; MAX_DIM] {
        let mut y = self.y;
        if let Some(a) = self.inside() {
            a.step.at(self.t - a.origin, &mut y);
        }
        y
    }

    /// The period's mean now, `y` the state now: inside a step taken ahead, with the force
    /// integral from its start (the step ends on the period's boundary at the latest, so it
    /// closes none).
    pub(super) fn mean_now(&self, y: &[f64; MAX_DIM]) -> PeriodMean {
        let mut mean = self.mean.clone();
        if self.trim.mean && self.inside().is_some() {
            mean.add(y[Q], self.t);
        }
        mean
    }

    /// Answers a call ending at `t_end` from the step taken ahead, if there is one: inside it,
    /// by moving the clock (true); at or past its end, by going on from there (true if `t_end`
    /// is its end, to round-off; false if the call must go on from `self.t`), the step then
    /// left in `behind` for the next to go on from.
    pub(super) fn read_step_ahead(&mut self, t_end: f64, behind: &mut Option<Ahead>) -> bool {
        let Some(ahead) = &self.ahead else {
            return false;
        };
        let call = CallEnd::of(t_end, ahead.end, self.mean.slack(t_end));
        if call == CallEnd::Inside {
            self.t = t_end;
            return true;
        }
        self.y = ahead.y_end;
        if self.trim.mean {
            self.mean.add(ahead.y_end[Q], ahead.end);
        }
        self.t = if call == CallEnd::AtEnd {
            t_end
        } else {
            ahead.end
        };
        *behind = self.ahead.take();
        call == CallEnd::AtEnd
    }

    /// Answers a call of `h` that ends inside the step taken ahead, short of its end (true): it
    /// moves the clock and cannot fail. False, with nothing changed, otherwise
    /// ([`crate::models::Simulation::read_inside`]).
    pub(super) fn read_inside_step_ahead(&mut self, h: f64) -> bool {
        let t_end = self.t + h;
        match &self.ahead {
            Some(a)
                if h > 0.0
                    && CallEnd::of(t_end, a.end, self.mean.slack(t_end)) == CallEnd::Inside => {}
            _ => return false,
        }
        // As do_step does: an input's derivative applies to one step, and vd is prescribed.
        self.vd_input.lapse();
        self.t = t_end;
        self.p.set_time(t_end);
        true
    }

    /// Where steps may be taken ahead and the solver takes one from `t` that holds `t_end`
    /// (not past the period's `boundary`, when the mean is read), holds it for
    /// [`Transverse::read_step_ahead`] (true); it goes on from `behind`, the last step taken
    /// ahead, where that ended at `t`. False, with nothing changed but the work, where it may
    /// not.
    pub(super) fn take_step_ahead(
        &mut self,
        (t, t_end, boundary): (f64, f64, f64),
        behind: Option<Ahead>,
    ) -> Result<bool, Error> {
        let Drive::Prescribed(vd) = self.drive else {
            return Ok(false);
        };
        let points = self.band_points;
        let Solver::General(method) = &mut self.solver else {
            return Ok(false);
        };
        let reach = (boundary - t).min(1.0 / self.p.f);
        // Going on from the last step taken ahead, where it ended.
        let behind = behind.filter(|b| b.end == t);
        let from = behind.as_ref().map(|b| &b.step);
        // The equations count time from the step's start.
        let mut p = self.p;
        p.set_time(t);
        let vd = Ramp {
            value: vd,
            rate: 0.0,
        };
        let q = self.y[Q];
        self.y[Q] = 0.0;
        let span = (0.0, t_end - t, reach);
        let taken = if self.trim.axial {
            let axial = axial::Axial {
                p: &p,
                vd,
                dim: self.trim.dim(),
                band_points: points,
            };
            method.step_ahead(&axial, span, &mut self.y, &mut self.work, from, |_| true)?
        } else {
            let planar = Equations::new(&p, vd, points);
            method.step_ahead(&planar, span, &mut self.y, &mut self.work, from, |_| true)?
        };
        let Some((end, step)) = taken else {
            self.y[Q] = q;
            return Ok(false);
        };
        // A step that reached the period's boundary ends on it, to the bit.
        let end_time = if end == boundary - t {
            boundary
        } else {
            t + end
        };
        // The calls that read inside the step are checked here, at its end.
        let contact = p.contact(end, &self.y);
        self.check_motion(end_time, &self.y, (contact.ff, contact.s))?;
        self.ahead = Some(Ahead {
            step,
            origin: t,
            end: end_time,
            y_end: self.y,
        });
        Ok(true)
    }

    /// Whether a saved state holds a step taken ahead (a flag, and the step if there is one):
    /// with a solver that can take them.
    pub(super) fn saves_ahead(&self) -> bool {
        matches!(&self.solver, Solver::General(m) if m.step_ahead_saved(MAX_DIM) > 0)
    }

    /// Appends the step taken ahead to a saved state: a flag, then
    /// [`Transverse::ahead_saved`] numbers.
    pub(super) fn save_ahead(&self, out: &mut Vec<f64>) {
        match &self.ahead {
            None => out.push(0.0),
            Some(a) => {
                out.extend_from_slice(&[1.0, a.origin, a.end]);
                out.extend_from_slice(&a.y_end);
                a.step.write(MAX_DIM, out);
            }
        }
    }

    /// The step taken ahead from what [`Transverse::save_ahead`] wrote.
    pub(super) fn restore_ahead(&mut self, saved: &[f64]) -> Result<(), Error> {
        let refused = || {
            Error::state(
                "a TransverseFriction state whose step taken ahead is not one",
                "a step taken ahead this simulation's solver takes, or none",
            )
        };
        let Solver::General(method) = &self.solver else {
            return Err(refused());
        };
        self.ahead = match saved {
            [flag] if *flag == 0.0 => None,
            [flag, origin, end, rest @ ..]
                if *flag == 1.0
                    && rest.len() == self.ahead_saved() - 2
                    && self.takes_steps_ahead() =>
            {
                let (y, step) = rest.split_at(MAX_DIM);
                let mut y_end = [0.0; MAX_DIM];
                y_end.copy_from_slice(y);
                Some(Ahead {
                    step: method
                        .restore_step_ahead(MAX_DIM, step)
                        .ok_or_else(refused)?,
                    origin: *origin,
                    end: *end,
                    y_end,
                })
            }
            _ => return Err(refused()),
        };
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::table::{vr, DRIVE_SOURCE, SLIP_LAW, TABLE};
    use super::super::Transverse;
    use crate::models::Simulation;
    use crate::variables::values::ValueSet;

    fn values(slip: &str, tolerance: f64) -> ValueSet {
        let mut v = ValueSet::start(&TABLE);
        v.set(vr::SLIP_LAW, f64::from(SLIP_LAW.value_of(slip).unwrap()));
        v.set(vr::TOLERANCE, tolerance);
        v
    }

    /// Oracle: a run at rtol 1e-13 calling every 10 us. Calls of 1 us, shorter than dopri5's
    /// steps at rtol 1e-8, read steps taken ahead: FFx and FFx_mean at every tenth point are
    /// as close to the reference as those of a run at the same tolerance calling every 10 us
    /// (within twice its largest difference, or within the tolerance of FC), from fewer
    /// right-hand sides than the seven a call takes stepping to its end.
    #[test]
    fn short_calls_read_steps_taken_ahead_within_the_tolerance() {
        for slip in ["split", "total"] {
            let (tight, v) = (values(slip, 1e-13), values(slip, 1e-8));
            let mut reference = Transverse::new(&tight, 0.0).unwrap();
            let mut stepped = Transverse::new(&v, 0.0).unwrap();
            let mut sim = Transverse::new(&v, 0.0).unwrap();
            let (mut worst, mut worst_stepped) = ([0.0f64; 3], [0.0f64; 3]);
            let (mut calls, mut read_inside) = (0, 0);
            for _ in 0..200 {
                reference.do_step(1e-5, &tight).unwrap();
                stepped.do_step(1e-5, &v).unwrap();
                for _ in 0..10 {
                    sim.do_step(1e-6, &v).unwrap();
                    calls += 1;
                    read_inside += usize::from(sim.ahead.is_some());
                }
                // The body's velocity, x', from the state the outputs' derivatives read, in
                // units of the drive's.
                let rate = |s: &Transverse, v: &ValueSet| s.output_derivative(vr::X, v).unwrap();
                let off = |s: &Transverse| {
                    let fc = s.fc;
                    [
                        (s.forces().1 - reference.forces().1).abs() / fc,
                        (s.mean_ffx() - reference.mean_ffx()).abs() / fc,
                        (rate(s, &v) - rate(&reference, &tight)).abs() / s.vd(),
                    ]
                };
                for (w, o) in worst.iter_mut().zip(off(&sim)) {
                    *w = w.max(o);
                }
                for (w, o) in worst_stepped.iter_mut().zip(off(&stepped)) {
                    *w = w.max(o);
                }
            }
            for (w, s) in worst.iter().zip(&worst_stepped) {
                assert!(
                    *w <= (2.0 * s).max(1e-8),
                    "{slip}: {worst:?} {worst_stepped:?}"
                );
            }
            assert!(read_inside * 2 > calls, "{slip}: {read_inside} of {calls}");
            assert!(
                sim.work.rhs_evaluations < 5 * calls as u64,
                "{slip}: {:?} for {calls} calls",
                sim.work
            );
        }
    }

    /// A state saved while a step taken ahead is being read holds that step and what the next
    /// goes on with: restored, the run goes on to the same bits as the one that saved it. A
    /// state that says it holds one where this simulation takes none is refused.
    #[test]
    fn a_state_saved_inside_a_step_taken_ahead_replays_the_motion() {
        let v = values("split", 1e-8);
        let mut sim = Transverse::new(&v, 0.0).unwrap();
        while sim.ahead.is_none() || sim.time() < 1e-4 {
            sim.do_step(1e-6, &v).unwrap();
        }
        let saved = sim.save();
        let run_on = |s: &mut Transverse| {
            for _ in 0..1000 {
                s.do_step(1e-6, &v).unwrap();
            }
            s.save()
        };
        let after = run_on(&mut sim);
        let mut other = Transverse::new(&v, 0.0).unwrap();
        other.restore(&saved).unwrap();
        assert_eq!(run_on(&mut other), after);

        let mut rk4 = v.clone();
        rk4.set(vr::SOLVER, 2.0);
        let mut other = Transverse::new(&rk4, 0.0).unwrap();
        assert!(other.restore(&saved).is_err());
    }

    /// fmi2DoStep asks `read_inside` first and saves no rollback for a call it answers: those
    /// calls go exactly as do_step's, and `read_inside` answers only calls inside a step taken
    /// ahead, short of its end.
    #[test]
    fn reading_inside_goes_as_the_step_does() {
        let v = values("split", 1e-8);
        let mut stepped = Transverse::new(&v, 0.0).unwrap();
        let mut sim = Transverse::new(&v, 0.0).unwrap();
        let mut answered = 0;
        for i in 0..3000 {
            stepped.do_step(1e-6, &v).unwrap();
            let end = sim.ahead.as_ref().map(|a| a.end);
            if sim.read_inside(1e-6) {
                answered += 1;
                assert!(sim.time() < end.unwrap(), "call {i}");
            } else {
                sim.do_step(1e-6, &v).unwrap();
            }
            assert_eq!(sim.save(), stepped.save(), "call {i}");
            assert_eq!(sim.forces(), stepped.forces(), "call {i}");
            let rate = |s: &Transverse| s.output_derivative(vr::FFX, &v).unwrap();
            assert_eq!(rate(&sim), rate(&stepped), "call {i}");
        }
        assert!(answered > 1500, "{answered} of 3000");
        let mut no_ahead = Transverse::new(&v, 0.0).unwrap();
        assert!(!no_ahead.read_inside(1e-6));
    }

    /// With the drive velocity an input, which may change at every call, no step is taken
    /// ahead.
    #[test]
    fn an_input_drive_takes_no_step_ahead() {
        let mut v = values("split", 1e-8);
        v.set(
            vr::DRIVE_SOURCE,
            f64::from(DRIVE_SOURCE.value_of("input").unwrap()),
        );
        v.set(vr::VD_IN, 5e-4);
        let mut sim = Transverse::new(&v, 0.0).unwrap();
        for _ in 0..200 {
            sim.do_step(1e-6, &v).unwrap();
            assert!(sim.ahead.is_none());
        }
    }
}
