//! In-process timing of scene T for benches/transverse.py: runs the simulation (no FMI layer) for
//! each solver setting given on the command line and prints one CSV line per run.
//!
//!   cargo run --release --example transverse_bench -- SLIP_LAW KT_FACTOR T_END COMM_STEP \
//!       SOLVER:KNOB [SOLVER:KNOB ...]
//!
//! KNOB is a tolerance for dopri5/radau5 and steps per period for rk4/two_phase/exponential.
//! Output: `slip_law,kt_factor,solver,knob,FFx_mean,cpu_seconds,rhs_evaluations,steps,rejected`.
//! The clock is the CPU time of the running thread (`cpu_clock`).

use friction_fmu::cpu_clock::time_cpu;
use friction_fmu::models::transverse::table::{vr, INITIAL, SLIP_LAW, SOLVER, TABLE};
use friction_fmu::models::transverse::Transverse;
use friction_fmu::models::Simulation;
use friction_fmu::variables::values::ValueSet;
use std::process::ExitCode;

fn run(args: &[String]) -> Result<(), String> {
    if args.len() < 5 {
        return Err(
            "usage: transverse_bench SLIP_LAW KT_FACTOR T_END COMM_STEP SOLVER:KNOB...".into(),
        );
    }
    let slip = args[0].as_str();
    let parse = |s: &str| s.parse::<f64>().map_err(|e| format!("{s}: {e}"));
    let (kt_factor, t_end, comm) = (parse(&args[1])?, parse(&args[2])?, parse(&args[3])?);
    for spec in &args[4..] {
        let (solver, knob) = spec
            .split_once(':')
            .ok_or(format!("{spec}: expected SOLVER:KNOB"))?;
        let knob = parse(knob)?;
        let mut v = ValueSet::start(&TABLE);
        let item = |e: &friction_fmu::variables::variable::EnumType, name: &str| {
            e.value_of(name)
                .map(f64::from)
                .ok_or(format!("no item {name}"))
        };
        v.set(vr::SLIP_LAW, item(&SLIP_LAW, slip)?);
        v.set(vr::INITIAL, item(&INITIAL, "sliding")?);
        v.set(vr::SOLVER, item(&SOLVER, solver)?);
        v.set(vr::VD, 5e-4);
        v.set(vr::VA, 2e-3);
        v.set(vr::F, 3000.0);
        v.set(vr::KT, v.real(vr::KT) * kt_factor);
        if matches!(solver, "rk4" | "two_phase" | "exponential") {
            v.set(vr::STEPS_PER_PERIOD, knob);
        } else {
            v.set(vr::TOLERANCE, knob);
        }
        let mut sim = Transverse::new(&v, 0.0)?;
        let steps = (t_end / comm).round() as u64;
        let (result, seconds) = time_cpu(|| -> Result<(), String> {
            for i in 0..steps {
                // The communication point from its index, as a master computes it.
                let h = (i + 1) as f64 * comm - sim.time();
                sim.do_step(h, &v)?;
            }
            Ok(())
        });
        result?;
        let w = sim.work;
        println!(
            "{slip},{kt_factor},{solver},{knob:e},{:.15e},{seconds:.6},{},{},{}",
            sim.mean_ffx(),
            w.rhs_evaluations,
            w.steps,
            w.rejected
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("transverse_bench: {e}");
            ExitCode::FAILURE
        }
    }
}
