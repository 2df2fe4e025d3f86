//! Instances are independent: four instances of each model, with different parameters, stepped
//! concurrently from four threads (in lockstep, so their calls really overlap) give bit-identical
//! outputs to the same instances run one after another on one thread.
//!
//! Oracle: the sequential run. Anything shared between instances (a global, a cache, the list of
//! live instances, the logger) that leaks one instance's data into another, or a data race,
//! shows up as a differing bit.
#![cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]

use friction_fmu::fmi2::ffi::Status;
use friction_fmu::importer::ImportedInstance;
use friction_fmu::models::{
    drive::table as drive, longitudinal::table as longitudinal, oscillator::table as oscillator,
    transverse::table as transverse, MODELS,
};
use friction_fmu::variables::variable::{Causality, Kind, ModelTable};
use std::sync::Barrier;

const THREADS: usize = 4;
const STEPS: usize = 60;
/// After this step each instance takes its state, runs on, and rolls back to it once, so that
/// FMU states are exercised concurrently too.
const ROLLBACK_AT: usize = 20;

/// One parameter per model, set differently in each of the four instances.
fn varied_parameter(table: &ModelTable, index: usize) -> (u32, f64) {
    let k = index as f64;
    match table.model_identifier {
        "LongitudinalFriction" => (longitudinal::vr::VC, 0.1 + 0.05 * k),
        "TransverseFriction" => (transverse::vr::VD, 0.02 + 0.01 * k),
        "DryFrictionOscillator" => (oscillator::vr::P, 2.0 + 1.5 * k),
        "DriveTrain" => (drive::vr::V, 1.0 + 0.5 * k),
        other => panic!("no varied parameter for {other}: add one here"),
    }
}

fn outputs(table: &ModelTable) -> Vec<u32> {
    table
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output && matches!(v.kind, Kind::Real { .. }))
        .map(|v| v.value_reference)
        .collect()
}

/// An initialised instance of `table`'s model with its varied parameter set for `index`.
fn start(table: &ModelTable, index: usize) -> ImportedInstance {
    let mut instance = ImportedInstance::new(table.model_identifier, &format!("thread{index}"))
        .unwrap_or_else(|log| panic!("{}: instantiate: {log:?}", table.model_identifier));
    let (vr, value) = varied_parameter(table, index);
    assert_eq!(instance.set_real(&[vr], &[value]), Status::Ok);
    assert_eq!(
        instance.initialize(),
        Status::Ok,
        "{}",
        instance.last_message()
    );
    instance
}

/// Runs `instance` step by step; `between_steps` is called after each step (a barrier in the
/// concurrent run). Returns the bits of every output after every step.
fn run(
    table: &ModelTable,
    instance: &mut ImportedInstance,
    mut between_steps: impl FnMut(),
) -> Vec<Vec<u64>> {
    let vrs = outputs(table);
    let h = table.default_experiment.step_size;
    let mut values = vec![0.0; vrs.len()];
    let mut trace = Vec::new();
    let mut t = 0.0;
    let mut step = 0;
    let mut saved = None;
    while step < STEPS {
        let status = instance.do_step(t, h, false);
        assert_eq!(status, Status::Ok, "{}", instance.last_message());
        t += h;
        step += 1;
        assert_eq!(instance.get_real_into(&vrs, &mut values), Status::Ok);
        trace.push(values.iter().map(|x| x.to_bits()).collect());
        between_steps();
        if step == ROLLBACK_AT && saved.is_none() {
            saved = Some((instance.get_fmu_state().expect("get state"), t, trace.len()));
        }
        if step == 2 * ROLLBACK_AT {
            if let Some((mut state, t_saved, len)) = saved.take() {
                assert_eq!(instance.set_fmu_state(state), Status::Ok);
                assert_eq!(instance.free_fmu_state(&mut state), Status::Ok);
                // The rerun must retrace the steps taken after the snapshot exactly.
                let replay = trace.split_off(len);
                let (mut t2, mut again) = (t_saved, Vec::new());
                for _ in 0..replay.len() {
                    assert_eq!(instance.do_step(t2, h, false), Status::Ok);
                    t2 += h;
                    assert_eq!(instance.get_real_into(&vrs, &mut values), Status::Ok);
                    again.push(values.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
                }
                assert_eq!(again, replay, "{}: rollback", table.model_identifier);
                trace.extend(again);
                t = t2;
            }
        }
    }
    trace
}

#[test]
fn concurrent_instances_match_sequential_runs_bit_for_bit() {
    // One by one: each instance from start to end before the next is created.
    let mut sequential = Vec::new();
    for index in 0..THREADS {
        let mut per_model = Vec::new();
        for table in MODELS.iter().map(|m| m.table) {
            let mut instance = start(table, index);
            per_model.push(run(table, &mut instance, || {}));
        }
        sequential.push(per_model);
    }

    // Concurrently: thread `index` owns instance `index` of every model and steps them
    // alternately; all threads pass a barrier after every step.
    let barrier = Barrier::new(THREADS);
    let concurrent: Vec<Vec<Vec<Vec<u64>>>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..THREADS)
            .map(|index| {
                let barrier = &barrier;
                scope.spawn(move || {
                    MODELS
                        .iter()
                        .map(|m| m.table)
                        .map(|table| {
                            let mut instance = start(table, index);
                            run(table, &mut instance, || {
                                barrier.wait();
                            })
                        })
                        .collect()
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a stepping thread panicked"))
            .collect()
    });

    for index in 0..THREADS {
        for (m, table) in MODELS.iter().map(|m| m.table).enumerate() {
            assert_eq!(sequential[index][m].len(), STEPS);
            assert!(
                concurrent[index][m] == sequential[index][m],
                "{} instance {index}: concurrent outputs differ from the sequential run",
                table.model_identifier
            );
        }
    }
    // The varied parameter must matter, or the comparison above could not tell instances apart.
    for (m, table) in MODELS.iter().map(|m| m.table).enumerate() {
        assert_ne!(
            sequential[0][m], sequential[1][m],
            "{}: instances 0 and 1 gave equal outputs",
            table.model_identifier
        );
    }
}
