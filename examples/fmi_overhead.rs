//! What the FMI layer costs per doStep: each model at its defaults is advanced over the same
//! interval (a) through the exported fmi2DoStep (in-process, src/importer.rs) in
//! communication steps of 1e-5 s, (b) by calling the scene directly with the same steps, and
//! (c) by calling the scene once per vibration (forcing) period (or once, for a shorter interval). (a) - (b) is the FMI layer per
//! call; (b) - (c) is what restarting the integrator at every communication point costs.
//!
//!   cargo run --release --example fmi_overhead [SECONDS]     (simulated time, default 0.05 s)

use friction_fmu::fmi2::ffi::Status;
use friction_fmu::importer::Instance;
use friction_fmu::interface::values::ValueSet;
use friction_fmu::scenes::{Model, Scope, MODELS};
use std::time::Instant;

const STEP: f64 = 1e-5;
const REPEATS: usize = 3;

/// The natural period of each model's excitation (s), read from its defaults.
fn period(model: &Model, values: &ValueSet) -> f64 {
    let table = model.table;
    let real = |name: &str| table.by_name(name).map(|v| values.real(v.value_reference));
    match (real("f"), real("w")) {
        (Some(f), _) => 1.0 / f,
        (None, Some(w)) => std::f64::consts::TAU / w,
        _ => STEP,
    }
}

/// The fastest of REPEATS runs of `run`, in seconds.
fn best(mut run: impl FnMut() -> Result<(), String>) -> Result<f64, String> {
    let mut fastest = f64::INFINITY;
    for _ in 0..REPEATS {
        let started = Instant::now();
        run()?;
        fastest = fastest.min(started.elapsed().as_secs_f64());
    }
    Ok(fastest)
}

fn measure(model: &Model, seconds: f64) -> Result<(), String> {
    let id = model.table.model_identifier;
    let values = ValueSet::start(model.table);
    let steps = (seconds / STEP).round() as u64;
    let through_fmi = best(|| {
        let mut fmu = Instance::new(id, "overhead").map_err(|log| format!("{log:?}"))?;
        if fmu.initialize() != Status::Ok {
            return Err(format!("{id}: initialisation: {}", fmu.last_message()));
        }
        for k in 0..steps {
            let t = k as f64 * STEP;
            if fmu.do_step(t, (k + 1) as f64 * STEP - t, true) != Status::Ok {
                return Err(format!("{id}: fmi2DoStep at {t}: {}", fmu.last_message()));
            }
        }
        Ok(())
    })?;
    let direct = |h: f64| {
        best(|| {
            let mut scene = (model.build)(&values, 0.0, &Scope::full())?;
            let n = (seconds / h).round() as u64;
            for k in 0..n {
                scene.do_step((k + 1) as f64 * h - scene.time(), &values)?;
            }
            Ok(())
        })
    };
    let same_steps = direct(STEP)?;
    let per_period = direct(period(model, &values).min(seconds))?;
    let n = steps as f64;
    println!(
        "| {id} | {steps} | {:.3} | {:.3} | {:.3} | {:.0} | {:.0} |",
        through_fmi * 1e3,
        same_steps * 1e3,
        per_period * 1e3,
        (through_fmi - same_steps) / n * 1e9,
        (same_steps - per_period) / n * 1e9,
    );
    Ok(())
}

fn main() -> std::process::ExitCode {
    let seconds = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.05);
    println!("Simulated {seconds} s at each model's defaults; communication step {STEP} s; fastest of {REPEATS} runs.\n");
    println!("| model | doSteps | fmi2DoStep (ms) | scene, same steps (ms) | scene, one call per period (ms) | FMI layer per doStep (ns) | integrator restart per doStep (ns) |");
    println!("|---|---|---|---|---|---|---|");
    for model in MODELS {
        if let Err(e) = measure(model, seconds) {
            eprintln!("fmi_overhead: {e}");
            return std::process::ExitCode::FAILURE;
        }
    }
    std::process::ExitCode::SUCCESS
}
