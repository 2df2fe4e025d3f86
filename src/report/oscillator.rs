//! Scene O beside the paper (paper O): how far each regularised law's steady amplitude is from
//! the exact switch model as D shrinks, and the paper's Fig. 1-4 panels for one law.
//!
//! The paper claims the trigonometric form is "more precise" without a reference to compare
//! with; the table measures it. The stiction laws are compared with `exact_stiction` at Da = D,
//! i.e. the paper's ratio ha = h (eq. 7), so their limit stays the same as D shrinks.

use crate::models::oscillator::table::{vr, LAW, TABLE};
use crate::models::oscillator::{steady_amplitude, trajectory};
use crate::report::figure::{Figure, Panel, Series};
use crate::variables::values::ValueSet;
use std::io::{self, Write};
use std::path::Path;

/// The widths of the transition region in the table (m/s).
pub const WIDTHS: [f64; 4] = [0.8, 0.2, 0.05, 0.01];

pub const REGULARISED: [&str; 4] = [
    "linear",
    "trigonometric",
    "linear_stiction",
    "trigonometric_stiction",
];

/// Forcing periods before the amplitude is read: the free response decays as e^(-c t/2m),
/// about 6e-9 after 60 periods at the paper's values.
pub const PERIODS: u32 = 60;

/// The paper's values (h 1.6, D 0.8, Da 0.8, c 0.1, P 4, m k w 1, at rest) with a law and D;
/// Da = D keeps ha = h.
pub fn paper_values(law: &str, d: f64) -> ValueSet {
    let mut values = ValueSet::start(&TABLE);
    values.set(vr::LAW, f64::from(LAW.value_of(law).unwrap_or(2)));
    values.set(vr::D, d);
    values.set(vr::DA, d);
    values
}

/// The exact law a regularised law tends to as D -> 0.
pub fn oracle_of(law: &str) -> &'static str {
    if law.ends_with("stiction") {
        "exact_stiction"
    } else {
        "exact"
    }
}

/// Relative error of the steady amplitude against the exact law, law x D.
pub fn amplitude_errors() -> Result<Vec<(&'static str, Vec<f64>)>, String> {
    let mut rows = Vec::new();
    for law in REGULARISED {
        let mut errors = Vec::new();
        for d in WIDTHS {
            let exact = steady_amplitude(&paper_values(oracle_of(law), d), PERIODS)?;
            let approx = steady_amplitude(&paper_values(law, d), PERIODS)?;
            errors.push(approx / exact - 1.0);
        }
        rows.push((law, errors));
    }
    Ok(rows)
}

/// Prints the table and writes `oscillator_trigonometric.csv` (and `.json`), the data of the
/// paper's Fig. 2 panels beside the exact solution, into `out_dir`.
pub fn print_summary(out_dir: &Path) -> io::Result<()> {
    let mut out = io::stdout().lock();
    writeln!(
        out,
        "DryFrictionOscillator (paper O): steady amplitude max|u|, relative error against the exact switch model"
    )?;
    writeln!(
        out,
        "(h 1.6, c 0.1, P 4, m k w 1; stiction laws with Da = D against exact_stiction, breakaway 2h)"
    )?;
    let rows = amplitude_errors().map_err(io::Error::other)?;
    write!(out, "{:<24}", "law \\ D (m/s)")?;
    for d in WIDTHS {
        write!(out, "{d:>12}")?;
    }
    writeln!(out)?;
    for (law, errors) in &rows {
        write!(out, "{law:<24}")?;
        for e in errors {
            write!(out, "{e:>12.3e}")?;
        }
        writeln!(out)?;
    }
    for (plain, stiction) in [(0, 1), (2, 3)] {
        let wins = rows[plain]
            .1
            .iter()
            .zip(&rows[stiction].1)
            .filter(|(a, b)| b.abs() < a.abs())
            .count();
        writeln!(
            out,
            "{} is closer than {} at {wins} of {} widths",
            rows[stiction].0,
            rows[plain].0,
            WIDTHS.len()
        )?;
    }
    let path = figure()?
        .write(out_dir, "oscillator_trigonometric")
        .map_err(io::Error::other)?;
    writeln!(out, "wrote {}", path.display())?;
    Ok(())
}

/// The paper's Fig. 2 panels (trigonometric law, D = 0.8) over two steady periods, with the
/// exact switch model drawn beside it. The paper letters its panels a, b, d, f, h, e; here they
/// are in the order drawn, and the title names each.
fn figure() -> io::Result<Figure> {
    let law = trajectory(&paper_values("trigonometric", 0.8), PERIODS, 2, 400)
        .map_err(io::Error::other)?;
    let exact =
        trajectory(&paper_values("exact", 0.8), PERIODS, 2, 400).map_err(io::Error::other)?;
    // samples: t, u, u', H, C
    let series = |samples: &[[f64; 5]], name: &str, x: usize, y: usize| {
        Series::new(name, samples.iter().map(|s| (s[x], s[y])).collect())
    };
    let panel = |title: &str, x_label: &str, y_label: &str, x: usize, y: usize| {
        let both = vec![
            series(&law, "trigonometric", x, y),
            series(&exact, "exact", x, y),
        ];
        Panel::lines(title, x_label, y_label, both)
    };
    // The exact law's slope is 0 (or undefined at the switch): the regularised law's alone.
    let slope = vec![series(&law, "trigonometric", 0, 4)];
    let panels = vec![
        panel("displacement", "t (s)", "u (m)", 0, 1),
        panel("velocity", "t (s)", "u' (m/s)", 0, 2),
        panel("friction force against time", "t (s)", "H (N)", 0, 3),
        panel("friction force against velocity", "u' (m/s)", "H (N)", 2, 3),
        panel("phase trajectory", "u (m)", "u' (m/s)", 1, 2),
        Panel::lines("slope C = dH/du' against time", "t (s)", "C (N s/m)", slope),
    ];
    let title =
        "DryFrictionOscillator, paper O's Fig. 2: trigonometric law, D = 0.8, two steady periods";
    Ok(Figure::new(title, 3, panels)
        .label("trigonometric", "trigonometric, D = 0.8")
        .label("exact", "exact switch model"))
}
