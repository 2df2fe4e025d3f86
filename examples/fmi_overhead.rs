//! What one fmi2DoStep costs at small communication steps, in CPU time of the running thread.
//! Each model at its defaults is advanced by CALLS communication steps of h from t = 0 (the
//! master's points t = i h), for h = 1e-6 s and 1e-5 s:
//!
//! - (a) through the exported fmi2DoStep, in-process (src/importer.rs), outputs not read;
//! - (b) the same, then fmi2GetReal of every output after each step;
//! - (c) by calling the simulation directly with the same steps;
//! - (d) by calling the simulation once per vibration (forcing) period over the same interval
//!   (once, for a model without one or an interval shorter than it).
//!
//! (a) - (c) is the FMI layer per call; (c) - (d) what restarting the integrator at every
//! communication point costs; (d) / CALLS the integration itself. Each figure is the median of
//! RUNS runs, the cases taking turns, and each difference the median of its runs' differences:
//! short runs taken in turn and paired keep the drift of a shared machine's speed out of them.
//!
//!   cargo run --release --example fmi_overhead [CALLS]          (default 5000)
//!   cargo run --release --example fmi_overhead -- --only MODEL [H] [CALLS] [read] [NAME=VALUE...]
//!
//! The second form runs (a) alone for one model ((b) with `read`), for an instruction count
//! under `valgrind --tool=callgrind`, which repeats where the CPU time of a shared machine does
//! not; NAME=VALUE sets a parameter before initialisation (`tolerance=1e-8`, or a switch by its
//! item's name, `solver=dop853`).

use friction_fmu::cpu_clock::time_cpu;
use friction_fmu::fmi2::ffi::Status;
use friction_fmu::importer::ImportedInstance;
use friction_fmu::models::{Model, Scope, MODELS};
use friction_fmu::variables::values::ValueSet;
use friction_fmu::variables::variable::{Causality, Kind};

const STEPS: [f64; 2] = [1e-6, 1e-5];
const RUNS: usize = 11;

/// The natural period of each model's excitation (s), read from its defaults; infinite for a
/// model without one.
fn period(model: &Model, values: &ValueSet) -> f64 {
    let table = model.table;
    let real = |name: &str| table.by_name(name).map(|v| values.real(v.value_reference));
    match (real("f"), real("w")) {
        (Some(f), _) => 1.0 / f,
        (None, Some(w)) => std::f64::consts::TAU / w,
        _ => f64::INFINITY,
    }
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// A parameter's value set before initialisation.
enum Setting {
    Real(u32, f64),
    Integer(u32, i32),
}

/// CPU seconds of `calls` fmi2DoSteps of `step` through the FMI layer, reading every output
/// after each when `read` is set, with `settings` made before initialisation.
fn through_fmi(
    model: &Model,
    step: f64,
    calls: u64,
    read: bool,
    settings: &[Setting],
) -> Result<f64, String> {
    let id = model.table.model_identifier;
    let mut fmu = ImportedInstance::new(id, "overhead").map_err(|log| format!("{id}: {log:?}"))?;
    for setting in settings {
        let status = match *setting {
            Setting::Real(vr, value) => fmu.set_real(&[vr], &[value]),
            Setting::Integer(vr, value) => fmu.set_integer(&[vr], &[value]),
        };
        if status != Status::Ok {
            return Err(format!("{id}: setting a parameter: {}", fmu.last_message()));
        }
    }
    if fmu.initialize() != Status::Ok {
        return Err(format!("{id}: initialisation: {}", fmu.last_message()));
    }
    let outputs: Vec<u32> = model
        .table
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| v.value_reference)
        .collect();
    let mut values = vec![0.0; outputs.len()];
    let (result, seconds) = time_cpu(|| {
        for k in 0..calls {
            let t = k as f64 * step;
            if fmu.do_step(t, (k + 1) as f64 * step - t, true) != Status::Ok {
                return Err(format!("{id}: fmi2DoStep at {t}: {}", fmu.last_message()));
            }
            if read && fmu.get_real_into(&outputs, &mut values) != Status::Ok {
                return Err(format!("{id}: fmi2GetReal at {t}: {}", fmu.last_message()));
            }
        }
        Ok(())
    });
    result.map(|()| seconds)
}

/// CPU seconds of the simulation advanced over `calls * step` in calls of `h` (the last one ending
/// on the interval's end).
fn direct(model: &Model, step: f64, calls: u64, h: f64) -> Result<f64, String> {
    let values = ValueSet::start(model.table);
    let mut sim = (model.build)(&values, 0.0, &Scope::full())?;
    let end = calls as f64 * step;
    let n = (end / h).round().max(1.0) as u64;
    let (result, seconds) = time_cpu(|| {
        for k in 0..n {
            let target = if k + 1 == n { end } else { (k + 1) as f64 * h };
            // As fmi2DoStep does: a call read inside a step already taken first.
            let h = target - sim.time();
            if !sim.read_inside(h) {
                sim.do_step(h, &values)?;
            }
        }
        Ok::<(), String>(())
    });
    result.map(|()| seconds)
}

fn measure(model: &Model, step: f64, calls: u64) -> Result<(), String> {
    let values = ValueSet::start(model.table);
    let per_period = period(model, &values).min(calls as f64 * step);
    let mut times: [Vec<f64>; 4] = Default::default();
    for _ in 0..RUNS {
        times[0].push(through_fmi(model, step, calls, false, &[])?);
        times[1].push(through_fmi(model, step, calls, true, &[])?);
        times[2].push(direct(model, step, calls, step)?);
        times[3].push(direct(model, step, calls, per_period)?);
    }
    let per_call = |t: &[f64]| median(t.to_vec()) / calls as f64 * 1e9;
    let difference =
        |a: &[f64], b: &[f64]| per_call(&a.iter().zip(b).map(|(a, b)| a - b).collect::<Vec<_>>());
    let [fmi, read, sim, whole] = &times;
    println!(
        "| {} | {step:e} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} |",
        model.table.model_identifier,
        per_call(fmi),
        per_call(read),
        per_call(sim),
        per_call(whole),
        difference(fmi, sim),
        difference(sim, whole),
    );
    Ok(())
}

/// `--only MODEL [H] [CALLS] [read]`: case (a) or (b) alone, for callgrind.
fn only(args: &[String]) -> Result<(), String> {
    let id = args.first().ok_or("--only needs a model identifier")?;
    let model = MODELS
        .iter()
        .find(|m| m.table.model_identifier == id)
        .ok_or_else(|| format!("no model {id}"))?;
    let step = args
        .get(1)
        .map_or(Ok(1e-6), |s| s.parse())
        .map_err(|e| format!("H: {e}"))?;
    let calls = args
        .get(2)
        .map_or(Ok(5000), |s| s.parse())
        .map_err(|e| format!("CALLS: {e}"))?;
    let rest = args.get(3..).unwrap_or_default();
    let read = rest.iter().any(|a| a == "read");
    let settings = rest
        .iter()
        .filter(|a| *a != "read")
        .map(|a| {
            let (name, value) = a
                .split_once('=')
                .ok_or(format!("{a}: expected NAME=VALUE"))?;
            let var = model
                .table
                .by_name(name)
                .ok_or_else(|| format!("{id} has no variable {name}"))?;
            let vr = var.value_reference;
            match var.kind {
                Kind::Real { .. } => value
                    .parse()
                    .map(|x| Setting::Real(vr, x))
                    .map_err(|e| format!("{a}: {e}")),
                Kind::Switch { type_name, .. } => model
                    .table
                    .enum_type(type_name)
                    .and_then(|t| t.value_of(value))
                    .map(|i| Setting::Integer(vr, i))
                    .ok_or_else(|| format!("{a}: no item {value} in {type_name}")),
                Kind::Integer { .. } => value
                    .parse()
                    .map(|i| Setting::Integer(vr, i))
                    .map_err(|e| format!("{a}: {e}")),
            }
        })
        .collect::<Result<Vec<Setting>, String>>()?;
    let seconds = through_fmi(model, step, calls, read, &settings)?;
    println!(
        "{id}: h = {step:e} s, {calls} calls, {:.0} ns of CPU a call",
        seconds / calls as f64 * 1e9
    );
    Ok(())
}

fn main() -> std::process::ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = if args.first().map(String::as_str) == Some("--only") {
        only(&args[1..])
    } else {
        let calls = args.first().and_then(|s| s.parse().ok()).unwrap_or(5000);
        println!("Each model at its defaults, {calls} communication steps of h from t = 0; CPU time of the thread per call (ns), median of {RUNS} runs.\n");
        println!("| model | h (s) | (a) fmi2DoStep | (b) fmi2DoStep + fmi2GetReal of every output | (c) simulation, same steps | (d) simulation, one call a period | FMI layer (a) - (c) | integrator restart (c) - (d) |");
        println!("|---|---|---|---|---|---|---|---|");
        STEPS.iter().try_for_each(|&step| {
            MODELS
                .iter()
                .try_for_each(|model| measure(model, step, calls))
        })
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fmi_overhead: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
