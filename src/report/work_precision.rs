//! Error against run time : for one scene, every solver
//! it offers over a range of steps or tolerances, the relative error of the quantity a user reads
//! (a mean force, an amplitude) against a reference run far more accurate, the run time and the
//! right-hand-side evaluations; written as a Markdown table and a log-log plot of error against
//! CPU time (as figure data, src/report/figure.rs).
//!
//! The reference is the best solver at a setting well beyond the table's; a second reference at
//! a neighbouring setting estimates its own error, which the table prints so a reader can check
//! it is at least 100 times below the smallest error shown.

use super::figure::{Figure, Panel, Series};
use super::progress::Progress;
use crate::cpu_clock::time_cpu;
use crate::solve::Work;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// How a solver's accuracy is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Knob {
    /// Relative tolerance of an adaptive solver.
    Tolerance(f64),
    /// Fixed steps per vibration (or forcing) period.
    StepsPerPeriod(u32),
}

impl Knob {
    pub fn label(&self) -> String {
        match self {
            Knob::Tolerance(t) => format!("rtol {t:.0e}"),
            Knob::StepsPerPeriod(n) => format!("{n} steps/period"),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setting {
    pub solver: &'static str,
    pub knob: Knob,
}

/// Runs one setting: the quantity and the work it took.
pub type Runner = Box<dyn Fn(&Setting) -> Result<(f64, Work), String>>;

/// One scene's work-precision study.
pub struct Case {
    /// File stem under the output directory (`longitudinal` writes longitudinal.md, .csv and
    /// .json).
    pub stem: &'static str,
    /// What is run, in a sentence (title of the table).
    pub title: String,
    /// A title short enough for the plot's one line.
    pub short_title: &'static str,
    /// The quantity whose error is measured.
    pub quantity: &'static str,
    pub settings: Vec<Setting>,
    /// The reference and a neighbour of it (for the reference's own error).
    pub reference: (Setting, Setting),
    pub run: Runner,
}

pub struct Row {
    pub setting: Setting,
    /// Relative error against the reference; None when the run failed.
    pub error: Option<f64>,
    pub seconds: f64,
    pub work: Work,
    pub failure: Option<String>,
}

pub struct Study {
    pub reference: f64,
    /// |reference - neighbour| / |reference|.
    pub reference_error: f64,
    pub rows: Vec<Row>,
}

/// Each run is repeated until this much CPU time has passed (at least MIN_REPEATS, at most
/// MAX_REPEATS times) and the median is kept: the thread's own CPU time does not count what other
/// processes take of a shared core, and the median drops the odd stall either way.
const MIN_TIMED: f64 = 0.05;
const MIN_REPEATS: usize = 3;
const MAX_REPEATS: usize = 21;

fn timed(case: &Case, setting: &Setting) -> (Result<(f64, Work), String>, f64) {
    let mut times = Vec::with_capacity(MAX_REPEATS);
    let mut total = 0.0;
    loop {
        let (result, seconds) = time_cpu(|| (case.run)(setting));
        times.push(seconds);
        total += seconds;
        let enough = times.len() >= MIN_REPEATS && total >= MIN_TIMED;
        if result.is_err() || enough || times.len() >= MAX_REPEATS {
            return (result, median(&mut times));
        }
    }
}

fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    let mid = times.len() / 2;
    if times.len() % 2 == 1 {
        times[mid]
    } else {
        0.5 * (times[mid - 1] + times[mid])
    }
}

pub fn study(case: &Case, progress: &mut Progress) -> Result<Study, String> {
    progress.draw(&format!("{} reference", case.stem));
    let (reference, _) = (case.run)(&case.reference.0)
        .map_err(|e| format!("{}: the reference run failed: {e}", case.stem))?;
    let (neighbour, _) = (case.run)(&case.reference.1)
        .map_err(|e| format!("{}: the second reference run failed: {e}", case.stem))?;
    progress.tick(&format!("{} reference", case.stem));
    let reference_error = ((neighbour - reference) / reference).abs();
    let mut rows = Vec::new();
    for setting in &case.settings {
        progress.draw(&format!(
            "{} {} {}",
            case.stem,
            setting.solver,
            setting.knob.label()
        ));
        let (result, seconds) = timed(case, setting);
        let row = match result {
            Ok((value, work)) => Row {
                setting: *setting,
                error: Some(((value - reference) / reference).abs()),
                seconds,
                work,
                failure: None,
            },
            Err(e) => Row {
                setting: *setting,
                error: None,
                seconds,
                work: Work::default(),
                failure: Some(e),
            },
        };
        rows.push(row);
        progress.tick(setting.solver);
    }
    Ok(Study {
        reference,
        reference_error,
        rows,
    })
}

pub fn markdown(case: &Case, study: &Study) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# {}\n", case.title);
    let _ = writeln!(
        s,
        "Reference {} = {:.12e} ({} {}); its estimated relative error (against {}) {:.1e}.\n",
        case.quantity,
        study.reference,
        case.reference.0.solver,
        case.reference.0.knob.label(),
        case.reference.1.knob.label(),
        study.reference_error,
    );
    let _ = writeln!(
        s,
        "| solver | step or tolerance | rel. error of {} | CPU time (s) | RHS evaluations | steps | rejected |",
        case.quantity
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for r in &study.rows {
        let error = match (&r.error, &r.failure) {
            (Some(e), _) => format!("{e:.2e}"),
            (None, Some(f)) => format!("failed: {}", f.replace('|', "/")),
            _ => "-".into(),
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.3e} | {} | {} | {} |",
            r.setting.solver,
            r.setting.knob.label(),
            error,
            r.seconds,
            r.work.rhs_evaluations,
            r.work.steps,
            r.work.rejected
        );
    }
    let _ = writeln!(
        s,
        "\nCPU time: the median over repeated runs of the CPU time of the thread running them."
    );
    if study
        .rows
        .iter()
        .any(|r| r.error.is_some() && r.work.rhs_evaluations == 0)
    {
        let _ = writeln!(
            s,
            "0 RHS evaluations: the scheme's step is algebraic (no right-hand side); the steps column counts its work."
        );
    }
    s
}

/// Error against CPU time, one line per solver (named by its `solver` item, so the drawing gives
/// it the colour and marker it has in every figure), a marker at each setting.
pub fn figure(case: &Case, study: &Study) -> Figure {
    let mut series = Vec::new();
    let mut solvers: Vec<&str> = Vec::new();
    for r in &study.rows {
        if !solvers.contains(&r.setting.solver) {
            solvers.push(r.setting.solver);
        }
    }
    for solver in solvers {
        let points: Vec<(f64, f64)> = study
            .rows
            .iter()
            .filter(|r| r.setting.solver == solver)
            .filter_map(|r| r.error.map(|e| (r.seconds, e)))
            .collect();
        series.push(Series::new(solver, points));
    }
    let y_label = format!("relative error of {}", case.quantity);
    let panel = Panel::lines("", "CPU time (s)", &y_label, series).log_log();
    Figure::new(case.short_title, 1, vec![panel]).with_markers()
}

/// Runs every case and writes `<out>/<stem>.md` and the plot's data, `<out>/<stem>.csv` and
/// `.json`; returns the paths of the tables and of the CSV files.
pub fn write_all(cases: &[Case], out: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let total: usize = cases.iter().map(|c| c.settings.len() + 1).sum();
    let mut progress = Progress::new("error against run time", total);
    let mut written = Vec::new();
    for case in cases {
        let study = study(case, &mut progress)?;
        let md = out.join(format!("{}.md", case.stem));
        std::fs::write(&md, markdown(case, &study))
            .map_err(|e| format!("{}: {e}", md.display()))?;
        let csv = figure(case, &study).write(out, case.stem)?;
        written.push(md);
        written.push(csv);
    }
    progress.finish();
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(solver: &'static str, knob: Knob, error: Option<f64>, seconds: f64) -> Row {
        Row {
            setting: Setting { solver, knob },
            error,
            seconds,
            work: Work::default(),
            failure: error
                .is_none()
                .then(|| "rk4: the state became non-finite".into()),
        }
    }

    /// The plot's data: one series per solver in the order they first appear, a point per
    /// setting that ran (CPU time, error), none for a failed one.
    #[test]
    fn figure_csv_has_one_row_per_setting_that_ran() {
        let at = |rtol| Setting {
            solver: "dopri5",
            knob: Knob::Tolerance(rtol),
        };
        let case = Case {
            stem: "scene",
            title: "a scene".into(),
            short_title: "a scene: error of FT_mean",
            quantity: "FT_mean",
            settings: Vec::new(),
            reference: (at(1e-13), at(1e-12)),
            run: Box::new(|_| Err("not run".into())),
        };
        let study = Study {
            reference: 1.0,
            reference_error: 1e-15,
            rows: vec![
                row("rk4", Knob::StepsPerPeriod(25), Some(1.5e-5), 2.5e-4),
                row("dopri5", Knob::Tolerance(1e-3), Some(3e-6), 1.5e-4),
                row("rk4", Knob::StepsPerPeriod(50), None, 1e-3),
                row("rk4", Knob::StepsPerPeriod(100), Some(4.75e-8), 8.875e-4),
            ],
        };
        let figure = figure(&case, &study);
        assert_eq!(
            figure.csv().unwrap(),
            "panel,series,x,y\n\
             0,rk4,2.5e-4,1.5e-5\n\
             0,rk4,8.875e-4,4.75e-8\n\
             0,dopri5,1.5e-4,3e-6\n"
        );
        let json = figure.json().unwrap();
        assert!(json.contains("\"title\": \"a scene: error of FT_mean\""));
        assert!(json.contains(
            "\"x\": \"CPU time (s)\", \"y\": \"relative error of FT_mean\", \"log_x\": true, \"log_y\": true"
        ));
        assert!(json.contains("\"markers\": true"));
    }
}
