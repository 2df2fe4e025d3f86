//! The work-precision studies of the `report` command, one per scene (two for scene T, one per
//! slip law): the experiment, the quantity, the solvers and the settings swept.

use super::work_precision::{Case, Knob, Setting};
use crate::models::longitudinal::Longitudinal;
use crate::models::oscillator::Oscillator;
use crate::models::transverse::Transverse;
use crate::models::Simulation;
use crate::models::{longitudinal::table as il, oscillator::table as io, transverse::table as it};
use crate::solve::Work;
use crate::variables::values::ValueSet;
use crate::variables::variable::EnumType;

fn tolerances(solver: &'static str, from: i32, to: i32) -> Vec<Setting> {
    (from..=to)
        .map(|k| Setting {
            solver,
            knob: Knob::Tolerance(10f64.powi(-k)),
        })
        .collect()
}

fn steps(solver: &'static str, counts: &[u32]) -> Vec<Setting> {
    counts
        .iter()
        .map(|&n| Setting {
            solver,
            knob: Knob::StepsPerPeriod(n),
        })
        .collect()
}

fn item(e: &EnumType, name: &str) -> Result<f64, String> {
    e.value_of(name)
        .map(f64::from)
        .ok_or_else(|| format!("{} has no item {name}", e.name))
}

/// Scene L at Table 1's row vc = 0.146 m/s, Dahl law: FT_mean over the 30th vibration period.
pub fn longitudinal() -> Case {
    const PERIODS: u32 = 30;
    let mut settings = steps("exponential", &[25, 50, 100, 200, 400, 800, 1600, 3200]);
    settings.extend(steps("rk4", &[25, 50, 100, 200, 400, 800, 1600]));
    settings.extend(tolerances("dopri5", 3, 10));
    settings.extend(tolerances("radau5", 3, 10));
    settings.extend(tolerances("closed_form", 3, 10));
    let run = |s: &Setting| -> Result<(f64, Work), String> {
        let mut v = ValueSet::start(&il::TABLE);
        v.set(il::vr::LAW, item(&il::LAW, "dahl")?);
        v.set(il::vr::VC, 0.146);
        v.set(il::vr::SOLVER, item(&il::SOLVER, s.solver)?);
        match s.knob {
            Knob::StepsPerPeriod(n) => v.set(il::vr::STEPS_PER_PERIOD, f64::from(n)),
            Knob::Tolerance(t) => v.set(il::vr::TOLERANCE, t),
        }
        let mut sim = Longitudinal::new(&v, 0.0)?;
        let period = 1.0 / sim.f;
        for _ in 0..PERIODS {
            sim.do_step(period, &v)?;
        }
        Ok((sim.mean_force(), sim.work))
    };
    Case {
        stem: "longitudinal",
        title: format!(
            "LongitudinalFriction, Dahl, vc = 0.146 m/s (Table 1), FT_mean of period {PERIODS}"
        ),
        short_title: "L: Dahl, vc 0.146 m/s, error of FT_mean",
        quantity: "FT_mean",
        settings,
        reference: reference("dopri5", 1e-13, 1e-12),
        run: Box::new(run),
    }
}

/// Scene T at vd = 0.5 mm/s, va = 2 mm/s, f = 3 kHz, from steady sliding, over 0.05 s: the mean
/// of FFx over the last vibration period.
pub fn transverse(slip_law: &'static str) -> Case {
    const PERIODS: u32 = 150;
    let mut settings = tolerances("dopri5", 4, 10);
    settings.extend(tolerances("radau5", 4, 9));
    settings.extend(tolerances("dop853", 4, 10));
    settings.extend(steps("rk4", &[50, 100, 200, 400, 800, 1600]));
    settings.extend(steps("exponential", &[50, 100, 200, 400, 800, 1600, 3200]));
    if slip_law == "split" {
        // The paper's scheme is the split law by construction: under `total` it converges to
        // the other model, which this table would show as an error floor (docs/performance.md,
        // "Measurements behind the code").
        settings.extend(steps("two_phase", &[100, 400, 1600, 6400, 25600]));
    }
    let run = move |s: &Setting| -> Result<(f64, Work), String> {
        let mut v = ValueSet::start(&it::TABLE);
        v.set(it::vr::SLIP_LAW, item(&it::SLIP_LAW, slip_law)?);
        v.set(it::vr::INITIAL, item(&it::INITIAL, "sliding")?);
        v.set(it::vr::VD, 5e-4);
        v.set(it::vr::VA, 2e-3);
        v.set(it::vr::F, 3000.0);
        v.set(it::vr::SOLVER, item(&it::SOLVER, s.solver)?);
        match s.knob {
            Knob::StepsPerPeriod(n) => v.set(it::vr::STEPS_PER_PERIOD, f64::from(n)),
            Knob::Tolerance(t) => v.set(it::vr::TOLERANCE, t),
        }
        let mut sim = Transverse::new(&v, 0.0)?;
        let period = 1.0 / 3000.0;
        for _ in 0..PERIODS {
            sim.do_step(period, &v)?;
        }
        Ok((sim.mean_ffx(), sim.work))
    };
    Case {
        stem: if slip_law == "total" {
            "transverse_total"
        } else {
            "transverse_split"
        },
        title: format!(
            "TransverseFriction, {slip_law} slip, vd 0.5 mm/s, va 2 mm/s, f 3 kHz, 0.05 s: FFx_mean"
        ),
        short_title: if slip_law == "total" {
            "T (total slip), 0.05 s: error of FFx_mean"
        } else {
            "T (split slip), 0.05 s: error of FFx_mean"
        },
        quantity: "FFx_mean",
        settings,
        reference: reference("dopri5", 1e-12, 1e-11),
        run: Box::new(run),
    }
}

/// Scene O at the paper's case (trigonometric law, D = 0.8, from rest): the amplitude max |u|
/// over the 60th forcing period.
pub fn oscillator() -> Case {
    const PERIODS: u32 = 60;
    let mut settings = tolerances("radau5", 3, 10);
    settings.extend(tolerances("dopri5", 3, 10));
    settings.extend(tolerances("piecewise", 3, 10));
    // Fewer than 50 steps a period would be cut to the communication step of 1/50 period.
    settings.extend(steps("rk4", &[64, 128, 256, 512, 1024, 2048, 4096]));
    let run = |s: &Setting| -> Result<(f64, Work), String> {
        let mut v = ValueSet::start(&io::TABLE);
        v.set(io::vr::LAW, item(&io::LAW, "trigonometric")?);
        v.set(io::vr::SOLVER, item(&io::SOLVER, s.solver)?);
        match s.knob {
            Knob::StepsPerPeriod(n) => v.set(io::vr::STEPS_PER_PERIOD, f64::from(n)),
            Knob::Tolerance(t) => {
                v.set(io::vr::RTOL, t);
                v.set(io::vr::ATOL, t);
                // The fewest sub-steps allowed, so the tolerance alone sets the step.
                v.set(io::vr::STEPS_PER_PERIOD, 8.0);
            }
        }
        let mut sim = Oscillator::new(&v, 0.0)?;
        // Communication steps of 1/50 period, as steady_amplitude.
        let step = std::f64::consts::TAU / v.real(io::vr::W) / 50.0;
        for _ in 0..PERIODS * 50 {
            sim.do_step(step, &v)?;
        }
        Ok((sim.amplitude(), sim.work))
    };
    Case {
        stem: "oscillator",
        title: format!(
            "DryFrictionOscillator, trigonometric law, paper's case: u_amplitude of period {PERIODS} (rtol = atol)"
        ),
        short_title: "O: trigonometric, paper's case: error of u_amplitude",
        quantity: "u_amplitude",
        settings,
        reference: reference("radau5", 1e-13, 1e-12),
        run: Box::new(run),
    }
}

pub fn all() -> Vec<Case> {
    vec![
        longitudinal(),
        transverse("split"),
        transverse("total"),
        oscillator(),
    ]
}

/// The reference run of a case (`solver` at `rtol`) and the one a decade looser that estimates
/// its own error.
fn reference(solver: &'static str, rtol: f64, looser: f64) -> (Setting, Setting) {
    let at = |rtol| Setting {
        solver,
        knob: Knob::Tolerance(rtol),
    };
    (at(rtol), at(looser))
}
