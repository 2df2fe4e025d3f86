//! The stability matrix (stiff and extreme cases): every
//! solver of every scene against each extreme the scene has a parameter for, run through the
//! exported fmi2* functions as a master would (src/importer.rs), with the outcome of each run.
//!
//! Each case is short (a few periods, or a few thousand communication steps); the long run is
//! 1e6 vibration periods in scene L (at 1 Hz, communication steps of 1e4 periods, coarse
//! settings) and 1e4 periods in T and O, whose solvers cost more per period.

mod run;

pub use run::{print, run, Outcome, Row};

/// A parameter value as the FMU takes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Real(f64),
    Integer(i32),
    /// An enumeration item, by name.
    Item(&'static str),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub model: &'static str,
    /// The `solver` item; "-" for cases whose friction law has a closed form (no solver).
    pub solver: &'static str,
    /// What is extreme, as the table shows it.
    pub extreme: &'static str,
    pub params: Vec<(&'static str, Value)>,
    pub step: f64,
    pub steps: u64,
}

/// One extreme of a scene: its parameters, communication step and number of steps.
type Extreme = (&'static str, &'static [(&'static str, Value)], f64, u64);

use Value::{Integer, Item, Real};

const L_PERIOD: f64 = 1.0 / 60e3;
/// Scene L, Dahl at Table 1's vc = 0.146 m/s unless the case says otherwise; 3 periods.
const LONGITUDINAL: &[Extreme] = &[
    ("paper", &[], L_PERIOD / 20.0, 60),
    ("kt x1e3", &[("kt", Real(5.6e7))], L_PERIOD / 20.0, 60),
    (
        "lugre vs 1e-9",
        &[("law", Item("lugre")), ("vs", Real(1e-9))],
        L_PERIOD / 20.0,
        60,
    ),
    ("f 1 Hz", &[("f", Real(1.0))], 0.05, 60),
    ("f 100 kHz", &[("f", Real(1e5))], 1e-5 / 20.0, 60),
    ("va 0", &[("va", Real(0.0))], L_PERIOD / 20.0, 60),
    ("va 100 vc", &[("vc", Real(0.00264))], L_PERIOD / 20.0, 60),
    ("vc 0", &[("vc", Real(0.0))], L_PERIOD / 20.0, 60),
    ("vc < 0", &[("vc", Real(-0.146))], L_PERIOD / 20.0, 60),
    // Below alpha 1 the bristle saturates in finite time, where the rate is not Lipschitz.
    (
        "dahl alpha 0.3",
        &[("law", Item("dahl")), ("alpha", Real(0.3))],
        L_PERIOD / 20.0,
        60,
    ),
    ("m 1e-6", &[("m", Real(1e-6))], L_PERIOD / 20.0, 60),
    ("step 1e-8", &[], 1e-8, 2000),
    ("step 1 s", &[], 1.0, 2),
    // Only where a period costs a few steps whatever the stiffness (see `applies`).
    (
        "1e6 periods",
        &[("f", Real(1.0)), ("steps_per_period", Integer(8))],
        1e4,
        100,
    ),
    (
        "1e4 periods",
        &[("steps_per_period", Integer(64)), ("tolerance", Real(1e-4))],
        100.0 * L_PERIOD,
        100,
    ),
];

const T_PERIOD: f64 = 1.0 / 3000.0;
/// Scene T at the paper's values (vd 0.5 mm/s, va 2 mm/s, 3 kHz) starting in steady sliding;
/// 4 periods.
const TRANSVERSE: &[Extreme] = &[
    ("paper", &[], T_PERIOD / 20.0, 80),
    ("kt x1e3", &[("kt", Real(6.286e10))], T_PERIOD / 20.0, 80),
    ("vs 1e-9", &[("vs", Real(1e-9))], T_PERIOD / 20.0, 80),
    ("f 1 Hz", &[("f", Real(1.0))], 1e-3, 10),
    ("f 100 kHz", &[("f", Real(1e5))], 1e-5 / 20.0, 80),
    ("va 0", &[("va", Real(0.0))], T_PERIOD / 20.0, 80),
    ("va 100 vd", &[("vd", Real(2e-5))], T_PERIOD / 20.0, 80),
    ("vd 0", &[("vd", Real(0.0))], T_PERIOD / 20.0, 80),
    // The body moves along y alone, so the bristle passes through zero where the slip reverses.
    (
        "vd 0, zeta 0.4, hv 1",
        &[("vd", Real(0.0)), ("zeta", Real(0.4)), ("hv", Real(1.0))],
        T_PERIOD / 20.0,
        80,
    ),
    ("vd < 0", &[("vd", Real(-5e-4))], T_PERIOD / 20.0, 80),
    ("eta 0", &[("eta", Real(0.0))], T_PERIOD / 20.0, 80),
    ("eta 1", &[("eta", Real(1.0))], T_PERIOD / 20.0, 80),
    // One period: dopri5 warns of the stiffness within it and then grinds on.
    ("m 1e-6", &[("m", Real(1e-6))], T_PERIOD / 20.0, 20),
    ("step 1e-8", &[], 1e-8, 2000),
    ("step 1 s", &[], 1.0, 2),
    (
        "1e4 periods",
        &[("steps_per_period", Integer(20)), ("tolerance", Real(1e-4))],
        100.0 * T_PERIOD,
        100,
    ),
];

const O_PERIOD: f64 = std::f64::consts::TAU;
/// Scene O, trigonometric law at the paper's values (w = 1 rad/s); 3 forcing periods.
const OSCILLATOR: &[Extreme] = &[
    ("paper", &[], O_PERIOD / 50.0, 150),
    ("D 1e-6", &[("D", Real(1e-6))], O_PERIOD / 50.0, 150),
    (
        "w 2 pi 1 Hz",
        &[("w", Real(std::f64::consts::TAU))],
        1.0 / 50.0,
        150,
    ),
    (
        "w 2 pi 100 kHz",
        &[("w", Real(std::f64::consts::TAU * 1e5))],
        1e-5 / 50.0,
        150,
    ),
    ("m 1e-6", &[("m", Real(1e-6))], O_PERIOD / 50.0, 50),
    ("step 1e-8", &[], 1e-8, 2000),
    ("step 1 s", &[], 1.0, 20),
    (
        "1e4 periods",
        &[("steps_per_period", Integer(20)), ("rtol", Real(1e-4))],
        100.0 * O_PERIOD,
        100,
    ),
];

/// DriveTrain at its defaults (10 ms mechanical, 0.2 ms electrical time constant) from rest;
/// every extreme runs through, the scheme being exact at any step.
const DRIVE: &[Extreme] = &[
    ("paper", &[], 1e-4, 500),
    ("L 1e-9", &[("L", Real(1e-9))], 1e-4, 500),
    ("J 1e-12", &[("J", Real(1e-12))], 1e-4, 500),
    ("efficiency 1e-3", &[("efficiency", Real(1e-3))], 1e-4, 500),
    ("step 1e-8", &[], 1e-8, 2000),
    ("step 1 s", &[], 1.0, 20),
    ("1e6 s", &[], 1e4, 100),
];

/// Parameters every case of a scene starts from.
fn base(model: &str) -> &'static [(&'static str, Value)] {
    match model {
        "LongitudinalFriction" => &[("law", Item("dahl")), ("vc", Real(0.146))],
        "TransverseFriction" => &[("initial", Item("sliding"))],
        _ => &[],
    }
}

/// The `solver` items of a model, in the order of its table.
pub fn solvers(model: &str) -> Vec<&'static str> {
    crate::scenes::model(model)
        .and_then(|m| {
            let var = m.table.by_name("solver")?;
            let crate::interface::variable::Kind::Switch { type_name, .. } = var.kind else {
                return None;
            };
            m.table.enum_type(type_name)
        })
        .map(|e| e.items.iter().map(|(name, _)| *name).collect())
        .unwrap_or_default()
}

/// Every case: scene x solver x extreme, plus scene O's exact law (no solver) and scene L's
/// Coulomb law (closed form) at each of their extremes.
pub fn cases() -> Vec<Case> {
    let mut cases = Vec::new();
    let scenes: [(&str, &[Extreme]); 4] = [
        ("LongitudinalFriction", LONGITUDINAL),
        ("TransverseFriction", TRANSVERSE),
        ("DryFrictionOscillator", OSCILLATOR),
        ("DriveTrain", DRIVE),
    ];
    for (model, extremes) in scenes {
        let mut menu: Vec<(&str, Option<(&str, &str)>)> =
            solvers(model).into_iter().map(|s| (s, None)).collect();
        match model {
            "LongitudinalFriction" => menu.push(("-", Some(("law", "coulomb")))),
            "DryFrictionOscillator" => menu.push(("-", Some(("law", "exact")))),
            _ => {}
        }
        for (solver, law) in menu {
            for &(extreme, params, step, steps) in extremes {
                // An extreme of another law (LuGre's vs) does not apply to a fixed law's row.
                if law.is_some() && params.iter().any(|(name, _)| *name == "law") {
                    continue;
                }
                // Scene L's long run: 1e6 periods where the scheme is closed-form per sub-step
                // (exponential, Coulomb), 1e4 where an ODE solver resolves each period.
                let closed_form = matches!(solver, "exponential" | "-");
                let long = match extreme {
                    "1e6 periods" => closed_form,
                    "1e4 periods" => model != "LongitudinalFriction" || !closed_form,
                    _ => true,
                };
                if !long {
                    continue;
                }
                let mut all: Vec<(&str, Value)> = base(model).to_vec();
                if solver != "-" {
                    all.push(("solver", Item(solver)));
                }
                if let Some((name, item)) = law {
                    all.push((name, Item(item)));
                }
                all.extend_from_slice(params);
                cases.push(Case {
                    model,
                    solver: law.map_or(solver, |(_, item)| item),
                    extreme,
                    params: all,
                    step,
                    steps,
                });
            }
        }
    }
    cases
}

/// Runs every case on `threads` threads; rows in the order of [`cases`]. `done` hears of each
/// row as it completes, with the number of cases (for progress).
pub fn matrix(threads: usize, done: &(dyn Fn(&Row, usize) + Sync)) -> Vec<Row> {
    let cases = cases();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut rows: Vec<Option<Row>> = vec![None; cases.len()];
    let slots = std::sync::Mutex::new(&mut rows);
    std::thread::scope(|scope| {
        for _ in 0..threads.max(1) {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(case) = cases.get(i) else { break };
                let row = run(case);
                done(&row, cases.len());
                slots.lock().unwrap_or_else(|e| e.into_inner())[i] = Some(row);
            });
        }
    });
    rows.into_iter().flatten().collect()
}
