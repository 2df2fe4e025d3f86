//! Current values of a model's variables, stored in table order.
//!
//! Integers and enumerations are kept as f64 (exact for every i32), so one flat vector holds a
//! whole model and copies, compares and serialises trivially.

use super::variable::{Kind, ModelTable, Variable};
use crate::error::Error;

#[derive(Clone, Debug, PartialEq)]
pub struct ValueSet {
    pub table: &'static ModelTable,
    values: Vec<f64>,
}

impl ValueSet {
    /// All variables at their start values.
    pub fn start(table: &'static ModelTable) -> Self {
        let values = table
            .variables
            .iter()
            .map(|v| match v.kind {
                Kind::Real { start, .. } => start,
                Kind::Switch { start, .. } | Kind::Integer { start, .. } => f64::from(start),
            })
            .collect();
        ValueSet { table, values }
    }

    fn position(&self, value_reference: u32) -> usize {
        self.table
            .variables
            .iter()
            .position(|v| v.value_reference == value_reference)
            // Model code only names value references from its own table (a unit test checks
            // each table), so a miss is a programming error, never user input.
            .unwrap_or_else(|| {
                panic!(
                    "value reference {value_reference} not in {}",
                    self.table.model_identifier
                )
            })
    }

    pub fn real(&self, value_reference: u32) -> f64 {
        self.values[self.position(value_reference)]
    }

    pub fn integer(&self, value_reference: u32) -> i32 {
        self.real(value_reference) as i32
    }

    /// The item name of an enumeration variable's current value.
    pub fn item(&self, value_reference: u32) -> &'static str {
        let var = &self.table.variables[self.position(value_reference)];
        match var.kind {
            Kind::Switch { type_name, .. } => self
                .table
                .enum_type(type_name)
                .and_then(|e| e.item(self.integer(value_reference)))
                .unwrap_or(""),
            _ => "",
        }
    }

    /// Stores a value without checks; callers check first with [`check_value`].
    pub fn set(&mut self, value_reference: u32, value: f64) {
        let i = self.position(value_reference);
        self.values[i] = value;
    }

    /// Stores a value at its variable's position in the table (an index the caller keeps),
    /// without checks, as [`ValueSet::set`].
    pub fn set_at(&mut self, position: usize, value: f64) {
        self.values[position] = value;
    }

    pub fn as_slice(&self) -> &[f64] {
        &self.values
    }

    /// Restores values saved with [`ValueSet::as_slice`]; false if the length does not match.
    pub fn load(&mut self, values: &[f64]) -> bool {
        if values.len() != self.values.len() {
            return false;
        }
        self.values.copy_from_slice(values);
        true
    }
}

/// Whether `value` may be stored in `var`: finite, within the table's range, a known item.
/// The error says what was expected, for the FMI logger.
pub fn check_value(table: &ModelTable, var: &Variable, value: f64) -> Result<(), Error> {
    let name = var.name;
    if !matches!(var.kind, Kind::Real { .. }) && (!value.is_finite() || value.fract() != 0.0) {
        return Err(Error::value_found(
            name,
            format!("{name} = {}", number(value)),
            "a whole number",
        ));
    }
    match var.kind {
        Kind::Real { min, max, unit, .. } => {
            if !value.is_finite() {
                return Err(Error::value_found(
                    name,
                    format!("{name} = {value}"),
                    "a finite number",
                ));
            }
            if value < min || value > max {
                return Err(Error::value(
                    name,
                    number(value),
                    format!(
                        "{} ({})",
                        range_text(name, min, max),
                        if unit.is_empty() { "no unit" } else { unit }
                    ),
                ));
            }
        }
        Kind::Integer { min, max, .. } => {
            if value < f64::from(min) || value > f64::from(max) {
                return Err(Error::value(
                    name,
                    value,
                    format!("an integer in [{min}, {max}]"),
                ));
            }
        }
        Kind::Switch { type_name, .. } => {
            let items = table.enum_type(type_name).map(|e| e.items).unwrap_or(&[]);
            if value < 1.0 || value > items.len() as f64 {
                let names: Vec<String> = items
                    .iter()
                    .enumerate()
                    .map(|(i, (name, _))| format!("{} = {name}", i + 1))
                    .collect();
                return Err(Error::value_found(
                    name,
                    format!("{name} = {value} is not an item of {type_name}"),
                    format!("one of {}", names.join(", ")),
                ));
            }
        }
    }
    Ok(())
}

/// A number as a person reads it: plain between 1e-4 and 1e6, else in exponent form (so 1e-300
/// is not three hundred zeros).
pub fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

fn range_text(name: &str, min: f64, max: f64) -> String {
    let (lo, hi) = (number(min), number(max));
    if min == f64::MIN_POSITIVE {
        return if max.is_finite() {
            format!("0 < {name} <= {hi}")
        } else {
            format!("{name} > 0")
        };
    }
    match (min.is_finite(), max.is_finite()) {
        (true, true) => format!("{lo} <= {name} <= {hi}"),
        (true, false) => format!("{name} >= {lo}"),
        (false, true) => format!("{name} <= {hi}"),
        (false, false) => format!("{name} finite"),
    }
}
