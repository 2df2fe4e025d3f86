//! How a scene O run starts: the parameters read and checked, the state at the start time, and
//! the periodic start.

use super::equations::{Equations, Forced};
use super::exact::{Mode, State, Switch};
use super::solver::Solver;
use super::switches::{ForceSource, OscillatorInitialState, OscillatorLaw, OscillatorSolver};
use super::table::vr;
use super::{Core, Oscillator, PeriodMax, NARROWEST_LINEAR_STICTION};
use crate::error::Error;
use crate::friction::regularized::{stiction_excess, Regularized};
use crate::models::switch::Switch as _;
use crate::models::{
    require_finite, require_non_negative, require_positive, require_steps, Scope, Simulation,
};
use crate::solve::shooting::{self, NoOrbit};
use crate::solve::stepping::Stepping;
use crate::solve::Work;
use crate::variables::values::ValueSet;
use std::f64::consts::TAU;

impl Oscillator {
    /// The full model.
    pub fn new(values: &ValueSet, start_time: f64) -> Result<Self, Error> {
        Oscillator::with_scope(values, start_time, &Scope::full())
    }

    /// The simulation for an interface that hides what `scope` lists.
    pub fn with_scope(values: &ValueSet, start_time: f64, scope: &Scope) -> Result<Self, Error> {
        let mut sim = Oscillator::starting_from(values, start_time, scope)?;
        if OscillatorInitialState::read(values, vr::INITIAL)? == OscillatorInitialState::Periodic {
            if ForceSource::read(values, vr::FORCE_SOURCE)? == ForceSource::Input {
                return Err(Error::combination(
                    "initial = periodic with an input force: the motion has no period known at initialization",
                    "the force prescribed (force_source = prescribed)",
                ));
            }
            if let Err(no_orbit) = sim.settle_on_orbit(values, scope) {
                let notice = format!(
                    "initial = periodic: {}; the run starts from (u0, v0) instead and goes through the transient",
                    no_orbit.why
                );
                sim.unresolved = Some(match sim.unresolved.take() {
                    Some(before) => format!("{before}; {notice}"),
                    None => notice,
                });
            }
        }
        Ok(sim)
    }

    /// Replaces (u0, v0) by the periodic orbit's state at the start time, found by shooting on
    /// the one-period map ([`crate::solve::shooting`]) with this simulation's law and solver, from
    /// a period after (u0, v0). The periods it integrates count in [`Oscillator::work`].
    fn settle_on_orbit(&mut self, values: &ValueSet, scope: &Scope) -> Result<(), NoOrbit> {
        // Without a spring u enters no force: the map's Jacobian has a zero column (to the
        // differences' noise, so Newton's method would step anywhere along it).
        if values.real(vr::K) == 0.0 {
            return Err("with k = 0 no spring holds the body, so every orbit shifted in u is an orbit too (a Floquet multiplier of 1) and the one the motion settles on depends on where it starts".into());
        }
        let period = self.amplitude.period;
        let start_time = self.state.t;
        let rtol = values.real(vr::RTOL);
        let at = |y: &[f64], tolerance: f64| {
            let mut v = values.clone();
            v.set(vr::U0, y[0]);
            v.set(vr::V0, y[1]);
            v.set(vr::RTOL, tolerance.max(rtol));
            v
        };
        let mut work = Work::default();
        let swing = std::cell::Cell::new(0.0_f64);
        let mut map = |y: &[f64], tolerance: f64| {
            let values = at(y, tolerance);
            let mut sim = Oscillator::starting_from(&values, start_time, scope)?;
            let result = sim.do_step(period, &values);
            work = work.plus(&sim.work);
            result?;
            swing.set(
                swing
                    .get()
                    .max(sim.amplitude.running.max(sim.amplitude.last)),
            );
            Ok(vec![sim.state.u, sim.state.v])
        };
        let orbit = map(&[self.state.u, self.state.v], 1e-6)
            .map_err(NoOrbit::from)
            .and_then(|guess| {
                // The states' scale: the swing of that first period (the atol where it is
                // still).
                let u_scale = swing.get().max(values.real(vr::ATOL));
                let w = values.real(vr::W);
                let scale = [u_scale, u_scale * w];
                shooting::periodic_orbit(&guess, (&scale, &[false, false]), rtol, &mut map)
            });
        self.work = self.work.plus(&work);
        let orbit = orbit?;
        let values = at(&orbit.state, rtol);
        *self = Oscillator {
            work: self.work,
            unresolved: self.unresolved.take(),
            ..Oscillator::starting_from(&values, start_time, scope)?
        };
        Ok(())
    }

    /// The simulation at `start_time` from (u0, v0).
    fn starting_from(values: &ValueSet, start_time: f64, scope: &Scope) -> Result<Self, Error> {
        let m = require_positive(values, vr::M)?;
        let c = require_non_negative(values, vr::C)?;
        let k = require_non_negative(values, vr::K)?;
        let p = require_non_negative(values, vr::P)?;
        let w = require_positive(values, vr::W)?;
        let h = require_non_negative(values, vr::H)?;
        let d = require_positive(values, vr::D)?;
        let da = require_non_negative(values, vr::DA)?;
        let u0 = require_finite(values, vr::U0)?;
        let v0 = require_finite(values, vr::V0)?;
        let rtol = require_positive(values, vr::RTOL)?;
        let atol = require_positive(values, vr::ATOL)?;
        let steps = f64::from(require_steps(values, vr::STEPS_PER_PERIOD)?);
        let ha = stiction_excess(h, d, da);
        if !ha.is_finite() {
            return Err(Error::combination(
                format!("ha = h*Da/D = {ha} (h = {h}, D = {d}, Da = {da})"),
                "a finite ha: Da/D of moderate size",
            ));
        }
        let plant = Forced {
            m,
            c,
            k,
            w,
            p,
            input: ForceSource::read(values, vr::FORCE_SOURCE)? == ForceSource::Input,
        };
        let held = require_finite(values, vr::P_IN)?;
        let period = TAU / w;
        let law = OscillatorLaw::read(values, vr::LAW)?;
        let regularized = match law {
            OscillatorLaw::Exact | OscillatorLaw::ExactStiction => None,
            OscillatorLaw::Linear => Some(Regularized::Linear { h, d }),
            OscillatorLaw::LinearStiction => Some(Regularized::LinearStiction { h, d, da }),
            OscillatorLaw::Trigonometric => Some(Regularized::Trigonometric { h, d }),
            OscillatorLaw::TrigonometricStiction => {
                Some(Regularized::TrigonometricStiction { h, d, da })
            }
        };
        let core = match regularized {
            None => {
                let hs = if law == OscillatorLaw::Exact {
                    h
                } else {
                    h + ha
                };
                Core::Exact(Box::new(Switch::new(plant, (h, hs), steps)?))
            }
            Some(law) => {
                let name = OscillatorSolver::read(values, vr::SOLVER)?;
                let equations = Equations {
                    plant,
                    held,
                    law,
                    with_work: scope.exposes(vr::W_DISS),
                };
                Core::Regularized(equations, Solver::new(name, rtol, atol, period / steps))
            }
        };
        let mode = match &core {
            Core::Exact(switch) => switch.initial_mode(start_time, u0, v0, held),
            Core::Regularized(..) => Mode::Sliding(1.0),
        };
        let takes_steps_ahead = matches!(
            &core,
            Core::Regularized(equations, Solver::General(method))
                if method.takes_steps_ahead() && !equations.plant.input
        );
        Ok(Oscillator {
            core,
            takes_steps_ahead,
            ahead: None,
            state: State {
                t: start_time,
                u: u0,
                v: v0,
                mode,
                dissipated: 0.0,
            },
            held,
            max_substep: period / steps,
            amplitude: PeriodMax {
                start_time,
                period,
                completed: 0,
                running: u0.abs(),
                last: u0.abs(),
            },
            tracks_amplitude: scope.exposes(vr::U_AMPLITUDE),
            reading_tolerance: rtol,
            unresolved: (law == OscillatorLaw::LinearStiction && d.min(da) < NARROWEST_LINEAR_STICTION).then(|| {
                format!(
                    "linear_stiction with D = {d:e} and Da = {da:e} m/s: its falling branch (slope -h/D) amplifies the solver's error across the band, and below {NARROWEST_LINEAR_STICTION:e} m/s the amplitude and W_diss are not accurate to the tolerance whatever rtol; trigonometric_stiction or exact_stiction resolve so narrow a band"
                )
            }),
            work: Work::default(),
        })
    }
}
