//! Runs one case of the stability matrix through the in-process FMI driver and judges it.

use super::{Case, Value};
use crate::fmi2::ffi::Status;
use crate::importer::ImportedInstance;
use crate::variables::variable::{Causality, Kind, ModelTable};
use std::time::Instant;

/// fmi2StatusKind fmi2LastSuccessfulTime.
const LAST_SUCCESSFUL_TIME: i32 = 2;

/// W_diss may fall below zero by this fraction of the energies it is the difference of (the
/// friction work and the stored energy), the round-off of that difference.
pub const PASSIVITY_SLACK: f64 = 1e-12;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Every communication step returned fmi2OK.
    Ok,
    /// Every communication step completed; one or more returned fmi2Warning (the first
    /// warning's message is kept).
    Warning,
    /// A step returned fmi2Discard.
    Discard,
    /// A step returned fmi2Error (or worse).
    Error,
    /// A parameter or the initialisation was refused.
    Refused,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub model: &'static str,
    pub solver: &'static str,
    pub extreme: &'static str,
    pub outcome: Outcome,
    /// Simulated time reached (the last successful communication point).
    pub t_reached: f64,
    /// fmi2LastSuccessfulTime after a failed step; None when the run succeeded or the FMU did
    /// not answer.
    pub last_successful: Option<f64>,
    /// The message logged with the failure ("" when none was).
    pub message: String,
    /// An output read as NaN at any point, whatever the status.
    pub nan: bool,
    /// Every output finite at every fmi2OK communication point.
    pub finite: bool,
    /// After a failed step, the outputs read (or refused) exactly as at the last successful
    /// communication point: the FMU rolled the step back.
    pub rolled_back: bool,
    /// The least W_diss / (friction work + stored energy) over the communication points.
    pub least_dissipation: f64,
    /// W_diss at the last successful communication point.
    pub w_diss: f64,
    pub seconds: f64,
}

impl Row {
    /// Never NaN; finite when fmi2OK; passive; a failure says why and where it stopped.
    pub fn sound(&self) -> bool {
        let passive = self.least_dissipation >= -PASSIVITY_SLACK;
        let explained = match self.outcome {
            Outcome::Ok => true,
            Outcome::Refused | Outcome::Warning => !self.message.is_empty(),
            Outcome::Discard | Outcome::Error => {
                // The FMU's clock adds steps; ours multiplies: equal to round-off.
                let at_stop =
                    |t: f64| (t - self.t_reached).abs() <= 1e-12 * self.t_reached.max(1.0);
                !self.message.is_empty()
                    && self.last_successful.is_some_and(at_stop)
                    && self.rolled_back
            }
        };
        !self.nan && self.finite && passive && explained
    }
}

fn set(
    fmu: &mut ImportedInstance,
    table: &ModelTable,
    name: &str,
    value: Value,
) -> Result<(), String> {
    let var = table
        .by_name(name)
        .ok_or_else(|| format!("no parameter {name}"))?;
    let vr = [var.value_reference];
    let status = match (value, var.kind) {
        (Value::Real(x), _) => fmu.set_real(&vr, &[x]),
        (Value::Integer(n), _) => fmu.set_integer(&vr, &[n]),
        (Value::Item(item), Kind::Switch { type_name, .. }) => {
            let code = table
                .enum_type(type_name)
                .and_then(|e| e.value_of(item))
                .ok_or_else(|| format!("{name} has no item {item}"))?;
            fmu.set_integer(&vr, &[code])
        }
        (Value::Item(_), _) => return Err(format!("{name} is not an enumeration")),
    };
    if status == Status::Ok {
        Ok(())
    } else {
        Err(fmu.last_message())
    }
}

/// The energy W_diss is the difference of: the friction work, W_diss plus the energy stored in
/// the deflection (kt z^2/2 or kt s^2/2; the oscillator's law stores none).
fn energy_scale(table: &ModelTable, outputs: &[u32], values: &[f64], kt: f64) -> f64 {
    let get = |name: &str| {
        table
            .by_name(name)
            .and_then(|v| outputs.iter().position(|&r| r == v.value_reference))
            .map(|i| values[i])
    };
    let deflection = get("z").or_else(|| get("s")).unwrap_or(0.0);
    get("W_diss").unwrap_or(0.0).abs() + 0.5 * kt * deflection * deflection
}

pub fn run(case: &Case) -> Row {
    let started = Instant::now();
    let mut row = Row {
        model: case.model,
        solver: case.solver,
        extreme: case.extreme,
        outcome: Outcome::Ok,
        t_reached: 0.0,
        last_successful: None,
        message: String::new(),
        nan: false,
        finite: true,
        rolled_back: true,
        least_dissipation: f64::INFINITY,
        w_diss: 0.0,
        seconds: 0.0,
    };
    let Some(model) = crate::models::model(case.model) else {
        row.outcome = Outcome::Refused;
        row.message = format!("no model {}", case.model);
        return row;
    };
    let table = model.table;
    let name = format!("{}-{}-{}", case.model, case.solver, case.extreme);
    let mut fmu = match ImportedInstance::new(table.model_identifier, &name) {
        Ok(fmu) => fmu,
        Err(log) => {
            row.outcome = Outcome::Refused;
            row.message = format!("instantiate: {log:?}");
            return row;
        }
    };
    let configured = case
        .params
        .iter()
        .try_for_each(|&(name, value)| set(&mut fmu, table, name, value));
    let initialized = configured.and_then(|()| match fmu.initialize() {
        Status::Ok => Ok(()),
        _ => Err(fmu.last_message()),
    });
    if let Err(message) = initialized {
        row.outcome = Outcome::Refused;
        row.message = message;
        return row;
    }
    let outputs: Vec<u32> = table
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| v.value_reference)
        .collect();
    let w_diss = table
        .by_name("W_diss")
        .and_then(|v| outputs.iter().position(|&r| r == v.value_reference));
    let kt = match table.by_name("kt") {
        Some(v) => fmu.get_real(&[v.value_reference]).1[0],
        None => 0.0,
    };
    let mut values = vec![0.0; outputs.len()];
    // The outputs at the last successful communication point, and whether they could be read.
    let mut good = vec![0.0; outputs.len()];
    let mut good_read = fmu.get_real_into(&outputs, &mut good);
    for k in 0..case.steps {
        let t = k as f64 * case.step;
        let status = fmu.do_step(t, case.step, true);
        // The step's own message, before reading the outputs can log another.
        let message = fmu.last_message();
        let read = fmu.get_real_into(&outputs, &mut values);
        if read == Status::Ok {
            row.nan |= values.iter().any(|v| v.is_nan());
        }
        if status == Status::Warning {
            if row.outcome == Outcome::Ok {
                row.outcome = Outcome::Warning;
                row.message = message;
            }
        } else if status != Status::Ok {
            row.outcome = if status == Status::Discard {
                Outcome::Discard
            } else {
                Outcome::Error
            };
            row.message = message;
            let (answered, last) = fmu.get_real_status(LAST_SUCCESSFUL_TIME);
            row.last_successful = (answered == Status::Ok).then_some(last);
            row.rolled_back = read == good_read && (read != Status::Ok || values == good);
            break;
        }
        good.copy_from_slice(&values);
        good_read = read;
        row.t_reached = t + case.step;
        row.finite &= read == Status::Ok && values.iter().all(|v| v.is_finite());
        if let Some(i) = w_diss {
            row.w_diss = values[i];
            let scale = energy_scale(table, &outputs, &values, kt);
            let ratio = if scale > 0.0 { values[i] / scale } else { 0.0 };
            row.least_dissipation = row.least_dissipation.min(ratio);
        }
    }
    row.seconds = started.elapsed().as_secs_f64();
    row
}

/// The matrix as a Markdown table, one row per case, with a last column saying whether the row
/// meets the contract (never NaN, finite when fmi2OK, passive, failures explained and rolled
/// back).
pub fn print(rows: &[Row], out: &mut dyn std::io::Write) -> std::io::Result<()> {
    writeln!(
        out,
        "| model | solver | extreme | status | t reached (s) | least W_diss/E | W_diss (J) | s | sound | message |"
    )?;
    writeln!(out, "|---|---|---|---|---|---|---|---|---|---|")?;
    for r in rows {
        // The reason, without fmi2DoStep's preamble (the step and time are in the row).
        const PREAMBLE_END: &str = "could not be completed: ";
        let reason = r
            .message
            .find(PREAMBLE_END)
            .map_or(r.message.as_str(), |i| &r.message[i + PREAMBLE_END.len()..]);
        let message: String = reason.chars().take(200).collect();
        let least = if r.least_dissipation.is_finite() {
            format!("{:.1e}", r.least_dissipation)
        } else {
            "-".into()
        };
        writeln!(
            out,
            "| {} | {} | {} | {:?} | {:.3e} | {least} | {:.3e} | {:.2} | {} | {} |",
            r.model,
            r.solver,
            r.extreme,
            r.outcome,
            r.t_reached,
            r.w_diss,
            r.seconds,
            if r.sound() { "yes" } else { "NO" },
            message.replace('|', "/")
        )?;
    }
    let sound = rows.iter().filter(|r| r.sound()).count();
    let ended = |r: &&Row| matches!(r.outcome, Outcome::Ok | Outcome::Warning);
    let ok = rows.iter().filter(ended).count();
    let warned = rows
        .iter()
        .filter(|r| r.outcome == Outcome::Warning)
        .count();
    writeln!(
        out,
        "\n{} cases: {ok} ran to the end ({warned} of them with a warning), {} stopped with a logged reason; {sound} sound.",
        rows.len(),
        rows.len() - ok
    )
}
