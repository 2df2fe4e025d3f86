//! The FMI 3.0 modelDescription.xml of the same [`Description`] the FMI 2.0 one is written from:
//! the same variables, value references, start values, units and experiment, so the two FMUs of
//! a model differ only in what each standard spells differently.

use super::fmi3_xml::*;
use super::xml::{to_xml, KindXml, VariableHead};
use super::Description;
use crate::variables::variable::{Causality, Variability, Variable};

/// The value reference of `time`, the independent variable FMI 3.0 requires every FMU to
/// declare (FMI 2.0 leaves it implicit); no table uses it.
pub const TIME_VALUE_REFERENCE: u32 = 0;

/// The name of the independent variable.
pub const TIME_NAME: &str = "time";

/// What `logCalls` logs, in FMI 3.0's names; the categories are those of FMI 2.0.
const LOG_CALLS: &str = "The calls that change the instance, with their arguments: fmi3Enter/ExitInitializationMode, fmi3SetXXX, fmi3DoStep, fmi3Get/Set/DeSerializeFMUState, fmi3Terminate, fmi3Reset";

impl Description<'_> {
    /// The FMI 3.0 modelDescription.xml. Its instantiationToken is `token`: the GUID of the FMI
    /// 2.0 description ([`Description::write`]), so that one library checks one string whichever
    /// standard instantiates it.
    pub fn write_fmi3(&self, token: &str) -> String {
        to_xml(&self.model_description3(token))
    }

    /// The variable with the type attributes FMI 2.0 writes ([`Description::kind`]), on the
    /// element FMI 3.0 names after the type.
    fn variable3<'b>(&'b self, v: &'b Variable) -> Variable3<'b> {
        let head = self.variable_head(v);
        match self.kind(v) {
            KindXml::Real {
                unit,
                start,
                min,
                max,
            } => Variable3::Float64 {
                head,
                // Every continuous input is read at the FMU's own steps inside a doStep.
                intermediate_update: (v.causality == Causality::Input
                    && v.variability == Variability::Continuous)
                    .then_some(true),
                unit,
                start,
                min,
                max,
            },
            KindXml::Integer {
                declared_type,
                start,
                min,
                max,
            } => Variable3::Int32 {
                head,
                declared_type,
                start,
                min,
                max,
            },
        }
    }

    /// The units the FMI 3.0 description names, in the order of the unit table: `s` (time's)
    /// and every unit of a listed Real.
    fn units_used3(&self) -> Vec<&'static str> {
        crate::variables::variable::UNITS
            .iter()
            .map(|u| u.name)
            .filter(|&name| name == "s" || self.uses_unit(name))
            .collect()
    }

    fn time_variable() -> Variable3<'static> {
        Variable3::Float64 {
            head: VariableHead {
                name: TIME_NAME,
                value_reference: TIME_VALUE_REFERENCE,
                description: "Simulation time".to_string(),
                causality: "independent",
                variability: "continuous",
            },
            intermediate_update: None,
            unit: Some("s"),
            start: None,
            min: None,
            max: None,
        }
    }

    fn model_structure3(&self) -> ModelStructure3 {
        let outputs = self.outputs();
        ModelStructure3 {
            outputs: outputs
                .iter()
                .map(|&(_, v)| Unknown3 {
                    value_reference: v.value_reference,
                    dependencies: Some(self.dependencies(v, |_, vr| vr.to_string())),
                })
                .collect(),
            // Every output is calculated at initialisation from all parameters and inputs.
            initial_unknowns: outputs
                .iter()
                .map(|&(_, v)| Unknown3 {
                    value_reference: v.value_reference,
                    dependencies: None,
                })
                .collect(),
        }
    }

    fn model_description3<'b>(&'b self, token: &'b str) -> ModelDescription3<'b> {
        let mut variables = vec![Self::time_variable()];
        variables.extend(self.variables.iter().map(|v| self.variable3(v)));
        ModelDescription3 {
            fmi_version: "3.0",
            model_name: self.model_identifier,
            instantiation_token: token,
            description: self.description,
            generation_tool: concat!("friction-fmu ", env!("CARGO_PKG_VERSION")),
            naming: "flat",
            co_simulation: CoSimulation3 {
                model_identifier: self.model_identifier,
                needs_execution_tool: false,
                once_per_process: false,
                get_set_state: true,
                serialize_state: true,
                directional_derivatives: false,
                variable_step: true,
                max_output_derivative_order: self.interpolates_inputs.into(),
                intermediate_update: true,
                might_return_early: false,
                return_early_after_intermediate_update: false,
                event_mode: false,
            },
            // `time` is in seconds.
            units: self.unit_definitions(&|name| self.units_used3().contains(&name)),
            types: TypeDefinitions3 {
                units: self
                    .units_used3()
                    .into_iter()
                    .map(|unit| Float64Type { name: unit, unit })
                    .collect(),
                types: self
                    .used_types()
                    .map(|e| Int32Type {
                        name: e.name,
                        description: e.listing(),
                        min: 1,
                        max: e.items.len() as i32,
                    })
                    .collect(),
            },
            log_categories: Self::log_categories(Some(LOG_CALLS)),
            default_experiment: self.default_experiment(),
            variables: ModelVariables3 { variables },
            structure: self.model_structure3(),
        }
    }
}
