//! The XML shape of modelDescription.xml (FMI 2.0), as serde structs for quick-xml.

use crate::variables::variable::{Causality, Variability};
use serde::Serialize;

#[derive(Serialize)]
#[serde(rename = "fmiModelDescription")]
pub struct ModelDescription<'a> {
    #[serde(rename = "@fmiVersion")]
    pub fmi_version: &'a str,
    #[serde(rename = "@modelName")]
    pub model_name: &'a str,
    #[serde(rename = "@guid")]
    pub guid: &'a str,
    #[serde(rename = "@description")]
    pub description: &'a str,
    #[serde(rename = "@generationTool")]
    pub generation_tool: &'a str,
    #[serde(rename = "@variableNamingConvention")]
    pub naming: &'a str,
    #[serde(rename = "@numberOfEventIndicators")]
    pub event_indicators: u32,
    #[serde(rename = "CoSimulation")]
    pub co_simulation: CoSimulation<'a>,
    #[serde(rename = "UnitDefinitions")]
    pub units: UnitDefinitions<'a>,
    #[serde(
        rename = "TypeDefinitions",
        skip_serializing_if = "TypeDefinitions::is_empty"
    )]
    pub types: TypeDefinitions<'a>,
    #[serde(rename = "LogCategories")]
    pub log_categories: LogCategories<'a>,
    #[serde(rename = "DefaultExperiment")]
    pub default_experiment: DefaultExperimentXml,
    #[serde(rename = "ModelVariables")]
    pub variables: ModelVariables<'a>,
    #[serde(rename = "ModelStructure")]
    pub structure: ModelStructure,
}

/// The capability flags: plain fields, one per attribute.
#[derive(Serialize)]
pub struct CoSimulation<'a> {
    #[serde(rename = "@modelIdentifier")]
    pub model_identifier: &'a str,
    #[serde(rename = "@needsExecutionTool")]
    pub needs_execution_tool: bool,
    #[serde(rename = "@canHandleVariableCommunicationStepSize")]
    pub variable_step: bool,
    #[serde(rename = "@canInterpolateInputs")]
    pub interpolate_inputs: bool,
    #[serde(rename = "@maxOutputDerivativeOrder")]
    pub max_output_derivative_order: u32,
    #[serde(rename = "@canRunAsynchronuously")]
    pub asynchronous: bool,
    #[serde(rename = "@canBeInstantiatedOnlyOncePerProcess")]
    pub once_per_process: bool,
    #[serde(rename = "@canNotUseMemoryManagementFunctions")]
    pub no_memory_functions: bool,
    #[serde(rename = "@canGetAndSetFMUstate")]
    pub get_set_state: bool,
    #[serde(rename = "@canSerializeFMUstate")]
    pub serialize_state: bool,
    #[serde(rename = "@providesDirectionalDerivative")]
    pub directional_derivative: bool,
}

#[derive(Serialize)]
pub struct UnitDefinitions<'a> {
    #[serde(rename = "Unit")]
    pub units: Vec<UnitXml<'a>>,
}

#[derive(Serialize)]
pub struct UnitXml<'a> {
    #[serde(rename = "@name")]
    pub name: &'a str,
    #[serde(rename = "BaseUnit")]
    pub base: BaseUnit,
}

#[derive(Serialize)]
pub struct BaseUnit {
    #[serde(rename = "@kg", skip_serializing_if = "is_zero")]
    pub kg: i32,
    #[serde(rename = "@m", skip_serializing_if = "is_zero")]
    pub m: i32,
    #[serde(rename = "@s", skip_serializing_if = "is_zero")]
    pub s: i32,
    #[serde(rename = "@A", skip_serializing_if = "is_zero")]
    pub a: i32,
    #[serde(rename = "@rad", skip_serializing_if = "is_zero")]
    pub rad: i32,
    #[serde(rename = "@factor", skip_serializing_if = "Option::is_none")]
    pub factor: Option<f64>,
}

fn is_zero(x: &i32) -> bool {
    *x == 0
}

#[derive(Serialize)]
pub struct TypeDefinitions<'a> {
    #[serde(rename = "SimpleType")]
    pub types: Vec<SimpleType<'a>>,
}

impl TypeDefinitions<'_> {
    fn is_empty(&self) -> bool {
        self.types.is_empty()
    }
}

/// A switch's type: an Integer range whose description numbers the items ("1 split, 2 total").
/// Switches are Integers, not Enumerations, because co-simulation engines (libcosim, ecos)
/// ignore FMI 2.0 Enumeration variables.
#[derive(Serialize)]
pub struct SimpleType<'a> {
    #[serde(rename = "@name")]
    pub name: &'a str,
    #[serde(rename = "@description")]
    pub description: String,
    #[serde(rename = "Integer")]
    pub integer: IntegerType,
}

#[derive(Serialize)]
pub struct IntegerType {
    #[serde(rename = "@min")]
    pub min: i32,
    #[serde(rename = "@max")]
    pub max: i32,
}

#[derive(Serialize)]
pub struct LogCategories<'a> {
    #[serde(rename = "Category")]
    pub categories: Vec<Category<'a>>,
}

#[derive(Serialize)]
pub struct Category<'a> {
    #[serde(rename = "@name")]
    pub name: &'a str,
    #[serde(rename = "@description")]
    pub description: &'a str,
}

#[derive(Serialize)]
pub struct DefaultExperimentXml {
    #[serde(rename = "@startTime")]
    pub start_time: f64,
    #[serde(rename = "@stopTime")]
    pub stop_time: f64,
    #[serde(rename = "@tolerance", skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    #[serde(rename = "@stepSize")]
    pub step_size: f64,
}

#[derive(Serialize)]
pub struct ModelVariables<'a> {
    #[serde(rename = "ScalarVariable")]
    pub variables: Vec<ScalarVariable<'a>>,
}

#[derive(Serialize)]
pub struct ScalarVariable<'a> {
    #[serde(flatten)]
    pub head: VariableHead<'a>,
    #[serde(rename = "$value")]
    pub kind: KindXml<'a>,
}

/// The attributes every variable's element starts with, in both standards. Flattened into the
/// element's struct, whose other attributes (and FMI 2.0's type element) follow them, as quick-xml
/// writes a flattened struct's `@` fields as attributes of the element, in field order.
#[derive(Serialize)]
pub struct VariableHead<'a> {
    #[serde(rename = "@name")]
    pub name: &'a str,
    #[serde(rename = "@valueReference")]
    pub value_reference: u32,
    #[serde(rename = "@description")]
    pub description: String,
    #[serde(rename = "@causality")]
    pub causality: &'a str,
    #[serde(rename = "@variability")]
    pub variability: &'a str,
}

#[derive(Serialize)]
pub enum KindXml<'a> {
    Real {
        #[serde(rename = "@unit", skip_serializing_if = "Option::is_none")]
        unit: Option<&'a str>,
        #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
        start: Option<String>,
        #[serde(rename = "@min", skip_serializing_if = "Option::is_none")]
        min: Option<String>,
        #[serde(rename = "@max", skip_serializing_if = "Option::is_none")]
        max: Option<String>,
    },
    Integer {
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

#[derive(Serialize)]
pub struct ModelStructure {
    #[serde(rename = "Outputs")]
    pub outputs: Unknowns,
    #[serde(rename = "InitialUnknowns")]
    pub initial_unknowns: Unknowns,
}

#[derive(Serialize)]
pub struct Unknowns {
    #[serde(rename = "Unknown")]
    pub unknowns: Vec<Unknown>,
}

#[derive(Serialize)]
pub struct Unknown {
    #[serde(rename = "@index")]
    pub index: usize,
    #[serde(rename = "@dependencies", skip_serializing_if = "Option::is_none")]
    pub dependencies: Option<String>,
}

pub fn causality(c: Causality) -> &'static str {
    match c {
        Causality::Parameter => "parameter",
        Causality::Input => "input",
        Causality::Output => "output",
        Causality::Independent => "independent",
    }
}

pub fn variability(v: Variability) -> &'static str {
    match v {
        Variability::Fixed => "fixed",
        Variability::Tunable => "tunable",
        Variability::Continuous => "continuous",
    }
}

/// The shortest text that reads back as the same f64, in exponent form when that is shorter
/// (serde would spell 2.2e-308 out with three hundred zeros).
pub fn number(x: f64) -> String {
    let plain = format!("{x}");
    let exponent = format!("{x:e}");
    if exponent.len() < plain.len() {
        exponent
    } else {
        plain
    }
}

pub fn finite(x: f64) -> Option<String> {
    x.is_finite().then(|| number(x))
}

/// Either standard's description (FMI 3.0's too) as the file's text: indented by two spaces,
/// after the XML declaration.
pub fn to_xml(description: &impl Serialize) -> String {
    let mut body = String::new();
    let mut serializer = quick_xml::se::Serializer::new(&mut body);
    serializer.indent(' ', 2);
    // Serialising plain structs into a String cannot fail; an empty body would be caught by
    // the GUID check and by every test that reads the XML.
    let _ = description.serialize(serializer);
    format!("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n{body}\n")
}
