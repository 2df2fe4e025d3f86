//! What restoring an FMU state costs against sliding on: each model at its defaults, and each
//! scene with a periodic start also at `initial = periodic`, steps to t = 1 ms, takes a state,
//! and then, CALLS times, either
//!
//! - (a) steps on by H, or
//! - (b) sets the state back and steps by H (a master retrying a step),
//!
//! in CPU time of the running thread per call, the median of RUNS runs taken in turn.
//!
//!   cargo run --release --example state_restore [CALLS]          (default 2000)

use friction_fmu::cpu_clock::time_cpu;
use friction_fmu::fmi2::ffi::Status;
use friction_fmu::importer::{ImportedInstance, Instantiation};
use friction_fmu::models::{Model, MODELS};
use friction_fmu::variables::variable::Kind;

const H: f64 = 1e-5;
const RUNS: usize = 11;
const WARM_UP: f64 = 1e-3;

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// The value reference and code of `initial = periodic`, where the model has that item.
fn periodic(model: &Model) -> Option<(u32, i32)> {
    let var = model.table.by_name("initial")?;
    let Kind::Switch { type_name, .. } = var.kind else {
        return None;
    };
    let items = model.table.enum_type(type_name)?;
    let code = (1..=8).find(|&code| items.item(code) == Some("periodic"))?;
    Some((var.value_reference, code))
}

/// An instance of `model` at its defaults and `setting`, stepped to WARM_UP.
fn started(model: &Model, setting: Option<(u32, i32)>) -> ImportedInstance {
    let id = model.table.model_identifier;
    let arguments = Instantiation::new(id, "restore").expect("a model of this crate");
    let mut instance = ImportedInstance::instantiate(&arguments).expect("instantiates");
    if let Some((vr, code)) = setting {
        assert_eq!(instance.set_integer(&[vr], &[code]), Status::Ok, "{id}");
    }
    assert_eq!(instance.initialize(), Status::Ok, "{id}: initialization");
    let mut t = 0.0;
    while t < WARM_UP - 1e-12 {
        assert!(instance.do_step(t, H, true) <= Status::Warning, "{id}");
        t += H;
    }
    instance
}

fn main() {
    let calls: usize = std::env::args()
        .nth(1)
        .map_or(2000, |n| n.parse().expect("CALLS is a count"));
    println!("| model | start | (a) step on (us) | (b) restore + step (us) | (b) / (a) |");
    println!("|---|---|---|---|---|");
    let cases = MODELS.iter().flat_map(|model| {
        let with_periodic = periodic(model).map(|setting| (model, Some(setting)));
        [(model, None)].into_iter().chain(with_periodic)
    });
    for (model, setting) in cases {
        let id = model.table.model_identifier;
        let start = if setting.is_some() {
            "periodic"
        } else {
            "default"
        };
        let mut sliding = started(model, setting);
        let mut restoring = started(model, setting);
        let state = restoring.get_fmu_state().expect("a state");
        let t0 = WARM_UP;
        let (mut on, mut back) = (Vec::new(), Vec::new());
        let mut t = t0;
        for _ in 0..RUNS {
            let (_, seconds) = time_cpu(|| {
                for _ in 0..calls {
                    sliding.do_step(t, H, true);
                    t += H;
                }
            });
            on.push(seconds / calls as f64);
            let (_, seconds) = time_cpu(|| {
                for _ in 0..calls {
                    restoring.set_fmu_state(state);
                    restoring.do_step(t0, H, false);
                }
            });
            back.push(seconds / calls as f64);
        }
        let (a, b) = (median(on) * 1e6, median(back) * 1e6);
        println!("| {id} | {start} | {a:.2} | {b:.2} | {:.2} |", b / a);
    }
}
