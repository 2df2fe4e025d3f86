//! Scene L beside the paper: Tables 1-3 of Leus & Gutowski (2008), recomputed.

use crate::friction::coulomb;
use crate::models::longitudinal::steady_mean_force;
use crate::models::longitudinal::table::{vr, LAW, TABLE};
use crate::variables::values::ValueSet;
use std::io::{self, Write};

/// Table 1 of the paper (va = 0.264 m/s, kt = 0.056 N/um): vc, FT_mean for Coulomb, Dahl and the
/// experiment (N), and the Dahl reduction S (%).
pub const TABLE_1: &[(f64, f64, f64, f64, f64)] = &[
    (0.324, 0.0196, 0.0196, 0.0197, 0.0),
    (0.264, 0.0196, 0.0196, 0.0187, 0.0),
    (0.230, 0.0131, 0.0181, 0.0179, 7.65),
    (0.199, 0.0107, 0.0156, 0.0168, 20.4),
    (0.146, 0.00724, 0.0109, 0.0112, 44.4),
    (0.095, 0.00454, 0.0066, 0.0077, 66.2),
];

/// Tables 2 (vc = 0.230 m/s) and 3 (vc = 0.146 m/s): kt in N/um, Dahl FT_mean in N.
pub const TABLES_2_3: &[(f64, &[(f64, f64)])] = &[
    (
        0.230,
        &[
            (0.030, 0.0186),
            (0.056, 0.0181),
            (0.120, 0.0172),
            (0.240, 0.0160),
            (0.480, 0.0148),
            (0.960, 0.0139),
        ],
    ),
    (
        0.146,
        &[
            (0.030, 0.0127),
            (0.056, 0.0109),
            (0.120, 0.00877),
            (0.240, 0.00783),
            (0.480, 0.00754),
            (0.960, 0.00742),
        ],
    ),
];

/// Periods simulated before the mean is read: the bristle settles within a few.
const PERIODS: u32 = 30;

/// The paper's parameters with one law and one (vc, kt).
pub fn paper_values(law: &str, vc: f64, kt: f64) -> ValueSet {
    let mut values = ValueSet::start(&TABLE);
    values.set(vr::LAW, f64::from(LAW.value_of(law).unwrap_or(1)));
    values.set(vr::VC, vc);
    values.set(vr::KT, kt);
    values
}

fn mean(law: &str, vc: f64, kt: f64) -> f64 {
    steady_mean_force(&paper_values(law, vc, kt), PERIODS).unwrap_or(f64::NAN)
}

fn deviation(model: f64, paper: f64) -> String {
    format!("{:+.2} %", (model / paper - 1.0) * 100.0)
}

pub fn print_tables(out: &mut dyn Write) -> io::Result<()> {
    let values = ValueSet::start(&TABLE);
    let kt = values.real(vr::KT);
    let va = values.real(vr::VA);
    let fc = values.real(vr::MU) * values.real(vr::M) * values.real(vr::G);
    writeln!(
        out,
        "Scene L: mean friction force over one vibration period (Leus & Gutowski 2008)"
    )?;
    writeln!(
        out,
        "Table 1 (va = {va} m/s, f = 60 kHz, kt = 0.056 N/um), FT_mean in N:"
    )?;
    writeln!(
        out,
        "{:>7} | {:>9} {:>9} {:>9} | {:>9} {:>9} {:>8} | {:>7} {:>7} | {:>9}",
        "vc m/s",
        "Coul.",
        "closed",
        "paper",
        "Dahl",
        "paper",
        "dev.",
        "S Dahl",
        "paper",
        "experim."
    )?;
    for &(vc, coulomb_paper, dahl_paper, experiment, s_paper) in TABLE_1 {
        let coulomb_model = mean("coulomb", vc, kt);
        let closed = coulomb::mean_under_vibration(fc, vc, va);
        let dahl = mean("dahl", vc, kt);
        writeln!(
            out,
            "{vc:>7.3} | {coulomb_model:>9.5} {closed:>9.5} {coulomb_paper:>9.5} | {dahl:>9.5} {dahl_paper:>9.5} {:>8} | {:>7.2} {:>7.2} | {experiment:>9.4}",
            deviation(dahl, dahl_paper),
            (1.0 - dahl / fc) * 100.0,
            s_paper,
        )?;
    }
    for &(vc, rows) in TABLES_2_3 {
        let table = if vc > 0.2 { 2 } else { 3 };
        writeln!(
            out,
            "Table {table} (vc = {vc} m/s), Dahl FT_mean in N against kt (Coulomb: {:.5} N):",
            coulomb::mean_under_vibration(fc, vc, va)
        )?;
        writeln!(
            out,
            "{:>9} | {:>9} {:>9} {:>8}",
            "kt N/um", "Dahl", "paper", "dev."
        )?;
        for &(kt_um, paper) in rows {
            let dahl = mean("dahl", vc, kt_um * 1e6);
            writeln!(
                out,
                "{kt_um:>9.3} | {dahl:>9.5} {paper:>9.5} {:>8}",
                deviation(dahl, paper)
            )?;
        }
    }
    Ok(())
}
