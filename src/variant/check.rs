//! From the raw TOML to a [`Variant`]: every name looked up in the model's table, every value
//! checked as a setter would check it. Each message names the file, the key and what was expected.

use super::raw::{Raw, RawExperiment};
use super::{Refused, Variant};
use crate::error::Error;
use crate::model_description::Experiment;
use crate::models::Model;
use crate::variables::values::{check_value, ValueSet};
use crate::variables::variable::{
    communication_grid, Causality, InputSwitch, Kind, ModelTable, Variable,
};

const SOLVER_PARAMETER: &str = "solver";

/// Checks a variant of one of `models`.
pub fn variant(
    file: &str,
    raw: Raw,
    text: &str,
    models: &'static [Model],
) -> Result<Variant, Refused> {
    let error = |key: &str, error: Error| Refused::at(file, key, error);
    check_name(&raw.name, models).map_err(|m| error("name", m))?;
    // The models with a friction law; DriveTrain has nothing to trim.
    let model = models
        .iter()
        .find(|m| m.table.model_identifier == raw.model);
    let model = model.filter(|m| m.table.law_parameter.is_some());
    let model = model.ok_or_else(|| {
        let known: Vec<&str> = models
            .iter()
            .filter(|m| m.table.law_parameter.is_some())
            .map(|m| m.table.model_identifier)
            .collect();
        error(
            "model",
            Error::value_found(
                "model",
                format!("unknown model \"{}\"", raw.model),
                format!("one of {}", known.join(", ")),
            ),
        )
    })?;
    let table = model.table;
    if let Some(description) = &raw.description {
        if let Some(c) = description.chars().find(|c| c.is_control()) {
            return Err(error(
                "description",
                Error::value_found(
                    "description",
                    format!("the control character {c:?}, which XML cannot carry"),
                    "printable text",
                ),
            ));
        }
    }
    let law_name = table.law_parameter.unwrap_or("law");
    let mut values = ValueSet::start(table);

    // law and solver first: they are enumerations named by item.
    for (key, parameter, item) in [
        ("law", law_name, &raw.law),
        ("solver", SOLVER_PARAMETER, &raw.solver),
    ] {
        let var = table.by_name(parameter).ok_or_else(|| {
            error(
                key,
                Error::refused(
                    format!("{} has no {parameter}", table.model_identifier),
                    "a model with it",
                ),
            )
        })?;
        let value = enum_value(table, var, item).map_err(|m| error(key, m))?;
        values.set(var.value_reference, value);
    }

    for (key, value) in &raw.parameters {
        let full_key = format!("parameters.{key}");
        let var = table.by_name(key).ok_or_else(|| {
            error(
                &full_key,
                Error::refused(
                    format!(
                        "{} has no parameter or input \"{key}\"",
                        table.model_identifier
                    ),
                    format!(
                        "one of {}",
                        names(table, |v| v.causality != Causality::Output)
                    ),
                ),
            )
        })?;
        if var.causality == Causality::Output {
            return Err(error(
                &full_key,
                Error::refused(format!("{key} is an output"), "a parameter or an input"),
            ));
        }
        if var.name == law_name || var.name == SOLVER_PARAMETER {
            let top = if var.name == law_name {
                "law"
            } else {
                SOLVER_PARAMETER
            };
            return Err(error(
                &full_key,
                Error::refused(
                    format!("{key} is set by the top-level key `{top}`"),
                    "it there",
                ),
            ));
        }
        let x = toml_value(table, var, value).map_err(|m| error(&full_key, m))?;
        values.set(var.value_reference, x);
    }

    let mut kept = Vec::new();
    for (key, list, causality, what) in [
        ("tunable", &raw.tunable, Causality::Parameter, "a parameter"),
        ("inputs", &raw.inputs, Causality::Input, "an input"),
        ("outputs", &raw.outputs, Causality::Output, "an output"),
    ] {
        for name in list {
            let var = table
                .by_name(name)
                .filter(|v| v.causality == causality)
                .ok_or_else(|| {
                    error(
                        key,
                        Error::refused(
                            format!("\"{name}\" is not {what} of {}", table.model_identifier),
                            format!("one of {}", names(table, |v| v.causality == causality)),
                        ),
                    )
                })?;
            if kept.contains(&var.value_reference) {
                return Err(error(
                    key,
                    Error::refused(format!("\"{name}\" is listed twice"), "each name once"),
                ));
            }
            kept.push(var.value_reference);
        }
    }
    if raw.outputs.is_empty() {
        return Err(error(
            "outputs",
            Error::refused("the list is empty", "at least one output"),
        ));
    }

    for &InputSwitch {
        switch,
        item,
        input,
    } in table.input_switches
    {
        let (Some(switch_var), Some(input_var)) = (table.by_name(switch), table.by_name(input))
        else {
            continue;
        };
        if kept.contains(&input_var.value_reference) {
            continue;
        }
        let tunable = kept.contains(&switch_var.value_reference);
        if tunable || values.item(switch_var.value_reference) == item {
            let why = if tunable {
                format!("{switch} is tunable, so it may read {input}")
            } else {
                format!("{switch} = {item} reads {input}")
            };
            return Err(error(
                "inputs",
                Error::combination(
                    format!("{why}, but the simulation hides it"),
                    format!("inputs to include \"{input}\""),
                ),
            ));
        }
    }

    // Kept variables in table order: the XML lists them so.
    kept.sort_by_key(|&vr| table.variables.iter().position(|v| v.value_reference == vr));
    let mut experiment = experiment(&raw.experiment).map_err(|(key, m)| error(key, m))?;
    // The DefaultExperiment's tolerance is the one the FMU integrates to, never a second number.
    if let Some(var) = table
        .tolerance_parameter
        .and_then(|name| table.by_name(name))
    {
        let used = values.real(var.value_reference);
        match experiment.tolerance {
            Some(stated) if stated != used => {
                return Err(error(
                    "experiment.tolerance",
                    Error::combination(
                        format!(
                            "tolerance = {stated:e}, but the solver integrates to {} = {used:e}",
                            var.name
                        ),
                        format!(
                            "the same value, or no experiment.tolerance (it then states {})",
                            var.name
                        ),
                    ),
                ))
            }
            _ => experiment.tolerance = Some(used),
        }
    }
    Ok(Variant {
        name: raw.name,
        description: raw
            .description
            .unwrap_or_else(|| table.description.to_string()),
        model,
        values,
        kept,
        experiment,
        text: text.to_string(),
    })
}

/// C keywords (C89 to C23), which no C identifier may be: an importer generating C from the
/// modelDescription would fail on them.
const C_KEYWORDS: &[&str] = &[
    "alignas",
    "alignof",
    "auto",
    "bool",
    "break",
    "case",
    "char",
    "const",
    "constexpr",
    "continue",
    "default",
    "do",
    "double",
    "else",
    "enum",
    "extern",
    "false",
    "float",
    "for",
    "goto",
    "if",
    "inline",
    "int",
    "long",
    "nullptr",
    "register",
    "restrict",
    "return",
    "short",
    "signed",
    "sizeof",
    "static",
    "static_assert",
    "struct",
    "switch",
    "thread_local",
    "true",
    "typedef",
    "typeof",
    "typeof_unqual",
    "union",
    "unsigned",
    "void",
    "volatile",
    "while",
];

/// Names Windows reserves for devices, with any extension: `CON.dll` cannot be a file there.
const WINDOWS_DEVICES: &[&str] = &[
    "con", "prn", "aux", "nul", "com1", "com2", "com3", "com4", "com5", "com6", "com7", "com8",
    "com9", "lpt1", "lpt2", "lpt3", "lpt4", "lpt5", "lpt6", "lpt7", "lpt8", "lpt9",
];

/// A modelIdentifier names the FMU's files and its library's C symbols' prefix: a C identifier
/// that is no keyword, not reserved to C implementations (a leading _), not an FMI function's
/// (fmi2..., fmi3...), no Windows device, and no full model's in any letter case (the files
/// would overwrite each other on a case-insensitive file system).
fn check_name(name: &str, models: &[Model]) -> Result<(), Error> {
    let refused = |found: String| Error::value_found("name", found, "another name");
    let mut chars = name.chars();
    let valid = chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !valid {
        return Err(Error::value_found(
            "name",
            format!("\"{name}\" is not a valid modelIdentifier"),
            "a letter followed by letters, digits or _",
        ));
    }
    let lower = name.to_ascii_lowercase();
    let reserved = if C_KEYWORDS.contains(&name) {
        Some("a C keyword")
    } else if lower.starts_with("fmi2") || lower.starts_with("fmi3") {
        Some("reserved for the FMI functions (fmi2..., fmi3...)")
    } else if WINDOWS_DEVICES.contains(&lower.as_str()) {
        Some("a device name on Windows, where no file may take it")
    } else {
        None
    };
    if let Some(why) = reserved {
        return Err(refused(format!("\"{name}\" is {why}")));
    }
    if let Some(model) = models
        .iter()
        .find(|m| m.table.model_identifier.eq_ignore_ascii_case(name))
    {
        return Err(refused(format!(
            "\"{name}\" is the name of the full model {} up to letter case, and the files would collide on a case-insensitive file system",
            model.table.model_identifier
        )));
    }
    Ok(())
}

fn names(table: &ModelTable, filter: impl Fn(&Variable) -> bool) -> String {
    let names: Vec<&str> = table
        .variables
        .iter()
        .filter(|v| filter(v))
        .map(|v| v.name)
        .collect();
    names.join(", ")
}

/// An enumeration's item by name, through the model's EnumType.
fn enum_value(table: &ModelTable, var: &Variable, item: &str) -> Result<f64, Error> {
    let Kind::Switch { type_name, .. } = var.kind else {
        return Err(Error::refused(
            format!("{} is not an enumeration", var.name),
            "an enumeration",
        ));
    };
    let enum_type = table.enum_type(type_name).ok_or_else(|| {
        Error::refused(
            format!("{} has no type {type_name}", table.model_identifier),
            "the type in the table",
        )
    })?;
    enum_type.value_of(item).map(f64::from).ok_or_else(|| {
        let items: Vec<&str> = enum_type.items.iter().map(|(name, _)| *name).collect();
        Error::value_found(
            var.name,
            format!("\"{item}\" is not an item of {type_name} ({})", var.name),
            format!("one of {}", items.join(", ")),
        )
    })
}

/// A TOML value for a variable, checked against the table's range.
fn toml_value(table: &ModelTable, var: &Variable, value: &toml::Value) -> Result<f64, Error> {
    let wrong = |expected: &str| {
        Error::value_found(
            var.name,
            format!("{} = {}", var.name, shown(value)),
            expected,
        )
    };
    let x = match (var.kind, value) {
        (Kind::Real { .. }, toml::Value::Float(x)) => *x,
        (Kind::Real { .. }, toml::Value::Integer(n)) => *n as f64,
        (Kind::Real { .. }, _) => return Err(wrong("a number")),
        (Kind::Integer { .. }, toml::Value::Integer(n)) => *n as f64,
        (Kind::Integer { .. }, _) => return Err(wrong("an integer")),
        (Kind::Switch { .. }, toml::Value::String(item)) => enum_value(table, var, item)?,
        (Kind::Switch { .. }, _) => return Err(wrong("an item name in quotes")),
    };
    check_value(table, var, x)?;
    Ok(x)
}

fn experiment(raw: &RawExperiment) -> Result<Experiment, (&'static str, Error)> {
    let RawExperiment {
        start,
        stop,
        step,
        tolerance,
    } = *raw;
    if !start.is_finite() {
        return Err((
            "experiment.start",
            Error::value_found("start", format!("start = {start}"), "a finite time"),
        ));
    }
    if !(stop.is_finite() && stop > start) {
        return Err((
            "experiment.stop",
            Error::value_found(
                "stop",
                format!("stop = {stop}"),
                format!("a finite time > start = {start}"),
            ),
        ));
    }
    if !(step.is_finite() && step > 0.0 && step <= stop - start) {
        return Err((
            "experiment.step",
            Error::value_found(
                "step",
                format!("step = {step}"),
                format!("0 < step <= stop - start = {}", stop - start),
            ),
        ));
    }
    communication_grid(start, stop, step).map_err(|e| ("experiment.step", e))?;
    if let Some(tolerance) = tolerance {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err((
                "experiment.tolerance",
                Error::value_found(
                    "tolerance",
                    format!("tolerance = {tolerance}"),
                    "a finite tolerance > 0",
                ),
            ));
        }
    }
    Ok(Experiment {
        start,
        stop,
        step,
        tolerance,
    })
}

/// A TOML value as the file spells it (strings quoted, tables and arrays by their kind).
fn shown(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => format!("\"{s}\""),
        toml::Value::Integer(n) => n.to_string(),
        toml::Value::Float(x) => x.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        other => format!("a {}", other.type_str()),
    }
}
