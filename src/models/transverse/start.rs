//! How a scene T run starts: the parameters read and checked, the state at the start time, andn//! the periodic start.

use super::equations::{tolerance_scales, Clocked, Params};
use super::solver::{self, Solver};
use super::switches;
use super::switches::{DriveSource, InitialState, TransverseSolver};
use super::table::vr;
use super::{Drive, Transverse, Trim, COUPLED, COUPLED_AXIAL, LAMBDA, VX, W, ZX, ZY};
use crate::error::Error;
use crate::friction::lugre2d::{LuGre2d, SlipLaw};
use crate::models::input_scheme::{Extrapolator, InputScheme};
use crate::models::period_mean::PeriodMean;
use crate::models::switch::Switch;
use crate::models::{
    require_finite, require_finite_start, require_non_negative, require_positive, require_steps,
    require_tolerance, Scope, Simulation,
};
use crate::solve::shooting::{self, NoOrbit};
use crate::solve::{Work, MAX_DIM};
use crate::variables::values::ValueSet;

impl Transverse {
    /// The full model.
    pub fn new(values: &ValueSet, start_time: f64) -> Result<Self, Error> {
        Transverse::with_scope(values, start_time, &Scope::full())
    }

    /// The simulation for an interface that hides what `scope` lists.
    pub fn with_scope(values: &ValueSet, start_time: f64, scope: &Scope) -> Result<Self, Error> {
        let mut sim = Transverse::starting_from(values, start_time, scope, None)?;
        if InitialState::read(values, vr::INITIAL)? == InitialState::Periodic {
            if sim.drive == Drive::Input || sim.p.held {
                return Err(Error::combination(
                    "initial = periodic with the body held or an input drive: the motion has no period known at initialization",
                    "the body free and the drive prescribed (body = free, drive_source = prescribed)",
                ));
            }
            if let Err(no_orbit) = sim.settle_on_orbit(values, scope) {
                let start = if no_orbit.nearest.is_some() {
                    "the state nearest to closing the period"
                } else {
                    "steady sliding instead"
                };
                sim.notice = Some(format!(
                    "initial = periodic: {}; the run starts from {start} and goes through the transient",
                    no_orbit.why
                ));
            }
        }
        Ok(sim)
    }

    /// The states the right-hand side reads, which make the motion's state.
    fn coupled(&self) -> usize {
        if self.trim.axial {
            COUPLED_AXIAL
        } else {
            COUPLED
        }
    }

    /// Replaces the initial state by the periodic orbit's at the start time, found by shooting
    /// on the one-period map ([`crate::solve::shooting`]) with this simulation's solver, from
    /// steady sliding; where shooting stalls short of the tolerance, by the state nearest to
    /// closing the period. The periods it integrates count in [`Transverse::work`].
    fn settle_on_orbit(&mut self, values: &ValueSet, scope: &Scope) -> Result<(), NoOrbit> {
        let n = self.coupled();
        let period = 1.0 / self.p.f;
        let start_time = self.t;
        let mut work = Work::default();
        // The guess: a period from steady sliding, which settles the bristle, with the drive
        // stretched to pull the mean friction force of that period (the vibration lowers it
        // from FC), which the body's slow motion would take many periods to find.
        let rtol = values.real(vr::TOLERANCE);
        // The maps' values: the run's, with the tolerance the shooting asks of each map (the
        // fixed-step solvers take their own steps whatever it is).
        let at = |tolerance: f64| {
            let mut v = values.clone();
            v.set(vr::TOLERANCE, tolerance.max(rtol));
            v
        };
        let coarse = at(1e-6);
        let mut first = Transverse::starting_from(&coarse, start_time, scope, Some(&self.y[..n]))?;
        let settled = first.do_step(period, &coarse);
        work = work.plus(&first.work);
        settled?;
        let mut guess = first.y[..n].to_vec();
        if self.p.kd > 0.0 {
            guess[LAMBDA] = first.mean_ffx() / self.p.kd;
        }
        let mut map = |y0: &[f64], tolerance: f64| {
            let values = at(tolerance);
            let mut sim = Transverse::starting_from(&values, start_time, scope, Some(y0))?;
            let result = sim.do_step(period, &values);
            work = work.plus(&sim.work);
            result?;
            Ok(sim.y[..n].to_vec())
        };
        let scale = tolerance_scales(&self.p, self.vd());
        let settling: Vec<bool> = (0..n).map(|j| j == ZX || j == ZY).collect();
        let orbit = shooting::periodic_orbit(&guess, (&scale[..n], &settling), rtol, &mut map);
        self.work = self.work.plus(&work);
        let start = match &orbit {
            Ok(orbit) => orbit.state.clone(),
            Err(NoOrbit {
                nearest: Some(nearest),
                ..
            }) => nearest.clone(),
            Err(_) => return orbit.map(|_| ()),
        };
        *self = Transverse {
            work: self.work,
            ..Transverse::starting_from(values, start_time, scope, Some(&start))?
        };
        orbit.map(|_| ())
    }

    /// The simulation at `start_time` from the initial state the values ask for, or, given, from
    /// `motion` (the states the right-hand side reads).
    fn starting_from(
        values: &ValueSet,
        start_time: f64,
        scope: &Scope,
        motion: Option<&[f64]>,
    ) -> Result<Self, Error> {
        require_finite_start(start_time)?;
        let m = require_positive(values, vr::M)?;
        let mu = require_positive(values, vr::MU)?;
        let g = require_positive(values, vr::G)?;
        let fs_ratio = require_positive(values, vr::FS_RATIO)?;
        let vs = require_positive(values, vr::VS)?;
        let kt = require_positive(values, vr::KT)?;
        let zeta = require_non_negative(values, vr::ZETA)?;
        let hv = require_non_negative(values, vr::HV)?;
        let kd = require_non_negative(values, vr::KD)?;
        let hd = require_non_negative(values, vr::HD)?;
        let eta = values.real(vr::ETA);
        if !(0.0..=1.0).contains(&eta) {
            return Err(Error::value("eta", eta, "0 <= eta <= 1"));
        }
        let va = require_non_negative(values, vr::VA)?;
        let f = require_positive(values, vr::F)?;
        let vd = require_finite(values, vr::VD)?;
        let vd_in = values.real(vr::VD_IN);
        let fc = mu * m * g;
        let law = LuGre2d {
            kt,
            fc,
            fs: fs_ratio * fc,
            vs,
            h0: 2.0 * zeta * (m * kt).sqrt(),
            hv,
        };
        let slip = match switches::SlipLaw::read(values, vr::SLIP_LAW)? {
            switches::SlipLaw::Total => SlipLaw::Total,
            switches::SlipLaw::Split => SlipLaw::Split,
        };
        let held = switches::Body::read(values, vr::BODY)? == switches::Body::Held;
        let p = Clocked::at(
            Params {
                law,
                slip,
                m,
                kd,
                hd,
                eta,
                va,
                f,
                held,
            },
            start_time,
        );
        let drive = match DriveSource::read(values, vr::DRIVE_SOURCE)? {
            DriveSource::Input => Drive::Input,
            DriveSource::Prescribed => Drive::Prescribed(vd),
        };
        let vd_start = match drive {
            Drive::Prescribed(v) => v,
            Drive::Input => vd_in,
        };
        if !vd_start.is_finite() {
            return Err(Error::value("vd_in", vd_in, "a finite number"));
        }
        let steps = require_steps(values, vr::STEPS_PER_PERIOD)?;
        let rtol = require_tolerance(values, vr::TOLERANCE)?;

        // Initial state.
        let mut y = [0.0; MAX_DIM];
        let sliding = InitialState::read(values, vr::INITIAL)? != InitialState::Rest;
        if let Some(motion) = motion {
            y[..motion.len()].copy_from_slice(motion);
        } else if sliding && !held && vd_start != 0.0 {
            y[VX] = vd_start;
            y[LAMBDA] = if kd > 0.0 {
                fc / kd * vd_start.signum()
            } else {
                0.0
            };
            y[ZX] = law.g(vd_start) * vd_start.signum();
        }
        // w counts from the energy stored at the start, so W_diss starts at 0 when the contact
        // starts deflected.
        y[W] = 0.5 * kt * (y[ZX] * y[ZX] + y[ZY] * y[ZY]);

        let name = TransverseSolver::read(values, vr::SOLVER)?;
        let trim = Trim::of(scope, values, name);
        let solver = Solver::new(name, &p, (start_time, &y), steps, (rtol, vd), trim.axial);

        Ok(Transverse {
            p,
            drive,
            solver,
            band_points: solver::band_points(name, rtol),
            fc,
            start_time,
            t: start_time,
            y,
            vd_held: vd_start,
            vd_input: Extrapolator::default(),
            input_scheme: InputScheme::read(values, vr::INPUT_SCHEME)?,
            mean: PeriodMean::new(start_time, 1.0 / f),
            work: Work::default(),
            trim,
            notice: None,
            ahead: None,
        })
    }
}
