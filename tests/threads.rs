//! Instances are independent: four instances of each model, with different parameters, stepped
//! concurrently from four threads (in lockstep, so their calls really overlap) give bit-identical
//! outputs to the same instances run one after another on one thread; so do FMI 3.0 instances
//! stepped concurrently beside them (the same core behind the other standard's boundary).
//!
//! Oracle: the sequential FMI 2.0 run. Anything shared between instances (a global, a cache, the
//! list of live instances, the logger) that leaks one instance's data into another, or a data
//! race, shows up as a differing bit.
#![cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]

use friction_fmu::fmi2::ffi::Status;
use friction_fmu::fmi3::ffi::Status as Status3;
use friction_fmu::importer::{fmi3, ImportedInstance, State};
use friction_fmu::models::{
    drive::table as drive, longitudinal::table as longitudinal, oscillator::table as oscillator,
    transverse::table as transverse, MODELS,
};
use friction_fmu::variables::variable::{Causality, Kind, ModelTable};
use std::sync::Barrier;

/// The calls `run` makes, through either standard's driver; each panics on a non-OK status.
trait Fmu {
    fn set_parameter(&mut self, vr: u32, value: f64);
    fn initialize(&mut self);
    fn do_step(&mut self, t: f64, h: f64);
    fn outputs(&mut self, vrs: &[u32], values: &mut [f64]);
    fn get_state(&mut self) -> State;
    /// Restores the state and frees it.
    fn restore(&mut self, state: State);
}

impl Fmu for ImportedInstance {
    fn set_parameter(&mut self, vr: u32, value: f64) {
        assert_eq!(self.set_real(&[vr], &[value]), Status::Ok);
    }
    fn initialize(&mut self) {
        let status = ImportedInstance::initialize(self);
        assert_eq!(status, Status::Ok, "{}", self.last_message());
    }
    fn do_step(&mut self, t: f64, h: f64) {
        let status = ImportedInstance::do_step(self, t, h, false);
        assert_eq!(status, Status::Ok, "{}", self.last_message());
    }
    fn outputs(&mut self, vrs: &[u32], values: &mut [f64]) {
        assert_eq!(self.get_real_into(vrs, values), Status::Ok);
    }
    fn get_state(&mut self) -> State {
        self.get_fmu_state().expect("get state")
    }
    fn restore(&mut self, mut state: State) {
        assert_eq!(self.set_fmu_state(state), Status::Ok);
        assert_eq!(self.free_fmu_state(&mut state), Status::Ok);
    }
}

impl Fmu for fmi3::ImportedInstance {
    fn set_parameter(&mut self, vr: u32, value: f64) {
        assert_eq!(self.set_float64(&[vr], &[value]), Status3::Ok);
    }
    fn initialize(&mut self) {
        let status = fmi3::ImportedInstance::initialize(self);
        assert_eq!(status, Status3::Ok, "{}", self.last_message());
    }
    fn do_step(&mut self, t: f64, h: f64) {
        let (status, outcome) = fmi3::ImportedInstance::do_step(self, t, h, false);
        assert_eq!(status, Status3::Ok, "{}", self.last_message());
        assert_eq!(outcome.last_successful_time, t + h);
    }
    fn outputs(&mut self, vrs: &[u32], values: &mut [f64]) {
        assert_eq!(self.get_float64_into(vrs, values), Status3::Ok);
    }
    fn get_state(&mut self) -> State {
        self.get_fmu_state().expect("get state")
    }
    fn restore(&mut self, mut state: State) {
        assert_eq!(self.set_fmu_state(state), Status3::Ok);
        assert_eq!(self.free_fmu_state(&mut state), Status3::Ok);
    }
}

/// Which standard's boundary an instance is driven through.
#[derive(Clone, Copy, Debug)]
enum Standard {
    Fmi2,
    Fmi3,
}

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
fn start(table: &ModelTable, index: usize, standard: Standard) -> Box<dyn Fmu> {
    let name = format!("thread{index}");
    let id = table.model_identifier;
    let mut instance: Box<dyn Fmu> = match standard {
        Standard::Fmi2 => Box::new(
            ImportedInstance::new(id, &name)
                .unwrap_or_else(|log| panic!("{id}: instantiate: {log:?}")),
        ),
        Standard::Fmi3 => Box::new(
            fmi3::ImportedInstance::new(id, &name)
                .unwrap_or_else(|log| panic!("{id}: instantiate: {log:?}")),
        ),
    };
    let (vr, value) = varied_parameter(table, index);
    instance.set_parameter(vr, value);
    instance.initialize();
    instance
}

/// The bits of every output after every step.
type Trace = Vec<Vec<u64>>;

/// Runs `instance` step by step; `between_steps` is called after each step (a barrier in the
/// concurrent run). Returns the bits of every output after every step.
fn run(table: &ModelTable, instance: &mut dyn Fmu, mut between_steps: impl FnMut()) -> Trace {
    let vrs = outputs(table);
    let h = table.default_experiment.step_size;
    let mut values = vec![0.0; vrs.len()];
    let mut trace = Vec::new();
    let mut t = 0.0;
    let mut step = 0;
    let mut saved = None;
    while step < STEPS {
        instance.do_step(t, h);
        t += h;
        step += 1;
        instance.outputs(&vrs, &mut values);
        trace.push(values.iter().map(|x| x.to_bits()).collect());
        between_steps();
        if step == ROLLBACK_AT && saved.is_none() {
            saved = Some((instance.get_state(), t, trace.len()));
        }
        if step == 2 * ROLLBACK_AT {
            if let Some((state, t_saved, len)) = saved.take() {
                instance.restore(state);
                // The rerun must retrace the steps taken after the snapshot exactly.
                let replay = trace.split_off(len);
                let (mut t2, mut again) = (t_saved, Vec::new());
                for _ in 0..replay.len() {
                    instance.do_step(t2, h);
                    t2 += h;
                    instance.outputs(&vrs, &mut values);
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
    // One by one, through FMI 2.0: each instance from start to end before the next is created.
    let mut sequential = Vec::new();
    for index in 0..THREADS {
        let mut per_model = Vec::new();
        for table in MODELS.iter().map(|m| m.table) {
            let mut instance = start(table, index, Standard::Fmi2);
            per_model.push(run(table, &mut *instance, || {}));
        }
        sequential.push(per_model);
    }

    // Concurrently: thread `index` owns instance `index` of every model in both standards and
    // runs them one after another, the even threads FMI 2.0 first, the odd ones FMI 3.0 first,
    // so that both standards' calls overlap; all threads pass a barrier after every step.
    let barrier = Barrier::new(THREADS);
    let concurrent: Vec<Vec<Vec<(Standard, Trace)>>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..THREADS)
            .map(|index| {
                let barrier = &barrier;
                let order = if index % 2 == 0 {
                    [Standard::Fmi2, Standard::Fmi3]
                } else {
                    [Standard::Fmi3, Standard::Fmi2]
                };
                scope.spawn(move || {
                    MODELS
                        .iter()
                        .map(|m| m.table)
                        .map(|table| {
                            order
                                .iter()
                                .map(|&standard| {
                                    let mut instance = start(table, index, standard);
                                    let trace = run(table, &mut *instance, || {
                                        barrier.wait();
                                    });
                                    (standard, trace)
                                })
                                .collect()
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
            for (standard, trace) in &concurrent[index][m] {
                assert!(
                    *trace == sequential[index][m],
                    "{} instance {index} ({standard:?}): concurrent outputs differ from the sequential run",
                    table.model_identifier
                );
            }
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
