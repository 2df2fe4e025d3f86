//! Every model's default experiment with each of its solvers, laws and initial states, and every shipped
//! variant's with each solver of its model, pinned to the bit: a hash of every output after
//! every communication step, run as fmi2DoStep runs a simulation (a step read inside one taken
//! before, else a saved state and a step), with the state saved half-way, handed to a simulation
//! built again from the same values and restored there, as fmi2SetFMUstate does. The pins,
//! `pinned_runs.txt`, were written by the code before the solvers were put behind one stepping
//! interface; a change to how the models step that is meant to change no number keeps them.
//!
//! `PINNED_RUNS_WRITE=1 cargo test --profile testing --lib pinned_runs` writes the file anew
//! (only for a change that is meant to change the numbers).

use super::{Model, Scope, Simulation, MODELS};
use crate::solve::Work;
use crate::variables::values::ValueSet;
use crate::variables::variable::{Causality, Kind, ModelTable};
use std::path::Path;

/// One run: what it is, and the experiment's start, stop and communication step.
struct Run {
    name: String,
    model: &'static Model,
    values: ValueSet,
    scope: Scope,
    experiment: (f64, f64, f64),
}

/// FNV-1a over 64-bit words: a stable hash (std's hashers may change between releases).
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn word(&mut self, x: u64) {
        for byte in x.to_le_bytes() {
            self.0 ^= u64::from(byte);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn text(&mut self, s: &str) {
        for byte in s.bytes() {
            self.word(u64::from(byte));
        }
    }
}

/// The item names of the switch parameter `name` of `table`, with the variable's reference.
fn items(table: &ModelTable, name: &str) -> Option<(u32, Vec<&'static str>)> {
    let variable = table.variables.iter().find(|v| v.name == name)?;
    let Kind::Switch { type_name, .. } = variable.kind else {
        return None;
    };
    let enum_type = table.enum_types.iter().find(|t| t.name == type_name)?;
    Some((
        variable.value_reference,
        enum_type.items.iter().map(|(item, _)| *item).collect(),
    ))
}

/// Sets the switch `(value_reference, items)` to `item`.
fn select(values: &mut ValueSet, (value_reference, items): &(u32, Vec<&str>), item: &str) {
    let number = items.iter().position(|i| *i == item).unwrap() + 1;
    values.set(*value_reference, number as f64);
}

fn runs() -> Vec<Run> {
    let mut runs = Vec::new();
    for model in MODELS {
        let table = model.table;
        let solvers = items(table, "solver").expect("every model has a solver switch");
        let laws = table.law_parameter.and_then(|law| items(table, law));
        let law_items = laws.as_ref().map_or(vec![""], |(_, items)| items.clone());
        let initials = items(table, "initial");
        let initial_items = initials
            .as_ref()
            .map_or(vec![""], |(_, items)| items.clone());
        let e = table.default_experiment;
        for solver in &solvers.1 {
            for law in &law_items {
                for initial in &initial_items {
                    let mut values = ValueSet::start(table);
                    select(&mut values, &solvers, solver);
                    if let Some(laws) = &laws {
                        select(&mut values, laws, law);
                    }
                    if let Some(initials) = &initials {
                        select(&mut values, initials, initial);
                    }
                    runs.push(Run {
                        name: format!("{} {solver} {law} {initial}", table.model_identifier),
                        model,
                        values,
                        scope: Scope::full(),
                        experiment: (e.start_time, e.stop_time, e.step_size),
                    });
                }
            }
        }
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("variants");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    for file in files {
        let variant = crate::variant::read(&file).unwrap();
        let solvers = items(variant.model.table, "solver").unwrap();
        let e = variant.experiment;
        for solver in &solvers.1 {
            let mut values = variant.values.clone();
            select(&mut values, &solvers, solver);
            runs.push(Run {
                name: format!("{} {solver}", variant.name),
                model: variant.model,
                values,
                scope: variant.scope(),
                experiment: (e.start, e.stop, e.step),
            });
        }
    }
    runs
}

/// The run's pin: the hash of every output after every step, or of the error that stopped it,
/// the hash of the state saved half-way, and the work (steps, rejected steps, right-hand sides)
/// of the models that count it.
fn pin(run: &Run) -> String {
    use super::{longitudinal::Longitudinal, oscillator::Oscillator, transverse::Transverse};
    let (values, start, scope) = (&run.values, run.experiment.0, &run.scope);
    match run.model.table.model_identifier {
        "LongitudinalFriction" => pin_with(
            run,
            || Longitudinal::with_scope(values, start, scope).map(Box::new),
            |s| Some(s.work),
        ),
        "TransverseFriction" => pin_with(
            run,
            || Transverse::with_scope(values, start, scope).map(Box::new),
            |s| Some(s.work),
        ),
        "DryFrictionOscillator" => pin_with(
            run,
            || Oscillator::with_scope(values, start, scope).map(Box::new),
            |s| Some(s.work),
        ),
        _ => pin_with(run, || (run.model.build)(values, start, scope), |_| None),
    }
}

fn pin_with<S: Simulation + ?Sized, B: std::ops::DerefMut<Target = S>>(
    run: &Run,
    build: impl Fn() -> Result<B, crate::error::Error>,
    work: impl Fn(&S) -> Option<Work>,
) -> String {
    let outputs: Vec<u32> = run
        .model
        .table
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output && matches!(v.kind, Kind::Real { .. }))
        .map(|v| v.value_reference)
        .collect();
    let mut sim = match build() {
        Ok(sim) => sim,
        Err(message) => {
            let mut hash = Fnv::new();
            hash.text(&message.to_string());
            return format!("build-error {:016x}", hash.0);
        }
    };
    let (start, stop, step) = run.experiment;
    let n = ((stop - start) / step).round() as usize;
    let t = |k: usize| start + (stop - start) * k as f64 / n as f64;
    let mut values = run.values.clone();
    let mut outputs_hash = Fnv::new();
    let mut saved_hash = Fnv::new();
    let mut rollback = Vec::new();
    let mut work_before = Work::default();
    let work_text = |sim: &S, before: &Work| {
        work(sim).map_or(String::new(), |w| {
            let w = w.plus(before);
            format!(" {} {} {}", w.steps, w.rejected, w.rhs_evaluations)
        })
    };
    for k in 0..n {
        if k == n / 2 {
            let saved = sim.save();
            for x in &saved {
                saved_hash.word(x.to_bits());
            }
            work_before = work(&sim).unwrap_or_default();
            sim = build().unwrap();
            sim.restore(&saved).unwrap();
        }
        let h = t(k + 1) - sim.time();
        let result = if sim.read_inside(h) {
            Ok(())
        } else {
            sim.save_into(&mut rollback);
            sim.do_step(h, &values)
        };
        if let Err(message) = result {
            outputs_hash.text(&message.to_string());
            return format!(
                "step-{k}-error {:016x} {:016x}{}",
                outputs_hash.0,
                saved_hash.0,
                work_text(&sim, &work_before)
            );
        }
        sim.write_outputs(&mut values);
        for &vr in &outputs {
            outputs_hash.word(values.real(vr).to_bits());
        }
    }
    format!(
        "{:016x} {:016x}{}",
        outputs_hash.0,
        saved_hash.0,
        work_text(&sim, &work_before)
    )
}

const PINS: &str = "src/models/pinned_runs.txt";

#[test]
fn every_model_and_variant_run_gives_its_pinned_bits() {
    let runs = runs();
    let lines: Vec<String> = std::thread::scope(|s| {
        let handles: Vec<_> = runs
            .iter()
            .map(|run| s.spawn(move || format!("{}: {}", run.name, pin(run))))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(PINS);
    if std::env::var_os("PINNED_RUNS_WRITE").is_some() {
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        return;
    }
    let pinned = std::fs::read_to_string(&path).unwrap();
    let pinned: Vec<&str> = pinned.lines().collect();
    let changed: Vec<String> = lines
        .iter()
        .zip(&pinned)
        .filter(|(now, then)| now != *then)
        .map(|(now, then)| format!("now {now}\nwas {then}"))
        .collect();
    assert!(
        changed.is_empty() && lines.len() == pinned.len(),
        "{} of {} runs changed ({} pinned):\n{}",
        changed.len(),
        lines.len(),
        pinned.len(),
        changed.join("\n")
    );
}
