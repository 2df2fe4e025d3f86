//! The variables of the committed FMI 3.0 modelDescription.xml files (modelDescription/fmi3/),
//! as the tests that drive the FMI 3.0 boundary need them: an importer calls the getter and
//! setter of the type the XML declares, so that is the type the tests use too.

use friction_fmu::instance::calls::ValueType;
use std::path::Path;

/// One variable as the XML declares it.
// Each test that includes this module reads the fields it needs.
#[allow(dead_code)]
#[derive(Clone, Debug)]
pub struct Declared {
    pub name: String,
    pub value_reference: u32,
    pub causality: String,
    pub value_type: ValueType,
}

const TYPES: [(&str, ValueType); 12] = [
    ("Float32", ValueType::Float32),
    ("Float64", ValueType::Float64),
    ("Int8", ValueType::Int8),
    ("UInt8", ValueType::UInt8),
    ("Int16", ValueType::Int16),
    ("UInt16", ValueType::UInt16),
    ("Int32", ValueType::Int32),
    ("UInt32", ValueType::UInt32),
    ("Int64", ValueType::Int64),
    ("UInt64", ValueType::UInt64),
    ("Boolean", ValueType::Boolean),
    ("String", ValueType::String),
];

/// The value of attribute `name` in `tag`.
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let start = tag.find(&format!(" {name}=\""))? + name.len() + 3;
    let length = tag[start..].find('"')?;
    Some(&tag[start..start + length])
}

/// Every variable of `model_identifier`'s committed FMI 3.0 modelDescription.xml, in order.
///
/// # Panics
/// If the file is missing or a variable lacks its name or value reference.
pub fn variables(model_identifier: &str) -> Vec<Declared> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("modelDescription/fmi3")
        .join(format!("{model_identifier}.xml"));
    let xml = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let start = xml.find("<ModelVariables>").expect("ModelVariables");
    let end = xml.find("</ModelVariables>").expect("ModelVariables' end");
    xml[start..end]
        .split('<')
        .filter_map(|tag| {
            let element = tag.split([' ', '\n', '/', '>']).next()?;
            let (_, value_type) = TYPES.iter().find(|(name, _)| *name == element)?;
            Some(Declared {
                name: attribute(tag, "name").expect("name").to_string(),
                value_reference: attribute(tag, "valueReference")
                    .and_then(|vr| vr.parse().ok())
                    .expect("valueReference"),
                causality: attribute(tag, "causality").unwrap_or("local").to_string(),
                value_type: *value_type,
            })
        })
        .collect()
}
