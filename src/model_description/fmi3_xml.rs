//! The XML shape of modelDescription.xml (FMI 3.0), as serde structs for quick-xml. Units, log
//! categories and the default experiment are written as in FMI 2.0 ([`super::xml`]), and so is
//! the document around them ([`super::xml::to_xml`]).

use super::xml::{DefaultExperimentXml, LogCategories, UnitDefinitions, VariableHead};
use serde::Serialize;

#[derive(Serialize)]
#[serde(rename = "fmiModelDescription")]
pub struct ModelDescription3<'a> {
    #[serde(rename = "@fmiVersion")]
    pub fmi_version: &'a str,
    #[serde(rename = "@modelName")]
    pub model_name: &'a str,
    #[serde(rename = "@instantiationToken")]
    pub instantiation_token: &'a str,
    #[serde(rename = "@description")]
    pub description: &'a str,
    #[serde(rename = "@generationTool")]
    pub generation_tool: &'a str,
    #[serde(rename = "@variableNamingConvention")]
    pub naming: &'a str,
    #[serde(rename = "CoSimulation")]
    pub co_simulation: CoSimulation3<'a>,
    #[serde(rename = "UnitDefinitions")]
    pub units: UnitDefinitions<'a>,
    #[serde(
        rename = "TypeDefinitions",
        skip_serializing_if = "TypeDefinitions3::is_empty"
    )]
    pub types: TypeDefinitions3<'a>,
    #[serde(rename = "LogCategories")]
    pub log_categories: LogCategories<'a>,
    #[serde(rename = "DefaultExperiment")]
    pub default_experiment: DefaultExperimentXml,
    #[serde(rename = "ModelVariables")]
    pub variables: ModelVariables3<'a>,
    #[serde(rename = "ModelStructure")]
    pub structure: ModelStructure3,
}

/// The capability flags: plain fields, one per attribute, each written even where it is the
/// schema's default, so that a reader sees every promise the FMU makes.
#[derive(Serialize)]
pub struct CoSimulation3<'a> {
    #[serde(rename = "@modelIdentifier")]
    pub model_identifier: &'a str,
    #[serde(rename = "@needsExecutionTool")]
    pub needs_execution_tool: bool,
    #[serde(rename = "@canBeInstantiatedOnlyOncePerProcess")]
    pub once_per_process: bool,
    #[serde(rename = "@canGetAndSetFMUState")]
    pub get_set_state: bool,
    #[serde(rename = "@canSerializeFMUState")]
    pub serialize_state: bool,
    #[serde(rename = "@providesDirectionalDerivatives")]
    pub directional_derivatives: bool,
    #[serde(rename = "@canHandleVariableCommunicationStepSize")]
    pub variable_step: bool,
    #[serde(rename = "@maxOutputDerivativeOrder")]
    pub max_output_derivative_order: u32,
    #[serde(rename = "@providesIntermediateUpdate")]
    pub intermediate_update: bool,
    #[serde(rename = "@mightReturnEarlyFromDoStep")]
    pub might_return_early: bool,
    #[serde(rename = "@canReturnEarlyAfterIntermediateUpdate")]
    pub return_early_after_intermediate_update: bool,
    #[serde(rename = "@hasEventMode")]
    pub event_mode: bool,
}

#[derive(Serialize)]
pub struct TypeDefinitions3<'a> {
    #[serde(rename = "Float64Type")]
    pub units: Vec<Float64Type<'a>>,
    #[serde(rename = "Int32Type")]
    pub types: Vec<Int32Type<'a>>,
}

impl TypeDefinitions3<'_> {
    fn is_empty(&self) -> bool {
        self.units.is_empty() && self.types.is_empty()
    }
}

/// A unit's type, named as the unit: Float64 variables name their unit through it, as the
/// Reference FMUs do, rather than by a `unit` attribute of their own, which importers built on
/// the `fmi-schema` crate refuse (docs/interoperability.md, "FMI 3.0").
#[derive(Serialize)]
pub struct Float64Type<'a> {
    #[serde(rename = "@name")]
    pub name: &'a str,
    #[serde(rename = "@unit")]
    pub unit: &'a str,
}

/// A switch's type: an Int32 range whose description numbers the items ("1 split, 2 total").
/// Not an Enumeration: ecos skips FMI 3.0 Enumeration variables, so a switch declared one could
/// not be set there (docs/interoperability.md, "FMI 3.0").
#[derive(Serialize)]
pub struct Int32Type<'a> {
    #[serde(rename = "@name")]
    pub name: &'a str,
    #[serde(rename = "@description")]
    pub description: String,
    #[serde(rename = "@min")]
    pub min: i32,
    #[serde(rename = "@max")]
    pub max: i32,
}

#[derive(Serialize)]
pub struct ModelVariables3<'a> {
    #[serde(rename = "$value")]
    pub variables: Vec<Variable3<'a>>,
}

/// One variable: the element's name is its type.
#[derive(Serialize)]
pub enum Variable3<'a> {
    Float64 {
        #[serde(flatten)]
        head: VariableHead<'a>,
        /// Only on inputs the FMU reads inside a step (set in Intermediate Update Mode).
        #[serde(
            rename = "@intermediateUpdate",
            skip_serializing_if = "Option::is_none"
        )]
        intermediate_update: Option<bool>,
        /// The unit's type ([`Float64Type`]).
        #[serde(rename = "@declaredType", skip_serializing_if = "Option::is_none")]
        unit: Option<&'a str>,
        #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
        start: Option<String>,
        #[serde(rename = "@min", skip_serializing_if = "Option::is_none")]
        min: Option<String>,
        #[serde(rename = "@max", skip_serializing_if = "Option::is_none")]
        max: Option<String>,
    },
    Int32 {
        #[serde(flatten)]
        head: VariableHead<'a>,
        #[serde(rename = "@declaredType", skip_serializing_if = "Option::is_none")]
        declared_type: Option<&'a str>,
        #[serde(rename = "@start")]
        start: i32,
        #[serde(rename = "@min")]
        min: i32,
        #[serde(rename = "@max")]
        max: i32,
    },
}

/// FMI 3.0 names unknowns and their dependencies by value reference, not by index.
#[derive(Serialize)]
pub struct ModelStructure3 {
    #[serde(rename = "Output")]
    pub outputs: Vec<Unknown3>,
    #[serde(rename = "InitialUnknown")]
    pub initial_unknowns: Vec<Unknown3>,
}

#[derive(Serialize)]
pub struct Unknown3 {
    #[serde(rename = "@valueReference")]
    pub value_reference: u32,
    #[serde(rename = "@dependencies", skip_serializing_if = "Option::is_none")]
    pub dependencies: Option<String>,
}
