//! The stability matrix : every solver of every scene at
//! each extreme the model has a parameter for (src/report/stability.rs lists them), run through
//! the exported fmi2* functions, and convergence of each solver at a stiff setting.
//!
//! Oracles: the FMI contract (fmi2OK with finite outputs; fmi2Warning with those and a logged
//! message; or fmi2Discard/fmi2Error with a logged message, lastSuccessfulTime at the stop and
//! the outputs of that time; never NaN); passivity of the contact (W_diss, the friction work
//! minus the stored energy, never below zero beyond round-off); a solver run tighter lands
//! closer to its own far tighter run than a looser one does.
//! `cargo test --profile testing --test stability_matrix -- --nocapture` prints the matrix.
#![cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]

use friction_fmu::fmi2::ffi::Status;
use friction_fmu::importer::ImportedInstance;
use friction_fmu::models::model;
use friction_fmu::report::stability::{self, Outcome, Value};

#[test]
fn every_solver_meets_every_extreme_soundly() {
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get().min(4));
    let rows = stability::matrix(threads, &|_, _| {});
    stability::print(&rows, &mut std::io::stdout()).unwrap();
    let unsound: Vec<_> = rows.iter().filter(|r| !r.sound()).collect();
    assert!(unsound.is_empty(), "unsound rows: {unsound:#?}");
    // Every solver item of every model is in the matrix, at the paper's setting at least.
    for m in friction_fmu::models::MODELS {
        let id = m.table.model_identifier;
        for solver in stability::solvers(id) {
            let paper = rows
                .iter()
                .find(|r| r.model == id && r.solver == solver && r.extreme == "paper");
            assert_eq!(
                paper.map(|r| r.outcome),
                Some(Outcome::Ok),
                "{id} {solver} at the paper's setting"
            );
        }
    }
    // The schemes sold as stable at any stiffness (L-stable radau5, the exact bristle updates,
    // the closed forms) run every extreme to the end; only the work limit may stop them, and
    // exponential's explicit body step its bound h sqrt((kt + kd)/m) < 2, which 2000 steps a
    // period at 1 Hz break.
    for r in &rows {
        let stiff_proof = matches!(r.solver, "radau5" | "exponential" | "coulomb" | "exact");
        let explicit_bound =
            r.model == "TransverseFriction" && r.solver == "exponential" && r.extreme == "f 1 Hz";
        if explicit_bound {
            assert_eq!(r.outcome, Outcome::Discard, "{r:?}");
            assert!(r.message.contains("expected steps_per_period >"), "{r:?}");
        } else if stiff_proof && r.extreme != "step 1 s" {
            assert_eq!(r.outcome, Outcome::Ok, "{r:?}");
        }
    }
}

/// Runs `model` from rest with `params` for `steps` communication steps of `step` and returns
/// `output` at the end.
fn final_output(
    model_identifier: &str,
    params: &[(&str, Value)],
    step: f64,
    steps: u32,
    output: &str,
) -> f64 {
    let table = model(model_identifier).unwrap().table;
    let mut fmu = ImportedInstance::new(model_identifier, "convergence").unwrap();
    for &(name, value) in params {
        let var = table.by_name(name).unwrap();
        let vr = [var.value_reference];
        let status = match value {
            Value::Real(x) => fmu.set_real(&vr, &[x]),
            Value::Integer(n) => fmu.set_integer(&vr, &[n]),
            Value::Item(item) => {
                let friction_fmu::variables::variable::Kind::Switch { type_name, .. } = var.kind
                else {
                    panic!("{name} is not an enumeration");
                };
                let code = table.enum_type(type_name).unwrap().value_of(item).unwrap();
                fmu.set_integer(&vr, &[code])
            }
        };
        assert_eq!(status, Status::Ok, "{name}: {}", fmu.last_message());
    }
    assert_eq!(fmu.initialize(), Status::Ok, "{}", fmu.last_message());
    for k in 0..steps {
        let status = fmu.do_step(f64::from(k) * step, step, true);
        // fmi2Warning: dopri5 found the stiff setting stiff, and said so.
        assert!(
            matches!(status, Status::Ok | Status::Warning),
            "{params:?}: {status:?} {}",
            fmu.last_message()
        );
    }
    let vr = table.by_name(output).unwrap().value_reference;
    fmu.get_real(&[vr]).1[0]
}

/// How a solver is tightened.
#[derive(Clone, Copy)]
enum Knob {
    Steps(i32),
    Tolerance(&'static str, f64),
}

impl Knob {
    fn params(self) -> Vec<(&'static str, Value)> {
        match self {
            Knob::Steps(n) => vec![("steps_per_period", Value::Integer(n))],
            // Scene O has rtol and atol; an absolute tolerance on the scale of u' = 1 m/s.
            Knob::Tolerance("rtol", x) => vec![("rtol", Value::Real(x)), ("atol", Value::Real(x))],
            Knob::Tolerance(name, x) => vec![(name, Value::Real(x))],
        }
    }
}

/// For one solver at one stiff setting: the error of the `loose` and `tight` runs against the
/// `reference` run of the same solver; the tight one must be the smaller (or both at round-off).
fn converges(
    model_identifier: &str,
    stiff: &[(&'static str, Value)],
    (step, steps, output): (f64, u32, &str),
    solver: &'static str,
    [loose, tight, reference]: [Knob; 3],
) {
    let value = |knob: Knob| {
        let mut params = stiff.to_vec();
        params.push(("solver", Value::Item(solver)));
        params.extend(knob.params());
        final_output(model_identifier, &params, step, steps, output)
    };
    let exact = value(reference);
    let (e_loose, e_tight) = ((value(loose) - exact).abs(), (value(tight) - exact).abs());
    println!(
        "{model_identifier} {solver}: {output} {exact:.9e}, errors {e_loose:.2e} -> {e_tight:.2e}"
    );
    // Round-off accumulated over up to a million steps.
    let round_off = 1e-10 * exact.abs();
    assert!(
        e_tight < e_loose || e_loose <= round_off,
        "{model_identifier} {solver}: error {e_loose:e} at the looser setting, {e_tight:e} at the tighter"
    );
}

/// Scene L at kt x 1000 (Dahl, Table 1's vc = 0.146 m/s): FT_mean after 3 periods.
#[test]
fn longitudinal_solvers_converge_at_kt_x1000() {
    let stiff = [
        ("law", Value::Item("dahl")),
        ("vc", Value::Real(0.146)),
        ("kt", Value::Real(5.6e7)),
    ];
    let run = (1.0 / 60e3 / 20.0, 60, "FT_mean");
    let tol = |x| Knob::Tolerance("tolerance", x);
    let m = "LongitudinalFriction";
    let steps = [Knob::Steps(200), Knob::Steps(400), Knob::Steps(12_800)];
    converges(m, &stiff, run, "exponential", steps);
    // rk4's stability bound: h kt |vr|/FC < 2.8, some 7000 steps a period here.
    let rk4 = [
        Knob::Steps(7_500),
        Knob::Steps(15_000),
        Knob::Steps(240_000),
    ];
    converges(m, &stiff, run, "rk4", rk4);
    for solver in ["dopri5", "radau5", "closed_form"] {
        converges(m, &stiff, run, solver, [tol(1e-5), tol(1e-7), tol(1e-11)]);
    }
}

/// Scene T at kt x 1000 from steady sliding: FFx_mean over the second period.
#[test]
fn transverse_solvers_converge_at_kt_x1000() {
    let stiff = [
        ("initial", Value::Item("sliding")),
        ("kt", Value::Real(6.286e10)),
    ];
    let run = (1.0 / 3000.0 / 20.0, 40, "FFx_mean");
    let tol = |x| Knob::Tolerance("tolerance", x);
    let m = "TransverseFriction";
    for solver in stability::solvers(m) {
        let knobs = match solver {
            "dopri5" | "radau5" | "dop853" => [tol(1e-5), tol(1e-7), tol(1e-10)],
            // The explicit schemes' bound: h kt |v|/FC < 2.8, some 16000 steps a period.
            "rk4" | "two_phase" => [
                Knob::Steps(32_000),
                Knob::Steps(64_000),
                Knob::Steps(512_000),
            ],
            _ => [Knob::Steps(64), Knob::Steps(128), Knob::Steps(4096)],
        };
        converges(m, &stiff, run, solver, knobs);
    }
}

/// Scene O with the trigonometric law narrowed to D = 1e-3 (slope h pi/(2D) = 2500):
/// u_amplitude over the third forcing period.
#[test]
fn oscillator_solvers_converge_at_narrow_regularisation() {
    let stiff = [
        ("law", Value::Item("trigonometric")),
        ("D", Value::Real(1e-3)),
    ];
    let run = (std::f64::consts::TAU / 50.0, 150, "u_amplitude");
    let tol = |x| Knob::Tolerance("rtol", x);
    let m = "DryFrictionOscillator";
    for solver in stability::solvers(m) {
        let knobs = match solver {
            "rk4" => [
                Knob::Steps(8_000),
                Knob::Steps(16_000),
                Knob::Steps(256_000),
            ],
            _ => [tol(1e-6), tol(1e-8), tol(1e-12)],
        };
        converges(m, &stiff, run, solver, knobs);
    }
}

/// Oracle, scene L with Coulomb friction: the dissipated energy is FC times the distance slid,
/// FC integral |vr| dt; over whole periods of vr = vc + va cos(wt) (|vc| < va) the mean of |vr| is
/// vc (2 theta0/pi - 1) + (2 va/pi) sin(theta0), theta0 = acos(-vc/va) (vr < 0 on
/// theta0 < wt < 2 pi - theta0). The scheme's midpoint rule is within 1e-6 of it at 2000 steps.
#[test]
fn coulomb_dissipates_fc_times_the_distance_slid() {
    let (vc, va, f, periods) = (0.146, 0.264, 60e3, 3);
    let params = [
        ("law", Value::Item("coulomb")),
        ("vc", Value::Real(vc)),
        ("va", Value::Real(va)),
        ("f", Value::Real(f)),
    ];
    let w_diss = final_output(
        "LongitudinalFriction",
        &params,
        1.0 / f / 20.0,
        20 * periods,
        "W_diss",
    );
    let fc = 0.1 * 0.02 * 9.81;
    let theta0 = (-vc / va).acos();
    let mean_speed = vc * (2.0 * theta0 / std::f64::consts::PI - 1.0)
        + 2.0 * va / std::f64::consts::PI * theta0.sin();
    let exact = fc * mean_speed * f64::from(periods) / f;
    assert!((w_diss / exact - 1.0).abs() < 1e-6, "{w_diss} vs {exact}");
}

/// Oracle, scene T in steady sliding without vibration (va = 0, started on the steady state):
/// the contact dissipates FC vd per second (vd far above vs, so the Stribeck excess is gone).
#[test]
fn steady_sliding_dissipates_fc_times_vd() {
    let (vd, f, periods) = (5e-4, 3000.0, 10);
    let m = "TransverseFriction";
    for solver in stability::solvers(m) {
        let params = [
            ("initial", Value::Item("sliding")),
            ("va", Value::Real(0.0)),
            ("vd", Value::Real(vd)),
            ("solver", Value::Item(solver)),
        ];
        let w_diss = final_output(m, &params, 1.0 / f, periods, "W_diss");
        let fc = 0.178 * 0.56 * 9.81;
        let exact = fc * vd * f64::from(periods) / f;
        assert!(
            (w_diss / exact - 1.0).abs() < 1e-6,
            "{solver}: {w_diss} vs {exact}"
        );
    }
}

/// Far from t = 0 a double's resolution of time passes the tolerance of the period readings:
/// the first step there returns fmi2Warning, saying so, and later steps fmi2OK; a run near 0
/// says nothing. LongitudinalFriction at 60 kHz: at 1e5 s time is resolved to 2e-11 s, 1.3e-6
/// of a period, above the default tolerance.
#[test]
fn a_clock_too_coarse_for_the_tolerance_is_said_once() {
    let table = model("LongitudinalFriction").unwrap().table;
    let step = table.default_experiment.step_size;
    for (start, expected) in [(0.0, Status::Ok), (1e5, Status::Warning)] {
        let mut fmu = ImportedInstance::new("LongitudinalFriction", "clock").unwrap();
        assert_eq!(fmu.setup_experiment(None, start, None), Status::Ok);
        assert_eq!(fmu.enter_initialization_mode(), Status::Ok);
        assert_eq!(fmu.exit_initialization_mode(), Status::Ok);
        let first = fmu.do_step(start, step, true);
        assert_eq!(first, expected, "from {start}: {}", fmu.last_message());
        if expected == Status::Warning {
            assert!(
                fmu.last_message().contains("a double resolves time to"),
                "{}",
                fmu.last_message()
            );
        }
        let second = fmu.do_step(start + step, step, true);
        assert_eq!(second, Status::Ok, "from {start}: {}", fmu.last_message());
    }
}
