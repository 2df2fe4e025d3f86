//! What a variant's FMU shows: its modelDescription.xml for FMI 2.0 and FMI 3.0 (from the one
//! writer), its GUID (FMI 3.0's instantiationToken), the
//! [`Scope`] its instances run in, and the values it fixes.

use super::Variant;
use crate::model_description::Description;
use crate::models::Scope;
use crate::variables::variable::{Causality, Kind, Variable};
use std::fmt::Write as _;

impl Variant {
    /// The kept variables, in table order.
    pub fn kept_variables(&self) -> Vec<&'static Variable> {
        self.model
            .table
            .variables
            .iter()
            .filter(|v| self.kept.contains(&v.value_reference))
            .collect()
    }

    /// Parameters and inputs the simulation hides, with the value each is fixed at.
    pub fn fixed(&self) -> Vec<(&'static Variable, f64)> {
        self.model
            .table
            .variables
            .iter()
            .filter(|v| v.causality != Causality::Output && !self.kept.contains(&v.value_reference))
            .map(|v| (v, self.values.real(v.value_reference)))
            .collect()
    }

    /// A value as a person reads it: enumerations by item name.
    pub fn value_text(&self, var: &Variable) -> String {
        match var.kind {
            Kind::Switch { .. } => self.values.item(var.value_reference).to_string(),
            _ => crate::variables::values::number(self.values.real(var.value_reference)),
        }
    }

    /// The trimmed modelDescription.xml and its GUID (the hash `build.rs` uses for full models).
    pub fn model_description(&self) -> (String, String) {
        self.with_description(|description| description.write())
    }

    /// The trimmed FMI 3.0 modelDescription.xml and its instantiationToken: the same string as
    /// the FMI 2.0 GUID ([`Self::model_description`]), so one library checks one string for both.
    pub fn model_description_fmi3(&self) -> (String, String) {
        self.with_description(|description| {
            let (guid, _) = description.write();
            let xml = description.write_fmi3(&guid);
            (guid, xml)
        })
    }

    /// Calls `write` with the description of the kept interface.
    fn with_description<R>(&self, write: impl FnOnce(&Description) -> R) -> R {
        let variables = self.kept_variables();
        let starts: Vec<(u32, f64)> = variables
            .iter()
            .filter(|v| v.causality != Causality::Output)
            .map(|v| (v.value_reference, self.values.real(v.value_reference)))
            .collect();
        // The model and every fixed value, exactly (their bits): an FMU whose variant was
        // edited anywhere that matters no longer matches its GUID.
        let mut hidden = format!("\nmodel={}", self.model.table.model_identifier);
        for (var, value) in self.fixed() {
            let _ = write!(hidden, ";{}={:016x}", var.value_reference, value.to_bits());
        }
        let keeps_input = variables.iter().any(|v| v.causality == Causality::Input);
        write(&Description {
            model_identifier: &self.name,
            description: &self.description,
            variables: &variables,
            starts: &starts,
            enum_types: self.model.table.enum_types,
            experiment: self.experiment,
            // Only a kept input can be interpolated; the output derivatives come with it.
            interpolates_inputs: keeps_input && self.model.table.interpolates_inputs,
            hidden: &hidden,
        })
    }

    /// What an instance of this FMU hides: every variable not kept.
    pub fn scope(&self) -> Scope {
        Scope::hiding(
            self.model
                .table
                .variables
                .iter()
                .map(|v| v.value_reference)
                .filter(|vr| !self.kept.contains(vr))
                .collect(),
        )
    }
}
