//! A co-simulation step never allocates: fmi2SetReal (inputs), fmi2SetRealInputDerivatives,
//! fmi2DoStep and fmi2GetReal (outputs), for every model and every solver, every variant's
//! trimmed FMU, inputs moving linearly over a step, and a master that changes its step size,
//! driven through the exported fmi2* functions in-process (src/importer.rs) with a
//! per-thread counting allocator around them; and the same master's fmi3SetFloat64, fmi3DoStep
//! and fmi3GetFloat64 through the FMI 3.0 boundary, for every model and solver.
//!
//! Oracle: the allocator's count; zero is the contract (src/solve/mod.rs: integrators keep their
//! scratch space inline). The first steps run before counting, so nothing lazily set up on the
//! first call (none is expected either) hides a per-step allocation or excuses one.
#![cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]

use friction_fmu::fmi2::ffi::Status;
use friction_fmu::fmi3::ffi::Status as Status3;
use friction_fmu::importer::{fmi3, ImportedInstance, Instantiation};
use friction_fmu::models::MODELS;
use friction_fmu::models::{drive::table as drive, transverse::table as transverse};
use friction_fmu::variables::variable::{Causality, Kind, ModelTable, Variable};
use friction_fmu::variant;
use std::path::Path;

mod fmi3_description;

/// The communication step of the FMI-overhead measurement (examples/fmi_overhead.rs).
const STEP: f64 = 1e-5;
/// Rounds counted per instance.
const ROUNDS: usize = 200;

/// What a master does each round besides setting inputs, stepping and reading outputs.
struct Master<'a> {
    /// Input value references and the values set every round.
    inputs: Vec<(u32, f64)>,
    /// First derivatives set (fmi2SetRealInputDerivatives) before every step, one per input.
    derivatives: Option<Vec<f64>>,
    /// Communication step sizes, used in turn.
    steps: &'a [f64],
}

/// The value references of the Real outputs among `variables`.
fn real_outputs(variables: &[&Variable]) -> Vec<u32> {
    variables
        .iter()
        .filter(|v| v.causality == Causality::Output && matches!(v.kind, Kind::Real { .. }))
        .map(|v| v.value_reference)
        .collect()
}

/// Runs `master` on an initialised instance: 10 rounds uncounted, then ROUNDS counted. Panics
/// if a call fails, an allocation happens while counting, or the outputs end non-finite.
fn assert_rounds_do_not_allocate(
    name: &str,
    fmu: &mut ImportedInstance,
    outputs: &[u32],
    master: &Master,
) {
    let (inputs, values): (Vec<u32>, Vec<f64>) = master.inputs.iter().copied().unzip();
    let orders = vec![1; inputs.len()];
    let mut out = vec![0.0; outputs.len()];
    let mut t = 0.0;
    let mut round = |fmu: &mut ImportedInstance, k: usize, t: &mut f64| {
        let h = master.steps[k % master.steps.len()];
        let set = fmu.set_real(&inputs, &values);
        let derivatives = match &master.derivatives {
            Some(d) => fmu.set_real_input_derivatives(&inputs, &orders, d),
            None => Status::Ok,
        };
        let step = fmu.do_step(*t, h, true);
        let get = fmu.get_real_into(outputs, &mut out);
        *t += h;
        set.max(derivatives).max(step).max(get)
    };
    for k in 0..10 {
        assert_eq!(
            round(fmu, k, &mut t),
            Status::Ok,
            "{name}: {:?}",
            fmu.messages()
        );
    }
    let mut statuses = [Status::Ok; ROUNDS];
    let info = allocation_counter::measure(|| {
        for (k, status) in statuses.iter_mut().enumerate() {
            *status = round(fmu, k, &mut t);
        }
    });
    assert!(
        statuses.iter().all(|s| *s == Status::Ok),
        "{name}: {statuses:?} {:?}",
        fmu.messages()
    );
    assert_eq!(
        info.count_total, 0,
        "{name}: {} allocations in {ROUNDS} rounds of a master's calls",
        info.count_total
    );
    // The steps did something: the outputs are finite and time has advanced.
    let mut values = vec![0.0; outputs.len()];
    assert_eq!(fmu.get_real_into(outputs, &mut values), Status::Ok);
    assert!(values.iter().all(|v| v.is_finite()), "{name}: {values:?}");
    assert!(t > 0.0);
}

/// An initialised instance of a full model with the given enumerations set.
fn full_model(table: &ModelTable, name: &str, enums: &[(u32, i32)]) -> ImportedInstance {
    let mut fmu = ImportedInstance::new(table.model_identifier, name)
        .unwrap_or_else(|log| panic!("{name}: instantiate: {log:?}"));
    for &(vr, value) in enums {
        assert_eq!(fmu.set_integer(&[vr], &[value]), Status::Ok, "{name}");
    }
    assert_eq!(fmu.initialize(), Status::Ok, "{name}: {:?}", fmu.messages());
    fmu
}

fn item(table: &ModelTable, variable: &str, item: &str) -> (u32, i32) {
    let var = table.by_name(variable).expect("variable");
    let Kind::Switch { type_name, .. } = var.kind else {
        panic!("{variable} is not an enumeration");
    };
    let value = table.enum_type(type_name).unwrap().value_of(item);
    (var.value_reference, value.expect("item"))
}

fn start(table: &ModelTable, vr: u32) -> f64 {
    match table.variable(vr).map(|v| v.kind) {
        Some(Kind::Real { start, .. }) => start,
        other => panic!("{vr}: not a Real: {other:?}"),
    }
}

#[test]
fn a_communication_step_does_not_allocate() {
    let mut checked = 0;
    for model in MODELS {
        let table = model.table;
        let solver = table.by_name("solver").expect("every model has `solver`");
        let Kind::Switch { type_name, .. } = solver.kind else {
            panic!("{}: `solver` is not an enumeration", table.model_identifier);
        };
        let items = table.enum_type(type_name).expect("solver type").items;
        let outputs = real_outputs(&table.variables.iter().collect::<Vec<_>>());
        // The inputs the default configuration reads (an input whose switch is off would be
        // reported, which is no step's work).
        let master = Master {
            inputs: table
                .variables
                .iter()
                .filter(|v| v.causality == Causality::Input)
                .filter(|v| !table.input_switches.iter().any(|s| s.input == v.name))
                .map(|v| (v.value_reference, 0.0))
                .collect(),
            derivatives: None,
            steps: &[STEP],
        };
        for (value, (item, _)) in (1..).zip(items.iter()) {
            let name = format!("{}-{item}", table.model_identifier);
            let mut fmu = full_model(table, &name, &[(solver.value_reference, value)]);
            assert_rounds_do_not_allocate(&name, &mut fmu, &outputs, &master);
            checked += 1;
        }
    }
    // Every solver of every model: L 4, T 3, O 3 at least.
    assert!(checked >= 10, "checked only {checked} solvers");
}

/// Inputs that move linearly over each step: TransverseFriction driven through vd_in, and
/// DriveTrain with its voltage an input, both with fmi2SetRealInputDerivatives before each step.
#[test]
fn inputs_with_derivatives_do_not_allocate() {
    let t = &transverse::TABLE;
    let mut fmu = full_model(t, "T-vd_in", &[item(t, "drive_source", "input")]);
    let vd = start(t, transverse::vr::VD_IN);
    let master = Master {
        inputs: vec![(transverse::vr::VD_IN, vd)],
        derivatives: Some(vec![vd / (10.0 * STEP)]),
        steps: &[STEP],
    };
    let outputs = real_outputs(&t.variables.iter().collect::<Vec<_>>());
    assert_rounds_do_not_allocate("T-vd_in", &mut fmu, &outputs, &master);

    let d = &drive::TABLE;
    let mut fmu = full_model(d, "DriveTrain-V_in", &[item(d, "voltage_source", "input")]);
    let master = Master {
        inputs: vec![
            (drive::vr::V_IN, start(d, drive::vr::V_IN)),
            // TransverseFriction's Coulomb force at its defaults, the load of drive.rs's example.
            (drive::vr::F_LOAD, 0.978),
        ],
        derivatives: Some(vec![100.0, -50.0]),
        steps: &[1e-4],
    };
    let outputs = real_outputs(&d.variables.iter().collect::<Vec<_>>());
    assert_rounds_do_not_allocate("DriveTrain-V_in", &mut fmu, &outputs, &master);
}

/// A master that changes its step size every step makes DriveTrain rebuild its matrix
/// exponential every step.
#[test]
fn changing_step_sizes_do_not_allocate() {
    let d = &drive::TABLE;
    let mut fmu = full_model(d, "DriveTrain-steps", &[]);
    let master = Master {
        inputs: vec![(drive::vr::F_LOAD, 0.978)],
        derivatives: None,
        steps: &[1e-4, 3e-5, 2.5e-4],
    };
    let outputs = real_outputs(&d.variables.iter().collect::<Vec<_>>());
    assert_rounds_do_not_allocate("DriveTrain-steps", &mut fmu, &outputs, &master);
}

/// Communication steps far shorter than dopri5's: TransverseFriction reads steps taken ahead,
/// takes the next from the end of the last, and its rollback copy holds the step.
#[test]
fn steps_taken_ahead_do_not_allocate() {
    let t = &transverse::TABLE;
    let mut fmu = full_model(t, "T-ahead", &[]);
    let master = Master {
        inputs: Vec::new(),
        derivatives: None,
        steps: &[1e-6, 3e-7],
    };
    let outputs = real_outputs(&t.variables.iter().collect::<Vec<_>>());
    assert_rounds_do_not_allocate("T-ahead", &mut fmu, &outputs, &master);
}

/// Every variant's trimmed FMU: the same library, instantiated with the variant's GUID and a
/// resource location holding the file as resources/variant.toml, stepped at the variant's step.
#[test]
fn every_variant_step_does_not_allocate() {
    let variants = Path::new(env!("CARGO_MANIFEST_DIR")).join("variants");
    let root = std::env::temp_dir().join(format!("no_alloc_variants_{}", std::process::id()));
    let mut files: Vec<_> = std::fs::read_dir(&variants)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    for path in &files {
        let variant_file = variant::read(path).unwrap();
        let resources = root.join(&variant_file.name).join("resources");
        std::fs::create_dir_all(&resources).unwrap();
        let file = resources.join(variant::RESOURCE);
        std::fs::write(&file, &variant_file.text).unwrap();
        // The GUID fmi2Instantiate checks the file against, computed the way it does.
        let guid = variant::registry::load(&file, friction_fmu::models::MODELS)
            .unwrap()
            .guid
            .clone();
        let mut arguments = Instantiation::new(
            variant_file.model.table.model_identifier,
            &variant_file.name,
        )
        .expect("the variant's model is in this binary");
        arguments.guid = Some(guid);
        arguments.resource_location = Some(format!("file://{}", resources.display()));
        let mut fmu = ImportedInstance::instantiate(&arguments)
            .unwrap_or_else(|log| panic!("{}: instantiate: {log:?}", variant_file.name));
        assert_eq!(
            fmu.initialize(),
            Status::Ok,
            "{}: {:?}",
            variant_file.name,
            fmu.messages()
        );
        let kept = variant_file.kept_variables();
        let master = Master {
            inputs: kept
                .iter()
                .filter(|v| v.causality == Causality::Input)
                .map(|v| {
                    (
                        v.value_reference,
                        variant_file.values.real(v.value_reference),
                    )
                })
                .collect(),
            derivatives: None,
            steps: &[variant_file.experiment.step],
        };
        assert_rounds_do_not_allocate(&variant_file.name, &mut fmu, &real_outputs(&kept), &master);
    }
    std::fs::remove_dir_all(&root).unwrap();
    assert!(files.len() >= 14, "only {} variants", files.len());
}

/// The same master through the FMI 3.0 boundary: fmi3SetFloat64 (inputs), fmi3DoStep and
/// fmi3GetFloat64 (outputs), 10 rounds uncounted, then ROUNDS counted.
fn assert_fmi3_rounds_do_not_allocate(
    name: &str,
    fmu: &mut fmi3::ImportedInstance,
    outputs: &[u32],
    inputs: &[(u32, f64)],
) {
    let (inputs, values): (Vec<u32>, Vec<f64>) = inputs.iter().copied().unzip();
    let mut out = vec![0.0; outputs.len()];
    let mut t = 0.0;
    let mut round = |fmu: &mut fmi3::ImportedInstance, t: &mut f64| {
        let set = fmu.set_float64(&inputs, &values);
        let (step, outcome) = fmu.do_step(*t, STEP, true);
        let get = fmu.get_float64_into(outputs, &mut out);
        *t += STEP;
        let ended_there = outcome.last_successful_time == *t;
        (set.max(step).max(get), ended_there)
    };
    for _ in 0..10 {
        let (status, _) = round(fmu, &mut t);
        assert_eq!(status, Status3::Ok, "{name}: {:?}", fmu.messages());
    }
    let mut results = [(Status3::Ok, true); ROUNDS];
    let info = allocation_counter::measure(|| {
        for result in results.iter_mut() {
            *result = round(fmu, &mut t);
        }
    });
    assert!(
        results.iter().all(|r| *r == (Status3::Ok, true)),
        "{name}: {results:?} {:?}",
        fmu.messages()
    );
    assert_eq!(
        info.count_total, 0,
        "{name}: {} allocations in {ROUNDS} rounds of an FMI 3.0 master's calls",
        info.count_total
    );
    let mut values = vec![0.0; outputs.len()];
    assert_eq!(fmu.get_float64_into(outputs, &mut values), Status3::Ok);
    assert!(values.iter().all(|v| v.is_finite()), "{name}: {values:?}");
}

/// fmi3DoStep and fmi3GetFloat64 at a communication step allocate nothing, for every model and
/// every solver.
#[test]
fn an_fmi3_communication_step_does_not_allocate() {
    let mut checked = 0;
    for model in MODELS {
        let table = model.table;
        let solver = table.by_name("solver").expect("every model has `solver`");
        let Kind::Switch { type_name, .. } = solver.kind else {
            panic!("{}: `solver` is not an enumeration", table.model_identifier);
        };
        let items = table.enum_type(type_name).expect("solver type").items;
        // Set with the setter of the type the FMI 3.0 modelDescription.xml declares it with.
        let solver_type = fmi3_description::variables(table.model_identifier)
            .into_iter()
            .find(|v| v.name == "solver")
            .expect("`solver` in the FMI 3.0 modelDescription.xml")
            .value_type;
        let outputs = real_outputs(&table.variables.iter().collect::<Vec<_>>());
        let inputs: Vec<(u32, f64)> = table
            .variables
            .iter()
            .filter(|v| v.causality == Causality::Input)
            .filter(|v| !table.input_switches.iter().any(|s| s.input == v.name))
            .map(|v| (v.value_reference, 0.0))
            .collect();
        for (value, (item, _)) in (1..).zip(items.iter()) {
            let name = format!("{}-{item} (FMI 3.0)", table.model_identifier);
            let mut fmu = fmi3::ImportedInstance::new(table.model_identifier, &name)
                .unwrap_or_else(|log| panic!("{name}: instantiate: {log:?}"));
            assert_eq!(
                fmu.set(solver_type, &[solver.value_reference], &[f64::from(value)]),
                Status3::Ok,
                "{name}: {:?}",
                fmu.messages()
            );
            assert_eq!(
                fmu.initialize(),
                Status3::Ok,
                "{name}: {:?}",
                fmu.messages()
            );
            assert_fmi3_rounds_do_not_allocate(&name, &mut fmu, &outputs, &inputs);
            checked += 1;
        }
    }
    assert!(checked >= 10, "checked only {checked} solvers");
}
