//! Our radau5 against diffsol's stiff solvers on the project's small, restarted problems, and our
//! small LU and matrix exponential against nalgebra's. Prints tables; run with
//! `cargo run --release --manifest-path benches/diffsol_compare/Cargo.toml`.

mod cases;
mod linalg;
mod run;

use cases::Case;
use friction_fmu::cpu_clock::time_cpu;
use friction_fmu::models::transverse::{self, Transverse};
use friction_fmu::models::Simulation;
use run::{run, Method, Run};

const REPEATS: usize = 5;

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// Largest error over the restart points and states, each state's error relative to its range
/// over the reference run (at least its tolerance scale).
fn error(case: &Case, states: &[Vec<f64>], reference: &[Vec<f64>]) -> f64 {
    let n = case.y0.len();
    let range: Vec<f64> = (0..n)
        .map(|i| {
            reference
                .iter()
                .map(|s| s[i].abs())
                .fold(case.scale[i], f64::max)
        })
        .collect();
    let mut worst = 0.0f64;
    for (s, r) in states.iter().zip(reference) {
        for i in 0..n {
            worst = worst.max((s[i] - r[i]).abs() / range[i]);
        }
    }
    worst
}

struct Row {
    method: Method,
    rtol: f64,
    error: f64,
    seconds: f64,
    evaluations: u64,
}

fn measure(case: &Case, method: Method, rtol: f64, atol: f64) -> Result<(Run, f64), String> {
    let mut times = Vec::with_capacity(REPEATS);
    let mut last = None;
    for _ in 0..REPEATS {
        let (out, seconds) = time_cpu(|| run(case, method, rtol, atol));
        last = Some(out?);
        times.push(seconds);
    }
    Ok((last.expect("REPEATS > 0"), median(times)))
}

/// CPU time of `rows` (one solver) at error `e`, log-log interpolated; None outside their range.
fn time_at(rows: &[&Row], e: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.error > 0.0)
        .map(|r| (r.error.ln(), r.seconds.ln()))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let x = e.ln();
    pts.windows(2)
        .find(|w| w[0].0 <= x && x <= w[1].0)
        .map(|w| {
            let f = if w[1].0 > w[0].0 {
                (x - w[0].0) / (w[1].0 - w[0].0)
            } else {
                0.0
            };
            (w[0].1 + f * (w[1].1 - w[0].1)).exp()
        })
}

fn compare(case: &Case, rtols: &[f64], atol_factor: f64, methods: &[Method]) {
    println!("\n## {}", case.name);
    let restarts = case.grid.len();
    // Reference: the closed form, or radau5 at rtol 1e-12 cross-checked with diffsol's bdf at
    // its tightest tolerance that runs.
    let reference: Vec<Vec<f64>> = match case.exact {
        Some(f) => case.grid.iter().map(|&t| f(t)).collect(),
        None => {
            let r = run(case, Method::Radau5Warm, 1e-12, 1e-12 * atol_factor)
                .expect("reference run")
                .states;
            if let Ok(looser) = run(case, Method::Radau5Warm, 1e-11, 1e-11 * atol_factor) {
                println!(
                    "reference: radau5 rtol 1e-12; radau5 at rtol 1e-11 differs from it by {:.2e}",
                    error(case, &looser.states, &r)
                );
            }
            for tight in [1e-12, 1e-11, 1e-10, 1e-9] {
                match run(case, Method::Bdf, tight, tight * atol_factor) {
                    Ok(b) => {
                        println!(
                            "reference: radau5 rtol 1e-12; diffsol bdf at rtol {tight:e} differs from it by {:.2e}",
                            error(case, &b.states, &r)
                        );
                        break;
                    }
                    Err(e) => println!("(diffsol bdf at rtol {tight:e} failed: {e})"),
                }
            }
            r
        }
    };
    if let Some(f) = case.exact {
        for (method, tight) in [(Method::Radau5Warm, 1e-12), (Method::Bdf, 1e-12)] {
            if let Ok(r) = run(case, method, tight, tight * atol_factor) {
                let exact: Vec<Vec<f64>> = case.grid.iter().map(|&t| f(t)).collect();
                println!(
                    "reference: closed form; {} at rtol {tight:e} is {:.2e} from it",
                    method.name(),
                    error(case, &r.states, &exact)
                );
            }
        }
    }
    println!(
        "| solver | rtol | error | CPU s (median of {REPEATS}) | RHS evals | us per restart | time / radau5 time at equal error |"
    );
    println!("|---|---|---|---|---|---|---|");
    let mut rows = Vec::new();
    let mut failures = Vec::new();
    for &method in methods {
        for &rtol in rtols {
            match measure(case, method, rtol, rtol * atol_factor) {
                Ok((r, seconds)) => rows.push(Row {
                    method,
                    rtol,
                    error: error(case, &r.states, &reference),
                    seconds,
                    evaluations: r.rhs_evaluations,
                }),
                Err(e) => failures.push(format!(
                    "| {} | {rtol:.0e} | failed: {e} | | | | |",
                    method.name()
                )),
            }
        }
    }
    let ours: Vec<&Row> = rows
        .iter()
        .filter(|r| r.method == Method::Radau5Warm)
        .collect();
    for r in &rows {
        // Outside radau5's error range: against its cheapest run that is at least as accurate
        // (then the ratio at equal error is at least this), else nothing to compare.
        let ratio = match time_at(&ours, r.error) {
            Some(t) => format!("{:.2}", r.seconds / t),
            None => ours
                .iter()
                .filter(|o| o.error <= r.error)
                .map(|o| o.seconds)
                .min_by(f64::total_cmp)
                .map(|t| format!(">= {:.2}", r.seconds / t))
                .unwrap_or_else(|| "-".into()),
        };
        println!(
            "| {} | {:.0e} | {:.2e} | {:.4} | {} | {:.2} | {} |",
            r.method.name(),
            r.rtol,
            r.error,
            r.seconds,
            r.evaluations,
            r.seconds / restarts as f64 * 1e6,
            ratio
        );
    }
    for f in failures {
        println!("{f}");
    }
}

/// Scene T's own radau5 run against the restated ODE: the same equations if x agrees.
fn check_transverse(kt_factor: f64, periods: usize) {
    let values = cases::transverse_values(kt_factor, 1e-10, true);
    let mut sim = Transverse::new(&values, 0.0).expect("scene T");
    let period = 1.0 / sim.p.f;
    for _ in 0..periods {
        sim.do_step(period, &values).expect("scene T step");
    }
    let case = cases::transverse(kt_factor, periods, true);
    let ours = run(&case, Method::Radau5Kinks, 1e-10, 1e-10).expect("restated ODE");
    let x_ours = sim.position().0;
    let x_bench = ours.states.last().expect("states")[transverse::X];
    println!(
        "check: scene T (kt x {kt_factor}) after {periods} periods, x = {x_ours:.12e} from the simulation, {x_bench:.12e} from the restated ODE (relative difference {:.1e})",
        ((x_ours - x_bench) / x_ours).abs()
    );
}

fn main() {
    let all = [
        Method::Radau5Warm,
        Method::Radau5Cold,
        Method::Bdf,
        Method::TrBdf2,
        Method::Esdirk34,
    ];
    println!("# radau5 (src/solve/radau.rs) against diffsol 0.18, nalgebra backend");
    println!("Errors: largest over restart points and states, relative to each state's range.");
    compare(&cases::linear(), &[1e-4, 1e-6, 1e-8, 1e-10], 1.0, &all);
    compare(
        &cases::oscillator(1e-4),
        &[1e-4, 1e-6, 1e-8, 1e-10],
        1.0,
        &all,
    );
    compare(
        &cases::oscillator(1e-6),
        &[1e-4, 1e-6, 1e-8, 1e-10],
        1.0,
        &all,
    );
    // The simulation's default experiment: 0.05 s, 150 periods at 3 kHz.
    check_transverse(1000.0, 5);
    let with_kinks = [
        Method::Radau5Warm,
        Method::Radau5Kinks,
        Method::Radau5Cold,
        Method::Radau5LooseAtol,
        Method::Bdf,
        Method::BdfKinks,
        Method::BdfLooseAtol,
        Method::TrBdf2,
        Method::Esdirk34,
    ];
    for sliding in [true, false] {
        compare(
            &cases::transverse(1000.0, 150, sliding),
            &[1e-4, 1e-6, 1e-8, 1e-10, 1e-11],
            1.0,
            &with_kinks,
        );
    }
    linalg::tables();
}
