//! How a scene L run starts: the parameters read and checked, the state at the start time, and
//! the periodic start.

use super::solver::Solver;
use super::switches::{
    LongitudinalInitialState, LongitudinalLaw, NormalForceSource, VelocitySource,
};
use super::table::vr;
use super::{Law, Longitudinal, Velocity};
use crate::error::Error;
use crate::friction::{dahl::Dahl, lugre::LuGre};
use crate::models::input_scheme::{Extrapolator, InputScheme};
use crate::models::period_mean::PeriodMean;
use crate::models::ramp::Ramp;
use crate::models::switch::Switch;
use crate::models::{require_positive, require_steps, Scope, Simulation};
use crate::solve::phase::turns;
use crate::solve::shooting::{self, NoOrbit};
use crate::solve::Work;
use crate::variables::values::ValueSet;
use std::f64::consts::TAU;

/// What a periodic start cannot promise for LuGre's first period with a fixed-step solver,
/// if anything: its FT_mean holds sigma1 f (z(T) - z(0)), 0 on the orbit, where z(T) is the
/// run's and z(0) the shooting's, each to the grid's error in z. Calls inside the period cut
/// the run's sub-steps elsewhere than the shooting's, and the difference reaches FT_mean
/// multiplied by sigma1 f/sigma0 (the adaptive solvers take the tolerance over that gain).
fn first_period_damping(law: &LuGre, f: f64) -> Option<String> {
    let gain = law.sigma1 * f / law.sigma0;
    (gain > 1.0).then(|| {
        format!(
            "initial = periodic: the first period's FT_mean holds sigma1 f (z(T) - z(0)), 0 on the orbit, which multiplies the fixed-step solver's error in z by sigma1 f/sigma0 = {gain:.3e} where calls inside the period cut the sub-steps elsewhere than the shooting did (more steps_per_period shrink it); from the second period on, where the calls repeat each period, it cancels"
        )
    })
}

impl Longitudinal {
    /// The full model.
    pub fn new(values: &ValueSet, start_time: f64) -> Result<Self, Error> {
        Longitudinal::with_scope(values, start_time, &Scope::full())
    }

    /// The simulation for an interface that hides what `scope` lists. (Coulomb has no bristle state
    /// in the full model already: z stays 0 and the force is integrated in closed form.)
    pub fn with_scope(values: &ValueSet, start_time: f64, scope: &Scope) -> Result<Self, Error> {
        let mut sim = Longitudinal::starting_from(values, start_time, scope)?;
        let initial = LongitudinalInitialState::read(values, vr::INITIAL)?;
        if initial == LongitudinalInitialState::Periodic {
            if sim.velocity == Velocity::Input || sim.load.is_some() {
                return Err(Error::combination(
                    "initial = periodic with an input (velocity or normal force): the motion has no period known at initialization",
                    "the velocity prescribed and the weight as the normal force (velocity_source = prescribed, normal_force_source = weight)",
                ));
            }
            if sim.law != Law::Coulomb {
                if let Err(no_orbit) = sim.settle_on_orbit(values, scope) {
                    sim.notice = Some(format!(
                        "initial = periodic: {}; the run starts from rest instead and goes through the transient",
                        no_orbit.why
                    ));
                } else if let (Law::LuGre(law), true) = (sim.law, sim.solver.fixed_step()) {
                    sim.notice = first_period_damping(&law, sim.f);
                }
            }
        }
        Ok(sim)
    }

    /// Replaces the undeflected bristle by the periodic orbit's deflection at the start time,
    /// found by shooting on the one-period map ([`crate::solve::shooting`]) with this simulation's
    /// solver, from a period after rest. (Coulomb has no state: its first period is steady.)
    /// The periods it integrates count in [`Longitudinal::work`].
    fn settle_on_orbit(&mut self, values: &ValueSet, scope: &Scope) -> Result<(), NoOrbit> {
        let period = 1.0 / self.f;
        let start_time = self.t;
        let rtol = values.real(vr::TOLERANCE);
        let at = |tolerance: f64| {
            let mut v = values.clone();
            v.set(vr::TOLERANCE, tolerance.max(rtol));
            v
        };
        let mut work = Work::default();
        let mut map = |z0: &[f64], tolerance: f64| {
            let values = at(tolerance);
            let mut sim = Longitudinal::starting_from(&values, start_time, scope)?;
            sim.z = z0[0];
            // Stored at the start, not dissipated (as below, at the orbit).
            sim.friction_work = sim.stored_energy();
            let result = sim.do_step(period, &values);
            work = work.plus(&sim.work);
            result?;
            Ok(vec![sim.z])
        };
        // LuGre's damping force sigma1 z' adds sigma1 f (z(T) - z(0)) to the first period's
        // FT_mean: the residual in z must close to FT_mean's tolerance through that factor too.
        let damping = match self.law {
            Law::LuGre(law) => self.fc / (law.sigma1 * self.f),
            _ => f64::INFINITY,
        };
        let scale = (self.fc / self.stiffness())
            .min(self.slip_per_period())
            .min(damping);
        let orbit = map(&[0.0], 1e-6).map_err(NoOrbit::from).and_then(|guess| {
            shooting::periodic_orbit(&guess, (&[scale], &[false]), rtol, &mut map)
        });
        self.work = self.work.plus(&work);
        self.z = orbit?.state[0];
        // W_diss (the work minus the energy stored) counts from 0 at the start: the orbit's
        // bristle holds its energy there, stored, not dissipated.
        self.friction_work = self.stored_energy();
        Ok(())
    }

    /// The farthest the contact can slide in a period (the prescribed velocity's).
    fn slip_per_period(&self) -> f64 {
        match self.velocity {
            Velocity::Prescribed { vc, va } => (vc.abs() + va) / self.f,
            Velocity::Input => f64::INFINITY,
        }
    }

    /// The simulation at `start_time` with the bristle undeflected.
    fn starting_from(values: &ValueSet, start_time: f64, scope: &Scope) -> Result<Self, Error> {
        let m = require_positive(values, vr::M)?;
        let mu = require_positive(values, vr::MU)?;
        let g = require_positive(values, vr::G)?;
        let f = require_positive(values, vr::F)?;
        let fc = mu * m * g;
        if !(fc.is_normal() && fc > 0.0) {
            return Err(Error::combination(
                format!("the Coulomb force FC = mu m g = {fc} N"),
                "a finite FC of at least 2.2e-308 N, the least normal number (check m, mu, g)",
            ));
        }
        let kt = require_positive(values, vr::KT)?;
        let law = match LongitudinalLaw::read(values, vr::LAW)? {
            LongitudinalLaw::Coulomb => Law::Coulomb,
            LongitudinalLaw::Dahl => Law::Dahl(Dahl {
                kt,
                fc,
                alpha: require_positive(values, vr::ALPHA)?,
            }),
            LongitudinalLaw::LuGre => Law::LuGre(LuGre {
                sigma0: kt,
                sigma1: values.real(vr::SIGMA1),
                sigma2: values.real(vr::SIGMA2),
                fc,
                fs: require_positive(values, vr::FS)?,
                vs: require_positive(values, vr::VS)?,
            }),
        };
        let velocity = match VelocitySource::read(values, vr::VELOCITY_SOURCE)? {
            VelocitySource::Input => Velocity::Input,
            VelocitySource::Prescribed => Velocity::Prescribed {
                vc: values.real(vr::VC),
                va: values.real(vr::VA),
            },
        };
        let load = match NormalForceSource::read(values, vr::NORMAL_FORCE_SOURCE)? {
            NormalForceSource::Input => Some(Ramp::default()),
            NormalForceSource::Weight => None,
        };
        let steps_per_period = require_steps(values, vr::STEPS_PER_PERIOD)?;
        // The farthest the contact can slide in a period, which bounds its deflection.
        let slip_per_period = match velocity {
            Velocity::Prescribed { vc, va } => (vc.abs() + va) / f,
            Velocity::Input => f64::INFINITY,
        };
        let solver = Solver::new(
            values,
            law,
            fc,
            (f, steps_per_period),
            slip_per_period,
            load.is_some(),
        )?;
        let fixed_step = solver.fixed_step();
        if let (Law::Dahl(d), Some(_)) = (law, load) {
            if d.alpha < 1.0 && !fixed_step {
                // Saturated under a constant FC the bristle holds, in closed form; under a moving
                // one it follows FC where the rate's slope is unbounded, which an adaptive solver
                // cannot step across.
                return Err(Error::combination(
                    format!(
                        "law dahl with alpha = {} and the normal force an input",
                        d.alpha
                    ),
                    "alpha >= 1, or solver exponential or rk4",
                ));
            }
        }
        if let (Solver::ClosedForm(_), Some(_), false) = (&solver, load, law == Law::Coulomb) {
            return Err(Error::combination(
                "solver closed_form with the normal force an input",
                "normal_force_source = weight (under a moving normal force the bristle has no closed form), or solver dopri5 or radau5",
            ));
        }
        let tracks_mean = scope.exposes(vr::FT_MEAN) || scope.exposes(vr::S);
        Ok(Longitudinal {
            law,
            velocity,
            fc,
            f,
            steps_per_period,
            solver,
            t: start_time,
            phase0: turns(start_time, f),
            z: 0.0,
            v_in: Ramp {
                value: values.real(vr::VR_IN),
                rate: 0.0,
            },
            inputs: [Extrapolator::default(); 2],
            input_scheme: InputScheme::read(values, vr::INPUT_SCHEME)?,
            weight: m * g,
            load: load.map(|_| Ramp {
                value: values.real(vr::FN_IN),
                rate: 0.0,
            }),
            fc_mean: load.map(|_| PeriodMean::new(start_time, 1.0 / f)),
            mean: PeriodMean::new(start_time, 1.0 / f),
            friction_work: 0.0,
            work: Work::default(),
            coulomb_grid: scope.exposes(vr::W_DISS),
            ode_dim: if scope.exposes(vr::W_DISS) || fixed_step {
                3
            } else if tracks_mean {
                2
            } else {
                1
            },
            tracks_mean,
            reversal_phase: match velocity {
                Velocity::Prescribed { vc, va } if vc.abs() < va => Some((-vc / va).acos() / TAU),
                _ => None,
            },
            notice: None,
            pending: None,
        })
    }
}
