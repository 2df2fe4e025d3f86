//! A co-simulation step never allocates: fmi2SetReal (inputs), fmi2DoStep and fmi2GetReal
//! (outputs), for every model and every solver, driven through the exported fmi2* functions
//! in-process (src/fmi2/driver.rs) with a per-thread counting allocator around them.
//!
//! Oracle: the allocator's count; zero is the contract (src/solve/mod.rs: integrators keep their
//! scratch space inline). The first steps run before counting, so nothing lazily set up on the
//! first call (none is expected either) hides a per-step allocation or excuses one.
#![cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]

use friction_fmu::fmi2::driver::Instance;
use friction_fmu::fmi2::ffi::Status;
use friction_fmu::interface::variable::{Causality, Kind};
use friction_fmu::scenes::MODELS;

/// The communication step of the FMI-overhead measurement (examples/fmi_overhead.rs).
const STEP: f64 = 1e-5;

#[test]
fn a_communication_step_does_not_allocate() {
    let mut checked = 0;
    for model in MODELS {
        let table = model.table;
        let solver = table.by_name("solver").expect("every model has `solver`");
        let Kind::Enumeration { type_name, .. } = solver.kind else {
            panic!("{}: `solver` is not an enumeration", table.model_identifier);
        };
        let items = table.enum_type(type_name).expect("solver type").items;
        let outputs: Vec<u32> = table
            .variables
            .iter()
            .filter(|v| v.causality == Causality::Output && matches!(v.kind, Kind::Real { .. }))
            .map(|v| v.value_reference)
            .collect();
        let mut values = vec![0.0; outputs.len()];
        for (value, (item, _)) in (1..).zip(items.iter()) {
            let name = format!("{}-{item}", table.model_identifier);
            let mut fmu = Instance::new(table.model_identifier, &name)
                .unwrap_or_else(|log| panic!("{name}: instantiate: {log:?}"));
            assert_eq!(
                fmu.set_integer(&[solver.value_reference], &[value]),
                Status::Ok
            );
            assert_eq!(fmu.initialize(), Status::Ok, "{name}: {:?}", fmu.messages());
            let mut t = 0.0;
            for _ in 0..10 {
                assert_eq!(fmu.do_step(t, STEP, true), Status::Ok, "{name}");
                t += STEP;
            }
            let inputs: Vec<u32> = table
                .variables
                .iter()
                .filter(|v| v.causality == Causality::Input)
                .map(|v| v.value_reference)
                .collect();
            let zeros = vec![0.0; inputs.len()];
            let mut statuses = [Status::Ok; 200];
            // A co-simulation step as a master makes it: set the inputs, step, read the outputs.
            let info = allocation_counter::measure(|| {
                for status in statuses.iter_mut() {
                    let set = fmu.set_real(&inputs, &zeros);
                    let step = fmu.do_step(t, STEP, true);
                    let get = fmu.get_real_into(&outputs, &mut values);
                    *status = set.max(step).max(get);
                    t += STEP;
                }
            });
            assert!(
                statuses.iter().all(|s| *s == Status::Ok),
                "{name}: {statuses:?}"
            );
            assert_eq!(
                info.count_total, 0,
                "{name}: {} allocations in 200 rounds of fmi2SetReal, fmi2DoStep, fmi2GetReal",
                info.count_total
            );
            // The steps did something: the outputs are finite and time has advanced.
            assert_eq!(fmu.get_real_into(&outputs, &mut values), Status::Ok);
            assert!(values.iter().all(|v| v.is_finite()), "{name}: {values:?}");
            checked += 1;
        }
    }
    // Every solver of every model: L 4, T 3, O 3 at least.
    assert!(checked >= 10, "checked only {checked} solvers");
}
