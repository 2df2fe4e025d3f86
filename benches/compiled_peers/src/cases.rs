//! The cases: for each, our solvers through the simulation (the step functions the FMU calls
//! in-process), the peers on the same right-hand sides, and the reference value.

use crate::fmu_library;
use crate::peers::{self, Outcome, Peer};
use crate::problem::{self, Mode, Reading, Spec};
use friction_fmu::friction::regularized::Regularized;
use friction_fmu::models::longitudinal::{Law, Longitudinal, Velocity};
use friction_fmu::models::oscillator::{Equations, Forced, Oscillator};
use friction_fmu::models::ramp::Ramp;
use friction_fmu::models::transverse::{
    tolerance_scales, Equations as TransverseEquations, Transverse, COUPLED,
};
use friction_fmu::models::Simulation;
use friction_fmu::models::{
    longitudinal::table as il, oscillator::table as io, transverse::table as it,
};
use friction_fmu::variables::values::ValueSet;
use friction_fmu::variables::variable::EnumType;
use std::cell::Cell;
use std::f64::consts::TAU;
use std::rc::Rc;

/// A solver's setting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Knob {
    Tolerance(f64),
    StepsPerPeriod(u32),
}

impl std::fmt::Display for Knob {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Knob::Tolerance(t) => write!(f, "rtol {t:.0e}"),
            Knob::StepsPerPeriod(n) => write!(f, "{n} steps/period"),
        }
    }
}

/// The name of a curve of ours through the FMU's library: its in-process twin's and this.
pub const LIBRARY_SUFFIX: &str = " (FMU library)";

pub type Runner = Rc<dyn Fn(Knob) -> Result<Outcome, String>>;

/// One solver's work-precision curve: its settings, loosest first.
pub struct Curve {
    pub name: String,
    pub ours: bool,
    /// Ours through the FMU's own library (`fmu` profile, fmi2 calls: [`crate::fmu_library`]),
    /// reported beside the in-process runs (`ours`), never as a peer.
    pub via_library: bool,
    pub knobs: Vec<Knob>,
    pub run: Runner,
    /// Why the solver is not run on this case, if it is not.
    pub absent: Option<String>,
}

/// A curve measured elsewhere: (error, CPU s) points and where they come from.
pub struct Quoted {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

pub struct Case {
    pub title: String,
    pub quantity: &'static str,
    pub curves: Vec<Curve>,
    pub quoted: Vec<Quoted>,
    pub reference: f64,
    /// How the reference was made and how far the second solver is from it.
    pub reference_note: String,
}

/// The loosest relative tolerance every solver, ours and the peers, is run at: the loosest our
/// FMUs' tolerance parameters accept.
const LOOSEST: f64 = 1e-2;

/// Relative tolerances from [`LOOSEST`] down to 1e-12, two a decade (1, 3).
pub fn tolerances() -> Vec<Knob> {
    let mut out = Vec::new();
    for k in 0..=12 {
        for m in [3.0, 1.0] {
            let t = m * 10f64.powi(-k);
            if (1e-12 * (1.0 - 1e-9)..=LOOSEST * (1.0 + 1e-9)).contains(&t) {
                out.push(Knob::Tolerance(t));
            }
        }
    }
    out
}

fn steps(counts: &[u32]) -> Vec<Knob> {
    counts.iter().map(|&n| Knob::StepsPerPeriod(n)).collect()
}

fn item(e: &EnumType, name: &str) -> f64 {
    f64::from(e.value_of(name).expect("enum item"))
}

fn tolerance(knob: Knob) -> f64 {
    match knob {
        Knob::Tolerance(t) => t,
        Knob::StepsPerPeriod(_) => panic!("peers take tolerances"),
    }
}

fn peer_curves<P: problem::Problem + 'static>(spec: Rc<Spec<P>>, peers: &[Peer]) -> Vec<Curve> {
    peers
        .iter()
        .map(|&peer| {
            let spec = spec.clone();
            Curve {
                name: peer.name().into(),
                ours: false,
                via_library: false,
                knobs: tolerances(),
                run: Rc::new(move |k| peers::run(peer, &spec, tolerance(k))),
                absent: None,
            }
        })
        .collect()
}

fn relative_difference(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Reference: `ours` at its tightest; the note gives `check`'s distance from it.
fn reference(ours: (&str, f64), check: (&str, Result<f64, String>)) -> (f64, String) {
    let (name, value) = ours;
    let note = match check.1 {
        Ok(v) => format!(
            "reference {value:.15e} from {name}; {} differs from it by {:.1e}",
            check.0,
            relative_difference(v, value)
        ),
        Err(e) => format!(
            "reference {value:.15e} from {name}; {} failed: {e}",
            check.0
        ),
    };
    (value, note)
}

// ---------------------------------------------------------------------------------------------
// Scene T

pub const T_PERIODS: u32 = 150;

fn transverse_values(slip_law: &str, kt_factor: f64, solver: &str, knob: Knob) -> ValueSet {
    let mut v = ValueSet::start(&it::TABLE);
    v.set(it::vr::SLIP_LAW, item(&it::SLIP_LAW, slip_law));
    v.set(it::vr::INITIAL, item(&it::INITIAL, "sliding"));
    v.set(it::vr::VD, 5e-4);
    v.set(it::vr::VA, 2e-3);
    v.set(it::vr::F, 3000.0);
    v.set(it::vr::KT, v.real(it::vr::KT) * kt_factor);
    v.set(it::vr::SOLVER, item(&it::SOLVER, solver));
    match knob {
        Knob::StepsPerPeriod(n) => v.set(it::vr::STEPS_PER_PERIOD, f64::from(n)),
        Knob::Tolerance(t) => v.set(it::vr::TOLERANCE, t),
    }
    v
}

/// Ours through the FMU's library: the same run by fmi2 calls, one fmi2DoStep a period.
fn transverse_library(
    library: Rc<fmu_library::Library>,
    slip_law: &'static str,
    kt_factor: f64,
    solver: &'static str,
) -> Runner {
    Rc::new(move |knob| {
        let v = transverse_values(slip_law, kt_factor, solver, knob);
        let mut integers: Vec<(u32, i32)> = [it::vr::SLIP_LAW, it::vr::INITIAL, it::vr::SOLVER]
            .map(|vr| (vr, v.real(vr) as i32))
            .to_vec();
        let mut reals: Vec<(u32, f64)> = [it::vr::VD, it::vr::VA, it::vr::F, it::vr::KT]
            .map(|vr| (vr, v.real(vr)))
            .to_vec();
        match knob {
            Knob::StepsPerPeriod(n) => integers.push((it::vr::STEPS_PER_PERIOD, n as i32)),
            Knob::Tolerance(t) => reals.push((it::vr::TOLERANCE, t)),
        }
        let setting = fmu_library::Setting { integers, reals };
        let value = library.run(&setting, 1.0 / 3000.0, T_PERIODS, it::vr::FFX_MEAN)?;
        // The library reports no counts: the in-process twin's are filled in (main.rs).
        Ok(Outcome { value, rhs: 0 })
    })
}

/// Ours: the simulation from steady sliding, one communication step a period, FFx_mean at the end.
fn transverse_ours(slip_law: &'static str, kt_factor: f64, solver: &'static str) -> Runner {
    Rc::new(move |knob| {
        let v = transverse_values(slip_law, kt_factor, solver, knob);
        let mut sim = Transverse::new(&v, 0.0)?;
        let period = 1.0 / 3000.0;
        for i in 0..T_PERIODS {
            let h = f64::from(i + 1) * period - sim.time();
            sim.do_step(h, &v)?;
        }
        Ok(Outcome {
            value: sim.mean_ffx(),
            rhs: sim.work.rhs_evaluations,
        })
    })
}

pub fn transverse(slip_law: &'static str, kt_factor: f64, scipy: &[(f64, f64)]) -> Case {
    let values = transverse_values(slip_law, kt_factor, "dopri5", Knob::Tolerance(1e-8));
    let sim = Transverse::new(&values, 0.0).expect("scene T");
    let vd = values.real(it::vr::VD);
    let p: &'static _ = Box::leak(Box::new(sim.p));
    let f = p.f;
    let drive = Ramp {
        value: vd,
        rate: 0.0,
    };
    let scales = tolerance_scales(p, vd);
    let mut scale = scales[..COUPLED].to_vec();
    scale.push(scales[friction_fmu::models::transverse::Q]);
    let spec = Rc::new(Spec {
        problem: problem::Transverse {
            equations: TransverseEquations::new(p, drive, &[]),
        },
        // The simulation's saved state is [t, vd, vd', y..], y's first five the coupled states.
        y0: sim.save()[3..3 + COUPLED].to_vec(),
        scale,
        t_read: f64::from(T_PERIODS - 1) / f,
        t_end: f64::from(T_PERIODS) / f,
        reading: Reading::Mean { period: 1.0 / f },
    });
    let stiff = kt_factor > 1.0;
    let mut curves = Vec::new();
    if !stiff {
        curves.push(Curve {
            name: "ours dopri5".into(),
            ours: true,
            via_library: false,
            knobs: tolerances(),
            run: transverse_ours(slip_law, kt_factor, "dopri5"),
            absent: None,
        });
        curves.push(Curve {
            name: "ours dop853".into(),
            ours: true,
            via_library: false,
            knobs: tolerances(),
            run: transverse_ours(slip_law, kt_factor, "dop853"),
            absent: None,
        });
        // The same through the FMU's library: the explicit pairs, which are ours' fastest here.
        let library = fmu_library::Library::load("TransverseFriction").map(Rc::new);
        for solver in ["dopri5", "dop853"] {
            let (run, absent): (Runner, _) = match &library {
                Ok(l) => (
                    transverse_library(l.clone(), slip_law, kt_factor, solver),
                    None,
                ),
                Err(e) => (Rc::new(|_| Err("no library".into())), Some(e.clone())),
            };
            curves.push(Curve {
                name: format!("ours {solver}{LIBRARY_SUFFIX}"),
                ours: false,
                via_library: true,
                knobs: tolerances(),
                run,
                absent,
            });
        }
    }
    curves.push(Curve {
        name: "ours radau5".into(),
        ours: true,
        via_library: false,
        knobs: tolerances(),
        run: transverse_ours(slip_law, kt_factor, "radau5"),
        absent: None,
    });
    curves.push(Curve {
        name: "ours exponential".into(),
        ours: true,
        via_library: false,
        knobs: steps(&[25, 50, 100, 200, 400, 800, 1600, 3200, 6400]),
        run: transverse_ours(slip_law, kt_factor, "exponential"),
        absent: None,
    });
    curves.extend(peer_curves(spec.clone(), &peers::ALL));
    // The reference: ours at the tightest tolerance the report uses, and an independent peer.
    let (ours_ref, check) = if stiff {
        (
            (
                "ours radau5 at rtol 1e-12",
                transverse_ours(slip_law, kt_factor, "radau5")(Knob::Tolerance(1e-12)),
            ),
            (
                "CVODE BDF at rtol 1e-11",
                peers::run(Peer::CvodeBdf, &spec, 1e-11).map(|o| o.value),
            ),
        )
    } else {
        (
            (
                "ours dopri5 at rtol 1e-12",
                transverse_ours(slip_law, kt_factor, "dopri5")(Knob::Tolerance(1e-12)),
            ),
            (
                "CVODE Adams at rtol 1e-12",
                peers::run(Peer::CvodeAdams, &spec, 1e-12).map(|o| o.value),
            ),
        )
    };
    let ours_value = ours_ref.1.expect("reference run").value;
    let (reference, reference_note) = reference((ours_ref.0, ours_value), check);
    Case {
        title: format!(
            "T: {slip_law} slip law, kt x {kt_factor}, vd 0.5 mm/s, va 2 mm/s, f 3 kHz, from steady sliding, {T_PERIODS} periods (0.05 s), one communication step a period"
        ),
        quantity: "FFx_mean of the last period",
        curves,
        quoted: if scipy.is_empty() {
            Vec::new()
        } else {
            vec![Quoted {
                name: "scipy Radau (Python; another process: benches/transverse_results.md)".into(),
                points: scipy.to_vec(),
            }]
        },
        reference,
        reference_note,
    }
}

// ---------------------------------------------------------------------------------------------
// Scene L

pub const L_PERIODS: u32 = 30;

fn longitudinal_values(solver: &str, knob: Knob) -> ValueSet {
    let mut v = ValueSet::start(&il::TABLE);
    v.set(il::vr::LAW, item(&il::LAW, "dahl"));
    v.set(il::vr::VC, 0.146);
    v.set(il::vr::SOLVER, item(&il::SOLVER, solver));
    match knob {
        Knob::StepsPerPeriod(n) => v.set(il::vr::STEPS_PER_PERIOD, f64::from(n)),
        Knob::Tolerance(t) => v.set(il::vr::TOLERANCE, t),
    }
    v
}

fn longitudinal_ours(solver: &'static str) -> Runner {
    Rc::new(move |knob| {
        let v = longitudinal_values(solver, knob);
        let mut sim = Longitudinal::new(&v, 0.0)?;
        let period = 1.0 / sim.f;
        for i in 0..L_PERIODS {
            let h = f64::from(i + 1) * period - sim.time();
            sim.do_step(h, &v)?;
        }
        Ok(Outcome {
            value: sim.mean_force(),
            rhs: sim.work.rhs_evaluations,
        })
    })
}

pub fn longitudinal() -> Case {
    let values = longitudinal_values("dopri5", Knob::Tolerance(1e-8));
    let sim = Longitudinal::new(&values, 0.0).expect("scene L");
    let Law::Dahl(law) = sim.law else {
        panic!("Dahl law expected")
    };
    let Velocity::Prescribed { vc, va } = sim.velocity else {
        panic!("prescribed velocity expected")
    };
    let f = sim.f;
    // The simulation's absolute-tolerance scales (src/models/longitudinal/solver.rs): the deflection,
    // FC/kt or the distance slid in a period if less, and the force integral over a period.
    let z_scale = (law.fc / law.kt).min((vc.abs() + va) / f);
    let spec = Rc::new(Spec {
        problem: problem::Longitudinal { law, vc, va, f },
        y0: vec![0.0],
        scale: vec![z_scale, law.kt * z_scale / f],
        t_read: f64::from(L_PERIODS - 1) / f,
        t_end: f64::from(L_PERIODS) / f,
        reading: Reading::Mean { period: 1.0 / f },
    });
    let mut curves = vec![
        Curve {
            name: "ours dopri5".into(),
            ours: true,
            via_library: false,
            knobs: tolerances(),
            run: longitudinal_ours("dopri5"),
            absent: None,
        },
        Curve {
            name: "ours radau5".into(),
            ours: true,
            via_library: false,
            knobs: tolerances(),
            run: longitudinal_ours("radau5"),
            absent: None,
        },
        Curve {
            name: "ours closed_form".into(),
            ours: true,
            via_library: false,
            knobs: tolerances(),
            run: longitudinal_ours("closed_form"),
            absent: None,
        },
        Curve {
            name: "ours exponential".into(),
            ours: true,
            via_library: false,
            knobs: steps(&[25, 50, 100, 200, 400, 800, 1600, 3200, 6400, 12800]),
            run: longitudinal_ours("exponential"),
            absent: None,
        },
    ];
    curves.extend(peer_curves(spec.clone(), &peers::ALL));
    let ours = longitudinal_ours("dopri5")(Knob::Tolerance(1e-13))
        .expect("reference run")
        .value;
    let (reference, reference_note) = reference(
        ("ours dopri5 at rtol 1e-13", ours),
        (
            "CVODE Adams at rtol 1e-12",
            peers::run(Peer::CvodeAdams, &spec, 1e-12).map(|o| o.value),
        ),
    );
    Case {
        title: format!(
            "L: Dahl law, Table 1's vc = 0.146 m/s (va 0.264 m/s, f 60 kHz, kt 0.056 N/um), from rest, {L_PERIODS} periods, one communication step a period"
        ),
        quantity: "FT_mean of the last period",
        curves,
        quoted: Vec::new(),
        reference,
        reference_note,
    }
}

// ---------------------------------------------------------------------------------------------
// Scene O

pub const O_PERIODS: u32 = 60;

fn oscillator_values(law: &str, solver: &str, knob: Knob) -> ValueSet {
    let mut v = ValueSet::start(&io::TABLE);
    v.set(io::vr::LAW, item(&io::LAW, law));
    v.set(io::vr::SOLVER, item(&io::SOLVER, solver));
    match knob {
        Knob::StepsPerPeriod(n) => v.set(io::vr::STEPS_PER_PERIOD, f64::from(n)),
        Knob::Tolerance(t) => {
            v.set(io::vr::RTOL, t);
            v.set(io::vr::ATOL, t);
            // The fewest sub-steps allowed, so the tolerance alone sets the step.
            v.set(io::vr::STEPS_PER_PERIOD, 8.0);
        }
    }
    v
}

fn oscillator_ours(law: &'static str, solver: &'static str) -> Runner {
    Rc::new(move |knob| {
        let v = oscillator_values(law, solver, knob);
        let mut sim = Oscillator::new(&v, 0.0)?;
        let period = TAU / v.real(io::vr::W);
        for i in 0..O_PERIODS {
            let h = f64::from(i + 1) * period - sim.time();
            sim.do_step(h, &v)?;
        }
        Ok(Outcome {
            value: sim.amplitude(),
            rhs: sim.work.rhs_evaluations,
        })
    })
}

fn plant(v: &ValueSet) -> Forced {
    Forced {
        m: v.real(io::vr::M),
        c: v.real(io::vr::C),
        k: v.real(io::vr::K),
        w: v.real(io::vr::W),
        p: v.real(io::vr::P),
        input: false,
    }
}

pub fn oscillator_trigonometric() -> Case {
    let values = oscillator_values("trigonometric", "radau5", Knob::Tolerance(1e-8));
    let (h, d) = (values.real(io::vr::H), values.real(io::vr::D));
    let period = TAU / values.real(io::vr::W);
    let spec = Rc::new(Spec {
        problem: problem::Oscillator {
            equations: Equations {
                plant: plant(&values),
                held: 0.0,
                law: Regularized::Trigonometric { h, d },
                with_work: false,
            },
        },
        y0: vec![0.0, 0.0],
        scale: vec![1.0, 1.0],
        t_read: f64::from(O_PERIODS - 1) * period,
        t_end: f64::from(O_PERIODS) * period,
        reading: Reading::Amplitude,
    });
    let mut curves = vec![
        Curve {
            name: "ours radau5".into(),
            ours: true,
            via_library: false,
            knobs: tolerances(),
            run: oscillator_ours("trigonometric", "radau5"),
            absent: None,
        },
        Curve {
            name: "ours dopri5".into(),
            ours: true,
            via_library: false,
            knobs: tolerances(),
            run: oscillator_ours("trigonometric", "dopri5"),
            absent: None,
        },
        Curve {
            name: "ours piecewise".into(),
            ours: true,
            via_library: false,
            knobs: tolerances(),
            run: oscillator_ours("trigonometric", "piecewise"),
            absent: None,
        },
    ];
    curves.extend(peer_curves(spec.clone(), &peers::ALL));
    let ours = oscillator_ours("trigonometric", "radau5")(Knob::Tolerance(1e-13))
        .expect("reference run")
        .value;
    let (reference, reference_note) = reference(
        ("ours radau5 at rtol = atol = 1e-13", ours),
        (
            "CVODE Adams at rtol = atol = 1e-12",
            peers::run(Peer::CvodeAdams, &spec, 1e-12).map(|o| o.value),
        ),
    );
    Case {
        title: format!(
            "O: trigonometric law, D = 0.8 (paper's case: m 1, c 0.1, k 1, P 4, w 1, h 1.6), from rest, {O_PERIODS} periods, one communication step a period; rtol = atol"
        ),
        quantity: "u_amplitude, max |u| over the last period",
        curves,
        quoted: Vec::new(),
        reference,
        reference_note,
    }
}

pub fn oscillator_exact() -> Case {
    let values = oscillator_values("exact", "radau5", Knob::StepsPerPeriod(128));
    let period = TAU / values.real(io::vr::W);
    let span = (
        f64::from(O_PERIODS - 1) * period,
        f64::from(O_PERIODS) * period,
    );
    let switch = Rc::new(problem::Switch {
        plant: plant(&values),
        h: values.real(io::vr::H),
        mode: Cell::new(Mode(0.0)),
    });
    let mut curves = vec![Curve {
        name: "ours exact (closed form)".into(),
        ours: true,
        via_library: false,
        knobs: steps(&[8, 128]),
        run: oscillator_ours("exact", "radau5"),
        absent: None,
    }];
    for peer in peers::ALL {
        let switch = switch.clone();
        curves.push(Curve {
            name: peer.name().into(),
            ours: false,
            via_library: false,
            knobs: tolerances(),
            run: Rc::new(move |k| {
                peers::run_switch(peer, &switch, span, period / 8.0, tolerance(k))
            }),
            absent: (!peer.locates_events())
                .then(|| "cannot: no event location (root finding) in ode_solvers".to_string()),
        });
    }
    let ours = oscillator_ours("exact", "radau5")(Knob::StepsPerPeriod(128))
        .expect("reference run")
        .value;
    let (reference, reference_note) = reference(
        ("ours exact (closed form, 128 steps/period)", ours),
        (
            "CVODE Adams with events at rtol 1e-12",
            peers::run_switch(Peer::CvodeAdams, &switch, span, period / 8.0, 1e-12)
                .map(|o| o.value),
        ),
    );
    Case {
        title: format!(
            "O: exact switch law (paper's case), from rest, {O_PERIODS} periods, one communication step a period; peers locate every stick and slip event and restart there"
        ),
        quantity: "u_amplitude, max |u| over the last period",
        curves,
        quoted: Vec::new(),
        reference,
        reference_note,
    }
}
