//! Writes `modelDescription/<Model>.xml` for every model of `src/interface` and the GUIDs (a hash
//! of each XML) that `fmi2Instantiate` checks, so the binary and its XML can never drift apart.

#[allow(dead_code)]
#[path = "src/interface/mod.rs"]
mod interface;

use interface::variable::{
    Causality, Kind, ModelTable, Unit, Variability, Variable, LOG_CATEGORIES, UNITS,
};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

#[derive(Serialize)]
#[serde(rename = "fmiModelDescription")]
struct ModelDescription {
    #[serde(rename = "@fmiVersion")]
    fmi_version: &'static str,
    #[serde(rename = "@modelName")]
    model_name: &'static str,
    #[serde(rename = "@guid")]
    guid: String,
    #[serde(rename = "@description")]
    description: &'static str,
    #[serde(rename = "@generationTool")]
    generation_tool: String,
    #[serde(rename = "@variableNamingConvention")]
    naming: &'static str,
    #[serde(rename = "@numberOfEventIndicators")]
    event_indicators: u32,
    #[serde(rename = "CoSimulation")]
    co_simulation: CoSimulation,
    #[serde(rename = "UnitDefinitions")]
    units: UnitDefinitions,
    #[serde(
        rename = "TypeDefinitions",
        skip_serializing_if = "TypeDefinitions::is_empty"
    )]
    types: TypeDefinitions,
    #[serde(rename = "LogCategories")]
    log_categories: LogCategories,
    #[serde(rename = "DefaultExperiment")]
    default_experiment: DefaultExperimentXml,
    #[serde(rename = "ModelVariables")]
    variables: ModelVariables,
    #[serde(rename = "ModelStructure")]
    structure: ModelStructure,
}

#[derive(Serialize)]
struct CoSimulation {
    #[serde(rename = "@modelIdentifier")]
    model_identifier: &'static str,
    #[serde(rename = "@needsExecutionTool")]
    needs_execution_tool: bool,
    #[serde(rename = "@canHandleVariableCommunicationStepSize")]
    variable_step: bool,
    #[serde(rename = "@canInterpolateInputs")]
    interpolate_inputs: bool,
    #[serde(rename = "@maxOutputDerivativeOrder")]
    max_output_derivative_order: u32,
    #[serde(rename = "@canRunAsynchronuously")]
    asynchronous: bool,
    #[serde(rename = "@canBeInstantiatedOnlyOncePerProcess")]
    once_per_process: bool,
    #[serde(rename = "@canNotUseMemoryManagementFunctions")]
    no_memory_functions: bool,
    #[serde(rename = "@canGetAndSetFMUstate")]
    get_set_state: bool,
    #[serde(rename = "@canSerializeFMUstate")]
    serialize_state: bool,
    #[serde(rename = "@providesDirectionalDerivative")]
    directional_derivative: bool,
}

#[derive(Serialize)]
struct UnitDefinitions {
    #[serde(rename = "Unit")]
    units: Vec<UnitXml>,
}

#[derive(Serialize)]
struct UnitXml {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "BaseUnit")]
    base: BaseUnit,
}

#[derive(Serialize)]
struct BaseUnit {
    #[serde(rename = "@kg", skip_serializing_if = "is_zero")]
    kg: i32,
    #[serde(rename = "@m", skip_serializing_if = "is_zero")]
    m: i32,
    #[serde(rename = "@s", skip_serializing_if = "is_zero")]
    s: i32,
    #[serde(rename = "@rad", skip_serializing_if = "is_zero")]
    rad: i32,
    #[serde(rename = "@factor", skip_serializing_if = "Option::is_none")]
    factor: Option<f64>,
}

fn is_zero(x: &i32) -> bool {
    *x == 0
}

#[derive(Serialize)]
struct TypeDefinitions {
    #[serde(rename = "SimpleType")]
    types: Vec<SimpleType>,
}

impl TypeDefinitions {
    fn is_empty(&self) -> bool {
        self.types.is_empty()
    }
}

#[derive(Serialize)]
struct SimpleType {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "Enumeration")]
    enumeration: EnumerationType,
}

#[derive(Serialize)]
struct EnumerationType {
    #[serde(rename = "Item")]
    items: Vec<Item>,
}

#[derive(Serialize)]
struct Item {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "@value")]
    value: i32,
    #[serde(rename = "@description")]
    description: &'static str,
}

#[derive(Serialize)]
struct LogCategories {
    #[serde(rename = "Category")]
    categories: Vec<Category>,
}

#[derive(Serialize)]
struct Category {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "@description")]
    description: &'static str,
}

#[derive(Serialize)]
struct DefaultExperimentXml {
    #[serde(rename = "@startTime")]
    start_time: f64,
    #[serde(rename = "@stopTime")]
    stop_time: f64,
    #[serde(rename = "@tolerance")]
    tolerance: f64,
    #[serde(rename = "@stepSize")]
    step_size: f64,
}

#[derive(Serialize)]
struct ModelVariables {
    #[serde(rename = "ScalarVariable")]
    variables: Vec<ScalarVariable>,
}

#[derive(Serialize)]
struct ScalarVariable {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "@valueReference")]
    value_reference: u32,
    #[serde(rename = "@description")]
    description: &'static str,
    #[serde(rename = "@causality")]
    causality: &'static str,
    #[serde(rename = "@variability")]
    variability: &'static str,
    #[serde(rename = "$value")]
    kind: KindXml,
}

#[derive(Serialize)]
enum KindXml {
    Real {
        #[serde(rename = "@unit", skip_serializing_if = "Option::is_none")]
        unit: Option<&'static str>,
        #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
        start: Option<String>,
        #[serde(rename = "@min", skip_serializing_if = "Option::is_none")]
        min: Option<String>,
        #[serde(rename = "@max", skip_serializing_if = "Option::is_none")]
        max: Option<String>,
    },
    Integer {
        #[serde(rename = "@start")]
        start: i32,
        #[serde(rename = "@min")]
        min: i32,
        #[serde(rename = "@max")]
        max: i32,
    },
    Enumeration {
        #[serde(rename = "@declaredType")]
        declared_type: &'static str,
        #[serde(rename = "@start")]
        start: i32,
    },
}

#[derive(Serialize)]
struct ModelStructure {
    #[serde(rename = "Outputs")]
    outputs: Unknowns,
    #[serde(rename = "InitialUnknowns")]
    initial_unknowns: Unknowns,
}

#[derive(Serialize)]
struct Unknowns {
    #[serde(rename = "Unknown")]
    unknowns: Vec<Unknown>,
}

#[derive(Serialize)]
struct Unknown {
    #[serde(rename = "@index")]
    index: usize,
    #[serde(rename = "@dependencies", skip_serializing_if = "Option::is_none")]
    dependencies: Option<String>,
}

fn causality(c: Causality) -> &'static str {
    match c {
        Causality::Parameter => "parameter",
        Causality::Input => "input",
        Causality::Output => "output",
        Causality::Independent => "independent",
    }
}

fn variability(v: Variability) -> &'static str {
    match v {
        Variability::Fixed => "fixed",
        Variability::Tunable => "tunable",
        Variability::Continuous => "continuous",
    }
}

/// The shortest text that reads back as the same f64, in exponent form when that is shorter
/// (serde would spell 2.2e-308 out with three hundred zeros).
fn number(x: f64) -> String {
    let plain = format!("{x}");
    let exponent = format!("{x:e}");
    if exponent.len() < plain.len() {
        exponent
    } else {
        plain
    }
}

fn finite(x: f64) -> Option<String> {
    x.is_finite().then(|| number(x))
}

fn scalar_variable(v: &Variable) -> ScalarVariable {
    let kind = match v.kind {
        Kind::Real {
            start,
            unit,
            min,
            max,
        } => KindXml::Real {
            unit: (!unit.is_empty()).then_some(unit),
            // Calculated outputs may not carry a start value.
            start: (v.causality != Causality::Output).then(|| number(start)),
            min: finite(min),
            max: finite(max),
        },
        Kind::Integer { start, min, max } => KindXml::Integer { start, min, max },
        Kind::Enumeration { type_name, start } => KindXml::Enumeration {
            declared_type: type_name,
            start,
        },
    };
    ScalarVariable {
        name: v.name,
        value_reference: v.value_reference,
        description: v.description,
        causality: causality(v.causality),
        variability: variability(v.variability),
        kind,
    }
}

fn used_units(table: &ModelTable) -> Vec<&'static Unit> {
    UNITS
        .iter()
        .filter(|u| {
            table
                .variables
                .iter()
                .any(|v| matches!(v.kind, Kind::Real { unit, .. } if unit == u.name))
        })
        .collect()
}

fn model_structure(table: &ModelTable) -> ModelStructure {
    // ModelVariables indices are 1-based, in table order.
    let index_of = |vr: u32| {
        table
            .variables
            .iter()
            .position(|v| v.value_reference == vr)
            .expect("dependency on an unknown value reference")
            + 1
    };
    let outputs: Vec<(usize, &Variable)> = table
        .variables
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == Causality::Output)
        .map(|(i, v)| (i + 1, v))
        .collect();
    ModelStructure {
        outputs: Unknowns {
            unknowns: outputs
                .iter()
                .map(|&(index, v)| Unknown {
                    index,
                    dependencies: Some(
                        v.depends_on
                            .iter()
                            .map(|&vr| index_of(vr).to_string())
                            .collect::<Vec<_>>()
                            .join(" "),
                    ),
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

fn model_description(table: &ModelTable, guid: &str) -> ModelDescription {
    ModelDescription {
        fmi_version: "2.0",
        model_name: table.model_identifier,
        guid: guid.to_string(),
        description: table.description,
        generation_tool: format!("friction-fmu {}", env!("CARGO_PKG_VERSION")),
        naming: "flat",
        event_indicators: 0,
        co_simulation: CoSimulation {
            model_identifier: table.model_identifier,
            needs_execution_tool: false,
            variable_step: true,
            interpolate_inputs: interface::interpolates_inputs(table),
            max_output_derivative_order: interface::interpolates_inputs(table).into(),
            asynchronous: false,
            once_per_process: false,
            no_memory_functions: true,
            get_set_state: true,
            serialize_state: true,
            directional_derivative: false,
        },
        units: UnitDefinitions {
            units: used_units(table)
                .into_iter()
                .map(|u| UnitXml {
                    name: u.name,
                    base: BaseUnit {
                        kg: u.kg,
                        m: u.m,
                        s: u.s,
                        rad: u.rad,
                        factor: (u.name == "%").then_some(0.01),
                    },
                })
                .collect(),
        },
        types: TypeDefinitions {
            types: table
                .enum_types
                .iter()
                .map(|e| SimpleType {
                    name: e.name,
                    enumeration: EnumerationType {
                        items: e
                            .items
                            .iter()
                            .enumerate()
                            .map(|(i, (name, description))| Item {
                                name,
                                value: i as i32 + 1,
                                description,
                            })
                            .collect(),
                    },
                })
                .collect(),
        },
        log_categories: LogCategories {
            categories: LOG_CATEGORIES
                .iter()
                .map(|&(name, description)| Category { name, description })
                .collect(),
        },
        default_experiment: DefaultExperimentXml {
            start_time: table.default_experiment.start_time,
            stop_time: table.default_experiment.stop_time,
            tolerance: table.default_experiment.tolerance,
            step_size: table.default_experiment.step_size,
        },
        variables: ModelVariables {
            variables: table.variables.iter().map(scalar_variable).collect(),
        },
        structure: model_structure(table),
    }
}

fn to_xml(description: &ModelDescription) -> String {
    let mut body = String::new();
    let mut serializer = quick_xml::se::Serializer::new(&mut body);
    serializer.indent(' ', 2);
    description
        .serialize(serializer)
        .expect("modelDescription serialises");
    format!("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n{body}\n")
}

/// FNV-1a, twice with different offsets: a stable 128-bit content hash without a dependency.
fn guid_of(text: &str) -> String {
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

fn write_if_changed(path: &Path, text: &str) {
    if std::fs::read_to_string(path).ok().as_deref() != Some(text) {
        std::fs::write(path, text)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    }
}

fn main() {
    println!("cargo:rerun-if-changed=src/interface");
    println!("cargo:rerun-if-changed=build.rs");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out_dir = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    std::fs::create_dir_all(root.join("modelDescription"))
        .expect("modelDescription/ can be created");
    let mut guids = String::from("/// GUID of each model: a hash of its modelDescription.xml.\npub const GUIDS: &[(&str, &str)] = &[\n");
    let mut xmls = String::from("/// Each model's modelDescription.xml, as packed into its FMU.\npub const XMLS: &[(&str, &str)] = &[\n");
    for table in interface::MODELS {
        // The GUID hashes the XML written with a placeholder, then takes its place.
        let guid = guid_of(&to_xml(&model_description(table, "")));
        let xml = to_xml(&model_description(table, &guid));
        write_if_changed(
            &root
                .join("modelDescription")
                .join(format!("{}.xml", table.model_identifier)),
            &xml,
        );
        let _ = writeln!(guids, "    ({:?}, {:?}),", table.model_identifier, guid);
        let _ = writeln!(xmls, "    ({:?}, {:?}),", table.model_identifier, xml);
    }
    guids.push_str("];\n");
    xmls.push_str("];\n");
    write_if_changed(&Path::new(&out_dir).join("guids.rs"), &guids);
    write_if_changed(&Path::new(&out_dir).join("model_descriptions.rs"), &xmls);
}
