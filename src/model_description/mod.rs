//! The one modelDescription.xml writer, for FMI 2.0 and FMI 3.0 (`fmi3`) from the same
//! [`Description`]: full models (written by `build.rs`, which includes this module with
//! `#[path]`) and the trimmed interfaces of variants (written by the library when it packs one,
//! and again at instantiation to check its GUID) come from the same code.
//!
//! Like `src/variables`, it depends only on that module (as `crate::interface`), serde and
//! quick-xml, so it compiles the same in both places.

mod fmi3;
mod fmi3_xml;
mod xml;

pub use fmi3::{TIME_NAME, TIME_VALUE_REFERENCE};

use crate::variables::variable::{Causality, EnumType, Kind, ModelTable, Variable, UNITS};
use xml::*;

/// The DefaultExperiment; `tolerance` is left out of the XML when None.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Experiment {
    pub start: f64,
    pub stop: f64,
    pub step: f64,
    pub tolerance: Option<f64>,
}

/// Everything one modelDescription.xml says: the variables it lists (a whole table, or the part
/// a variant keeps) with their start values, and the model's name and experiment.
pub struct Description<'a> {
    pub model_identifier: &'a str,
    pub description: &'a str,
    /// In the order ModelVariables lists them (their 1-based indices are used by ModelStructure).
    pub variables: &'a [&'a Variable],
    /// Start values that replace the table's, by value reference.
    pub starts: &'a [(u32, f64)],
    /// The model's enumeration types; the XML declares those the variables use.
    pub enum_types: &'a [EnumType],
    pub experiment: Experiment,
    /// canInterpolateInputs, and first output derivatives (maxOutputDerivativeOrder = 1).
    pub interpolates_inputs: bool,
    /// What the XML does not show but the FMU runs with (a variant's model and hidden values),
    /// hashed into the GUID with the XML so that changing any of it changes the GUID; empty for a
    /// full model.
    pub hidden: &'a str,
}

impl<'a> Description<'a> {
    /// A whole model table, as `build.rs` writes it.
    pub fn full(table: &'a ModelTable, variables: &'a [&'a Variable]) -> Self {
        let e = table.default_experiment;
        Description {
            model_identifier: table.model_identifier,
            description: table.description,
            variables,
            starts: &[],
            enum_types: table.enum_types,
            experiment: Experiment {
                start: e.start_time,
                stop: e.stop_time,
                step: e.step_size,
                tolerance: Some(e.tolerance),
            },
            interpolates_inputs: table.interpolates_inputs,
            hidden: "",
        }
    }

    /// The XML and its GUID: the GUID hashes the XML written with an empty GUID (and `hidden`),
    /// then takes its place, so an FMU's binary can recompute it from what it describes.
    pub fn write(&self) -> (String, String) {
        let guid = guid_of(&(to_xml(&self.model_description("")) + self.hidden));
        let xml = to_xml(&self.model_description(&guid));
        (guid, xml)
    }

    fn start(&self, v: &Variable) -> Option<f64> {
        self.starts
            .iter()
            .find(|(vr, _)| *vr == v.value_reference)
            .map(|&(_, x)| x)
    }

    /// A variable's type attributes, which both standards write alike: FMI 2.0 as the
    /// ScalarVariable's Real or Integer element, FMI 3.0 on its Float64 or Int32 element.
    fn kind(&self, v: &Variable) -> KindXml<'static> {
        let start = self.start(v);
        match v.kind {
            Kind::Real {
                start: table_start,
                unit,
                min,
                max,
            } => KindXml::Real {
                unit: (!unit.is_empty()).then_some(unit),
                // Calculated outputs may not carry a start value.
                start: (v.causality != Causality::Output)
                    .then(|| number(start.unwrap_or(table_start))),
                min: finite(min),
                max: finite(max),
            },
            Kind::Integer {
                start: table_start,
                min,
                max,
            } => KindXml::Integer {
                declared_type: None,
                start: start.map_or(table_start, |x| x as i32),
                min,
                max,
            },
            Kind::Switch {
                type_name,
                start: table_start,
            } => KindXml::Integer {
                declared_type: Some(type_name),
                start: start.map_or(table_start, |x| x as i32),
                min: 1,
                max: self.switch_type(type_name).items.len() as i32,
            },
        }
    }

    /// A variable's description; a switch's numbers its items, as its type's does.
    fn variable_description(&self, v: &Variable) -> String {
        match v.kind {
            Kind::Switch { type_name, .. } => format!(
                "{} ({})",
                v.description,
                self.switch_type(type_name).listing()
            ),
            _ => v.description.to_string(),
        }
    }

    /// The attributes both standards start a variable's element with.
    fn variable_head(&self, v: &Variable) -> VariableHead<'static> {
        VariableHead {
            name: v.name,
            value_reference: v.value_reference,
            description: self.variable_description(v),
            causality: causality(v.causality),
            variability: variability(v.variability),
        }
    }

    fn scalar_variable(&self, v: &Variable) -> ScalarVariable<'static> {
        ScalarVariable {
            head: self.variable_head(v),
            kind: self.kind(v),
        }
    }

    fn switch_type(&self, name: &str) -> &EnumType {
        self.enum_types
            .iter()
            .find(|e| e.name == name)
            .expect("every switch names a type of its table (interface tests)")
    }

    fn uses_unit(&self, name: &str) -> bool {
        self.variables
            .iter()
            .any(|v| matches!(v.kind, Kind::Real { unit, .. } if unit == name))
    }

    /// The enumeration types the listed switches use, in the model's order.
    fn used_types(&self) -> impl Iterator<Item = &EnumType> {
        self.enum_types.iter().filter(|e| {
            self.variables
                .iter()
                .any(|v| matches!(v.kind, Kind::Switch { type_name, .. } if type_name == e.name))
        })
    }

    /// The listed outputs with their ModelVariables indices (1-based, in list order).
    fn outputs(&self) -> Vec<(usize, &Variable)> {
        self.variables
            .iter()
            .enumerate()
            .filter(|(_, v)| v.causality == Causality::Output)
            .map(|(i, v)| (i + 1, *v))
            .collect()
    }

    /// What `v` depends on, space-separated, each named by `name` from its index and value
    /// reference (FMI 2.0 names the index, FMI 3.0 the value reference). A dependency on an
    /// input the list leaves out (a variant's hidden input, held at its value) is no dependency.
    fn dependencies(&self, v: &Variable, name: impl Fn(usize, u32) -> String) -> String {
        v.depends_on
            .iter()
            .filter_map(|&vr| {
                let index = self
                    .variables
                    .iter()
                    .position(|v| v.value_reference == vr)?;
                Some(name(index + 1, vr))
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    fn model_structure(&self) -> ModelStructure {
        let outputs = self.outputs();
        ModelStructure {
            outputs: Unknowns {
                unknowns: outputs
                    .iter()
                    .map(|&(index, v)| Unknown {
                        index,
                        dependencies: Some(self.dependencies(v, |index, _| index.to_string())),
                    })
                    .collect(),
            },
            // Every output is calculated at initialisation from all parameters and inputs.
            initial_unknowns: Unknowns {
                unknowns: outputs
                    .iter()
                    .map(|&(index, _)| Unknown {
                        index,
                        dependencies: None,
                    })
                    .collect(),
            },
        }
    }

    /// The units `listed` keeps, in [`UNITS`] order.
    fn unit_definitions(&self, listed: &dyn Fn(&str) -> bool) -> UnitDefinitions<'static> {
        UnitDefinitions {
            units: UNITS
                .iter()
                .filter(|u| listed(u.name))
                .map(|u| UnitXml {
                    name: u.name,
                    base: BaseUnit {
                        kg: u.kg,
                        m: u.m,
                        s: u.s,
                        a: u.a,
                        rad: u.rad,
                        factor: (u.name == "%").then_some(0.01),
                    },
                })
                .collect(),
        }
    }

    /// The log categories, `logCalls` described as `log_calls` if given (each standard names its
    /// own functions) and as the table has it (FMI 2.0's) if not.
    fn log_categories(log_calls: Option<&'static str>) -> LogCategories<'static> {
        LogCategories {
            categories: crate::variables::variable::LOG_CATEGORIES
                .iter()
                .map(|&(name, description)| Category {
                    name,
                    description: match log_calls {
                        Some(calls) if name == "logCalls" => calls,
                        _ => description,
                    },
                })
                .collect(),
        }
    }

    fn default_experiment(&self) -> DefaultExperimentXml {
        DefaultExperimentXml {
            start_time: self.experiment.start,
            stop_time: self.experiment.stop,
            tolerance: self.experiment.tolerance,
            step_size: self.experiment.step,
        }
    }

    fn model_description<'b>(&'b self, guid: &'b str) -> ModelDescription<'b> {
        ModelDescription {
            fmi_version: "2.0",
            model_name: self.model_identifier,
            guid,
            description: self.description,
            generation_tool: concat!("friction-fmu ", env!("CARGO_PKG_VERSION")),
            naming: "flat",
            event_indicators: 0,
            co_simulation: CoSimulation {
                model_identifier: self.model_identifier,
                needs_execution_tool: false,
                variable_step: true,
                interpolate_inputs: self.interpolates_inputs,
                max_output_derivative_order: self.interpolates_inputs.into(),
                asynchronous: false,
                once_per_process: false,
                no_memory_functions: true,
                get_set_state: true,
                serialize_state: true,
                directional_derivative: false,
            },
            units: self.unit_definitions(&|name| self.uses_unit(name)),
            types: TypeDefinitions {
                types: self
                    .used_types()
                    .map(|e| SimpleType {
                        name: e.name,
                        description: e.listing(),
                        integer: IntegerType {
                            min: 1,
                            max: e.items.len() as i32,
                        },
                    })
                    .collect(),
            },
            log_categories: Self::log_categories(None),
            default_experiment: self.default_experiment(),
            variables: ModelVariables {
                variables: self
                    .variables
                    .iter()
                    .map(|v| self.scalar_variable(v))
                    .collect(),
            },
            structure: self.model_structure(),
        }
    }
}

/// FNV-1a, twice with different offsets: a stable 128-bit content hash without a dependency.
pub fn guid_of(text: &str) -> String {
    let fnv = |offset: u64| {
        text.bytes().fold(offset, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
        })
    };
    let (a, b) = (fnv(0xcbf2_9ce4_8422_2325), fnv(0x6c62_272e_07bb_0142));
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}

#[cfg(test)]
mod tests {
    use super::Description;
    use crate::package::{committed_xml_path, model_description_for, Standard};
    use crate::variables::variable::Variable;

    /// Oracle: the XML and GUID `build.rs` wrote into OUT_DIR: the library's writer, which also
    /// writes variants, gives the same bytes for a whole table, in both standards, and FMI 3.0's
    /// instantiationToken is FMI 2.0's GUID.
    #[test]
    fn library_writes_the_full_models_as_the_build_script_did() {
        for table in crate::models::MODELS.iter().map(|m| m.table) {
            let variables: Vec<&Variable> = table.variables.iter().collect();
            let description = Description::full(table, &variables);
            let (guid, xml) = description.write();
            let id = table.model_identifier;
            assert_eq!(Some(xml.as_str()), crate::package::model_description(id));
            assert_eq!(Some(guid.as_str()), crate::fmi2::guid(id));
            let xml3 = description.write_fmi3(&guid);
            assert_eq!(
                Some(xml3.as_str()),
                model_description_for(Standard::Fmi3, id)
            );
            assert!(xml3.contains(&format!(" instantiationToken=\"{guid}\" ")));
        }
    }

    /// The committed modelDescription/ (FMI 2.0) and modelDescription/fmi3/ are what this build
    /// packs: an interface changed without `friction-fmu build` (which refreshes the copies)
    /// fails here, naming the file.
    #[test]
    fn committed_model_descriptions_are_current() {
        for table in crate::models::MODELS.iter().map(|m| m.table) {
            let id = table.model_identifier;
            for standard in [Standard::Fmi2, Standard::Fmi3] {
                let path = committed_xml_path(standard, id);
                let committed = std::fs::read_to_string(&path).unwrap_or_default();
                assert!(
                    Some(committed.as_str()) == model_description_for(standard, id),
                    "{} is not this build's modelDescription.xml: run `cargo run --release -- build` and commit it",
                    path.display()
                );
            }
        }
    }
}
