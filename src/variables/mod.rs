//! What a model's variable table is made of (variables, their kinds and units, the values an
//! instance holds), and the checks on it; each model's table is in `src/models/<model>/table.rs`.
//!
//! `build.rs` includes this module and the tables too (with `#[path]` and `include!`) to write
//! modelDescription.xml, so nothing here may refer to the rest of the crate.

pub mod declare;
pub mod unread_inputs;
pub mod values;
pub mod variable;

#[cfg(test)]
mod tests {
    use super::values::{check_value, ValueSet};
    use super::variable::{communication_grid, Causality, Kind, NO_UNIT, UNITS};

    /// Every table is self-consistent: unique names and value references, start values inside
    /// their ranges, enumeration defaults that name an item, output dependencies on inputs,
    /// units declared in the unit table (the XML writer drops a unit it cannot find), and a
    /// DefaultExperiment whose grid is whole and whose tolerance is the one integrated to.
    #[test]
    fn every_table_is_consistent() {
        for table in crate::models::MODELS.iter().map(|m| m.table) {
            let vars = table.variables;
            for (i, a) in vars.iter().enumerate() {
                for b in &vars[i + 1..] {
                    assert_ne!(a.name, b.name, "{}: duplicate name", table.model_identifier);
                    assert_ne!(
                        a.value_reference, b.value_reference,
                        "{}: {} and {} share a value reference",
                        table.model_identifier, a.name, b.name
                    );
                }
                let start = ValueSet::start(table).real(a.value_reference);
                if a.causality != Causality::Output {
                    assert_eq!(
                        check_value(table, a, start),
                        Ok(()),
                        "{}: start of {}",
                        table.model_identifier,
                        a.name
                    );
                }
                if let Kind::Real { unit, .. } = a.kind {
                    assert!(
                        unit == NO_UNIT || UNITS.iter().any(|u| u.name == unit),
                        "{}: {} has unit {unit:?}, not in UNITS",
                        table.model_identifier,
                        a.name
                    );
                }
                if let Kind::Switch { type_name, .. } = a.kind {
                    assert!(
                        table.enum_type(type_name).is_some(),
                        "{}: no type {type_name}",
                        a.name
                    );
                }
                for &input in a.depends_on {
                    assert_eq!(
                        table.variable(input).map(|v| v.causality),
                        Some(Causality::Input),
                        "{}: depends on a non-input",
                        a.name
                    );
                }
            }
            let experiment = table.default_experiment;
            // The DefaultExperiment states the tolerance the FMU integrates to by default.
            if let Some(name) = table.tolerance_parameter {
                let tolerance = table.by_name(name).expect("the tolerance parameter");
                assert_eq!(
                    ValueSet::start(table).real(tolerance.value_reference),
                    experiment.tolerance,
                    "{}: DefaultExperiment tolerance",
                    table.model_identifier
                );
            }
            assert_eq!(
                communication_grid(
                    experiment.start_time,
                    experiment.stop_time,
                    experiment.step_size
                )
                .map(|_| ()),
                Ok(()),
                "{}: DefaultExperiment",
                table.model_identifier
            );
            for governed in table.input_switches {
                let Some(Kind::Switch { type_name, .. }) =
                    table.by_name(governed.switch).map(|v| v.kind)
                else {
                    panic!(
                        "{}: {} is not a switch",
                        table.model_identifier, governed.switch
                    );
                };
                assert!(table
                    .enum_type(type_name)
                    .and_then(|t| t.value_of(governed.item))
                    .is_some());
                assert_eq!(
                    table.by_name(governed.input).map(|v| v.causality),
                    Some(Causality::Input)
                );
            }
        }
    }
}
