//! Trimmed models against the full ones: per case, the run time of the simulation built for the
//! full interface and of the one built for a variant's interface (the parameters it fixes and the
//! outputs it leaves out hidden), on the same values and solver settings, and how far the outputs
//! the trimmed interface keeps differ between the two.
//!
//! Both simulations are built by the models' own builders (as the FMU does), stepped through the
//! same communication points, their outputs written after every step as fmi2DoStep does.

use crate::models::{self, Scope};
use crate::models::{longitudinal::table as il, oscillator::table as io, transverse::table as it};
use crate::variables::values::ValueSet;
use crate::variables::variable::{Causality, EnumType, ModelTable};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One comparison: a model at fixed values, run over `steps` communication steps of `step`.
pub struct Case {
    pub title: &'static str,
    /// What the trimmed model leaves out of its run.
    pub skips: &'static str,
    pub values: ValueSet,
    /// What the variant fixes and leaves out, by value reference.
    pub hidden: Vec<u32>,
    pub step: f64,
    pub steps: u32,
}

/// The outputs the trimmed interface keeps, after every communication step.
struct Trace {
    kept: Vec<u32>,
    samples: Vec<f64>,
}

pub struct Row {
    pub title: &'static str,
    pub skips: &'static str,
    pub kept: String,
    /// Names of the hidden variables.
    pub hidden: String,
    pub full_seconds: f64,
    pub trimmed_seconds: f64,
    /// Largest |full - trimmed| over every kept output and communication point, relative to
    /// that output's largest |value| in the full run.
    pub max_difference: f64,
}

/// An item the cases below name; a misspelt one is a bug in this file, never user input.
fn item(e: &EnumType, name: &str) -> f64 {
    let value = e.value_of(name);
    f64::from(value.unwrap_or_else(|| panic!("{} has no item {name}", e.name)))
}

fn outputs(table: &ModelTable) -> impl Iterator<Item = u32> + '_ {
    table
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| v.value_reference)
}

/// Every output of `table` but `kept`.
fn hide_outputs_but(table: &ModelTable, kept: &[u32]) -> Vec<u32> {
    outputs(table).filter(|vr| !kept.contains(vr)).collect()
}

/// Scene T as in the paper's Fig. 4a: no vibration (va fixed at 0), from rest at vd = 0.5 mm/s,
/// 0.05 s in steps of 0.1 ms, only FFx read.
pub fn transverse_fig4a() -> Case {
    let mut values = ValueSet::start(&it::TABLE);
    values.set(it::vr::VA, 0.0);
    // Named, not the default: the case keeps its workload when the default moves.
    values.set(it::vr::TOLERANCE, 1e-10);
    let mut hidden = vec![it::vr::VA];
    hidden.extend(hide_outputs_but(&it::TABLE, &[it::vr::FFX]));
    Case {
        title: "T, Fig. 4a: va = 0, from rest, 0.05 s, dopri5 1e-10",
        skips: "the plane (y, y', z_y: the right-hand side reads 3 states, not 5), the period cuts",
        values,
        hidden,
        step: 1e-4,
        steps: 500,
    }
}

/// The Fig. 4a case with FFx_mean read too: the 1D equations alone (the period cuts stay).
pub fn transverse_fig4a_with_mean() -> Case {
    let mut case = transverse_fig4a();
    case.hidden.retain(|&vr| vr != it::vr::FFX_MEAN);
    case.title = "T, Fig. 4a as above, FFx_mean read too";
    case.skips = "the plane (y, y', z_y: the right-hand side reads 3 states, not 5)";
    case
}

/// The Fig. 4a case with the exponential scheme (2000 steps a period of f = 3 kHz).
pub fn transverse_fig4a_exponential() -> Case {
    let mut case = transverse_fig4a();
    case.values
        .set(it::vr::SOLVER, item(&it::SOLVER, "exponential"));
    case.title = "T, Fig. 4a as above, exponential, 2000 steps/period";
    case
}

/// Scene T vibrating (va 2 mm/s, 3 kHz) from rest, steps of 0.1 ms, only FFx read: the period
/// cuts alone (they fall between the communication points).
pub fn transverse_vibrating() -> Case {
    let mut values = ValueSet::start(&it::TABLE);
    values.set(it::vr::TOLERANCE, 1e-10);
    Case {
        title: "T, va 2 mm/s, 3 kHz, from rest, 0.01 s in steps of 0.1 ms, dopri5 1e-10",
        skips: "the period cuts",
        values,
        hidden: hide_outputs_but(&it::TABLE, &[it::vr::FFX]),
        step: 1e-4,
        steps: 100,
    }
}

/// Scene T at a Fig. 8 point: vd 0.5 mm/s, va 2 mm/s, f 3 kHz from steady sliding, 150 periods
/// one per communication step, dopri5 at 1e-8 (as the report's Fig. 8 table), only FFx_mean read.
pub fn transverse_fig8() -> Case {
    let mut values = ValueSet::start(&it::TABLE);
    values.set(it::vr::INITIAL, item(&it::INITIAL, "sliding"));
    values.set(it::vr::TOLERANCE, 1e-8);
    Case {
        title: "T, Fig. 8 point: vd 0.5, va 2 mm/s, 3 kHz, 150 periods, dopri5 1e-8",
        skips: "nothing: the mean needs q and the period cuts",
        values,
        hidden: hide_outputs_but(&it::TABLE, &[it::vr::FFX_MEAN]),
        step: 1.0 / 3000.0,
        steps: 150,
    }
}

/// Scene L, Table 1's Coulomb row at vc = 0.146 m/s: 30 periods, one per communication step,
/// FT_mean and S read; the law and its unused parameters fixed.
pub fn longitudinal_coulomb() -> Case {
    let mut values = ValueSet::start(&il::TABLE);
    values.set(il::vr::LAW, item(&il::LAW, "coulomb"));
    values.set(il::vr::VC, 0.146);
    let mut hidden = vec![
        il::vr::LAW,
        il::vr::KT,
        il::vr::ALPHA,
        il::vr::FS,
        il::vr::VS,
        il::vr::SIGMA1,
        il::vr::SIGMA2,
    ];
    hidden.extend(hide_outputs_but(&il::TABLE, &[il::vr::FT_MEAN, il::vr::S]));
    let f = values.real(il::vr::F);
    Case {
        title: "L, Table 1 Coulomb row, vc = 0.146 m/s, 30 periods",
        skips: "the 1/n grid: sub-steps end only where vr changes sign and on period ends",
        values,
        hidden,
        step: 1.0 / f,
        steps: 30,
    }
}

/// Scene L, Table 1's Dahl row at vc = 0.146 m/s with radau5: 30 periods in steps of 0.37
/// period, the force and the deflection read (no mean, no energy).
pub fn longitudinal_dahl_trace() -> Case {
    let mut values = ValueSet::start(&il::TABLE);
    values.set(il::vr::LAW, item(&il::LAW, "dahl"));
    values.set(il::vr::VC, 0.146);
    values.set(il::vr::SOLVER, item(&il::SOLVER, "radau5"));
    let mut hidden = vec![
        il::vr::LAW,
        il::vr::FS,
        il::vr::VS,
        il::vr::SIGMA1,
        il::vr::SIGMA2,
    ];
    hidden.extend(hide_outputs_but(
        &il::TABLE,
        &[il::vr::FT, il::vr::Z, il::vr::VR],
    ));
    let f = values.real(il::vr::F);
    Case {
        title: "L, Table 1 Dahl row, vc = 0.146 m/s, radau5 1e-8, 81 steps of 0.37 period",
        skips: "the force integral and work states (1 state of 3), the period cuts",
        values,
        hidden,
        step: 0.37 / f,
        steps: 81,
    }
}

/// Scene O at the paper's case (trigonometric law, radau5): 60 forcing periods in steps of 1/50
/// period, the motion u, u', u'' read (no amplitude, no dissipated energy).
pub fn oscillator_trace() -> Case {
    let mut values = ValueSet::start(&io::TABLE);
    values.set(io::vr::LAW, item(&io::LAW, "trigonometric"));
    let mut hidden = vec![io::vr::LAW];
    hidden.extend(hide_outputs_but(
        &io::TABLE,
        &[io::vr::U, io::vr::V, io::vr::A],
    ));
    let period = std::f64::consts::TAU / values.real(io::vr::W);
    Case {
        title: "O, paper's case, trigonometric, radau5, 60 periods, u u' u'' read",
        skips: "the turning-point search, the period cuts, the friction-work state",
        values,
        hidden,
        step: period / 50.0,
        steps: 3000,
    }
}

pub fn cases() -> Vec<Case> {
    vec![
        transverse_fig4a(),
        transverse_fig4a_with_mean(),
        transverse_fig4a_exponential(),
        transverse_vibrating(),
        transverse_fig8(),
        longitudinal_coulomb(),
        longitudinal_dahl_trace(),
        oscillator_trace(),
    ]
}

/// Runs `case` with the simulation built for `scope`; the kept outputs after every step.
fn run(case: &Case, scope: &Scope) -> Result<Trace, String> {
    let table = case.values.table;
    let model = models::model(table.model_identifier)
        .ok_or_else(|| format!("no model {}", table.model_identifier))?;
    let mut values = case.values.clone();
    let kept: Vec<u32> = outputs(table)
        .filter(|vr| !case.hidden.contains(vr))
        .collect();
    let mut sim = (model.build)(&values, 0.0, scope)?;
    let mut samples = Vec::with_capacity(kept.len() * case.steps as usize);
    for _ in 0..case.steps {
        sim.do_step(case.step, &values)?;
        sim.write_outputs(&mut values);
        samples.extend(kept.iter().map(|&vr| values.real(vr)));
    }
    Ok(Trace { kept, samples })
}

/// Repeats per case; the median of each is kept. Full and trimmed runs alternate so a change in
/// the machine's load falls on both.
const REPEATS: usize = 7;

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

/// The CPU time this thread has run, so the time other processes take the core from it does not
/// count; elsewhere the wall clock since `origin`.
fn cpu_seconds(origin: Instant) -> f64 {
    crate::cpu_clock::thread_cpu_seconds().unwrap_or_else(|| origin.elapsed().as_secs_f64())
}

/// Each timed sample repeats the run for at least this long and divides, so one sample does not
/// hang on a single scheduler interruption.
const SAMPLE_SECONDS: f64 = 0.1;

/// How many runs of `case` under `scope` fill a sample (from one run's wall time).
fn runs_per_sample(case: &Case, scope: &Scope) -> Result<u32, String> {
    let started = Instant::now();
    run(case, scope)?;
    let once = started.elapsed().as_secs_f64().max(1e-6);
    Ok((SAMPLE_SECONDS / once).ceil().clamp(1.0, 10_000.0) as u32)
}

/// `run` and the CPU time one run took, averaged over `runs`.
fn timed(case: &Case, scope: &Scope, runs: u32) -> Result<(Trace, f64), String> {
    let origin = Instant::now();
    let started = cpu_seconds(origin);
    let mut trace = run(case, scope)?;
    for _ in 1..runs {
        trace = run(case, scope)?;
    }
    Ok((trace, (cpu_seconds(origin) - started) / f64::from(runs)))
}

pub fn compare(case: &Case) -> Result<Row, String> {
    let trimmed_scope = Scope::hiding(case.hidden.clone());
    let (mut full_times, mut trimmed_times) = (Vec::new(), Vec::new());
    let mut traces = None;
    let full_runs = runs_per_sample(case, &Scope::full())?;
    let trimmed_runs = runs_per_sample(case, &trimmed_scope)?;
    for _ in 0..REPEATS {
        let (full, seconds) = timed(case, &Scope::full(), full_runs)?;
        full_times.push(seconds);
        let (trimmed, seconds) = timed(case, &trimmed_scope, trimmed_runs)?;
        trimmed_times.push(seconds);
        traces = Some((full, trimmed));
    }
    let (full, trimmed) = traces.ok_or("no repeats")?;
    let n = full.kept.len();
    let mut max_difference: f64 = 0.0;
    for j in 0..n {
        let column = |t: &Trace| {
            t.samples
                .iter()
                .skip(j)
                .step_by(n)
                .copied()
                .collect::<Vec<_>>()
        };
        let (a, b) = (column(&full), column(&trimmed));
        let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let worst = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        max_difference = max_difference.max(if scale > 0.0 { worst / scale } else { worst });
    }
    let table = case.values.table;
    let kept = full
        .kept
        .iter()
        .filter_map(|&vr| table.variable(vr).map(|v| v.name))
        .collect::<Vec<_>>()
        .join(", ");
    let hidden = case
        .hidden
        .iter()
        .filter_map(|&vr| table.variable(vr).map(|v| v.name))
        .collect::<Vec<_>>()
        .join(", ");
    Ok(Row {
        title: case.title,
        skips: case.skips,
        kept,
        hidden,
        full_seconds: median(full_times),
        trimmed_seconds: median(trimmed_times),
        max_difference,
    })
}

pub fn markdown(rows: &[Row]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| case | outputs kept | the trimmed model skips | full (s) | trimmed (s) | speed-up | max rel. difference |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.3e} | {:.3e} | {:.2} | {:.1e} |",
            r.title,
            r.kept,
            r.skips,
            r.full_seconds,
            r.trimmed_seconds,
            r.full_seconds / r.trimmed_seconds,
            r.max_difference
        );
    }
    let _ = writeln!(
        s,
        "\nTime: CPU time of the thread for one run, median of {REPEATS} samples (each repeating the run for at least {SAMPLE_SECONDS} s) single-threaded, full and trimmed alternating. Difference: the largest |full - trimmed| of a kept output over every communication point, relative to that output's largest |value|.\n\nHidden by each case's variant (fixed parameters and outputs left out):\n"
    );
    for r in rows {
        let _ = writeln!(s, "- {}: {}", r.title, r.hidden);
    }
    s
}

/// Runs every case, writes `<out>/trimmed.md` and returns its path and text.
pub fn write(out: &Path) -> Result<(PathBuf, String), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let cases = cases();
    let mut progress = super::progress::Progress::new("trimmed against full models", cases.len());
    let mut rows = Vec::new();
    for case in cases {
        progress.draw(case.title);
        rows.push(compare(&case).map_err(|e| format!("{}: {e}", case.title))?);
        progress.tick(case.title);
    }
    progress.finish();
    let text = format!(
        "# Trimmed models against the full ones\n\n{}",
        markdown(&rows)
    );
    let path = out.join("trimmed.md");
    std::fs::write(&path, &text).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok((path, text))
}
