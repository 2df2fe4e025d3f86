//! The drive-coupled system as an SSP 1.0 archive (`DriveFriction.ssp`): DriveTrain's nut drives
//! TransverseFriction's drive spring, and the spring's force loads the nut. The archive holds
//! both FMUs under resources/ and `SystemStructure.ssd` with the connections, the parameter
//! values that make the two a system, and a default experiment, so that libcosim, ecos or any
//! SSP tool runs it without a line of XML written by hand.

use crate::models::{drive::table as drive, transverse::table as transverse};
use crate::variables::variable::{Kind, ModelTable};
use std::fmt::Write as _;
use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use zip::write::SimpleFileOptions;

/// The archive's name, without extension.
pub const NAME: &str = "DriveFriction";

/// One component of the system: its name in the SSD and its model.
pub struct Component {
    pub name: &'static str,
    pub table: &'static ModelTable,
    /// Parameter and input values the system sets: (variable, switch item or number).
    pub values: &'static [(&'static str, Value)],
}

/// A value in a parameter set: a switch by item name, or a Real.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Item(&'static str),
    Real(f64),
}

/// How both components move their inputs over a step: engines hold them, and the coupled run
/// is then first order in the step; `corrected` makes it about 2.5th (docs/coupling.md).
const INPUT_SCHEME: (&str, Value) = ("input_scheme", Value::Item("corrected"));

/// The drive, with its defaults (illustrative small stage running the nut at 0.5 mm/s).
pub const DRIVE: Component = Component {
    name: "drive",
    table: &drive::TABLE,
    values: &[INPUT_SCHEME],
};

/// The contact, driven by the nut: no support vibration, so that the coupled motion (break-away
/// after about 8 ms, then sliding with the body ringing on the drive spring) is what the
/// communication step has to resolve; the case of `examples/drive_coupling.py`.
pub const FRICTION: Component = Component {
    name: "friction",
    table: &transverse::TABLE,
    values: &[
        ("drive_source", Value::Item("input")),
        ("va", Value::Real(0.0)),
        ("initial", Value::Item("rest")),
        ("vd_in", Value::Real(0.0)),
        INPUT_SCHEME,
    ],
};

/// (from component, output) -> (to component, input).
pub const CONNECTIONS: &[(&str, &str, &str, &str)] = &[
    ("drive", "v_nut", "friction", "vd_in"),
    ("friction", "Fd", "drive", "F_load"),
];

/// The default experiment: 40 ms (break-away and the first ringing periods) at 0.1 ms.
pub const STOP_TIME: f64 = 0.04;
pub const STEP_SIZE: f64 = 1e-4;

/// Writes `<out_dir>/DriveFriction.ssp` from the FMUs already packed in `out_dir`.
pub fn write(out_dir: &Path) -> io::Result<PathBuf> {
    let components = [&DRIVE, &FRICTION];
    let ssd = system_structure(&components)
        .map_err(|message| io::Error::new(io::ErrorKind::InvalidData, message))?;
    let path = out_dir.join(format!("{NAME}.ssp"));
    let mut zip = zip::ZipWriter::new(File::create(&path)?);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("SystemStructure.ssd", options)?;
    zip.write_all(ssd.as_bytes())?;
    // An FMU is already compressed.
    let stored = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for component in components {
        let fmu = format!("{}.fmu", component.table.model_identifier);
        let bytes = std::fs::read(out_dir.join(&fmu))
            .map_err(|e| io::Error::new(e.kind(), format!("{fmu} must be packed first: {e}")))?;
        zip.start_file(format!("resources/{fmu}"), stored)?;
        zip.write_all(&bytes)?;
    }
    zip.finish()?;
    Ok(path)
}

/// SystemStructure.ssd. The engines read only the prefixed SSP 1.0 form (`ssd:`, `ssc:`,
/// `ssv:`), a type on every connector, and switches as `ssv:Integer` (both reject
/// Enumerations); libcosim takes its step from the OSP annotation of the default experiment.
pub fn system_structure(components: &[&Component]) -> Result<String, String> {
    let mut xml = String::from(concat!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n",
        "<ssd:SystemStructureDescription version=\"1.0\" name=\"DriveFriction\"",
        " xmlns:ssd=\"http://ssp-standard.org/SSP1/SystemStructureDescription\"",
        " xmlns:ssc=\"http://ssp-standard.org/SSP1/SystemStructureCommon\"",
        " xmlns:ssv=\"http://ssp-standard.org/SSP1/SystemStructureParameterValues\"",
        " xmlns:osp=\"http://opensimulationplatform.com/SSP/OSPAnnotations\">\n",
        "  <ssd:System name=\"DriveFriction\" description=\"DriveTrain's lead-screw nut drives ",
        "TransverseFriction's drive spring (v_nut -> vd_in); the spring's force loads the nut ",
        "(Fd -> F_load)\">\n",
        "    <ssd:Elements>\n",
    ));
    for component in components {
        component_xml(&mut xml, component)?;
    }
    xml.push_str("    </ssd:Elements>\n    <ssd:Connections>\n");
    for (from, output, to, input) in CONNECTIONS {
        let _ = writeln!(
            xml,
            "      <ssd:Connection startElement=\"{from}\" startConnector=\"{output}\" endElement=\"{to}\" endConnector=\"{input}\"/>"
        );
    }
    let _ = write!(
        xml,
        concat!(
            "    </ssd:Connections>\n",
            "  </ssd:System>\n",
            "  <ssd:DefaultExperiment startTime=\"0\" stopTime=\"{stop:?}\">\n",
            "    <ssd:Annotations>\n",
            "      <ssc:Annotation type=\"com.opensimulationplatform\">\n",
            "        <osp:Algorithm><osp:FixedStepAlgorithm baseStepSize=\"{step:?}\"/></osp:Algorithm>\n",
            "      </ssc:Annotation>\n",
            "    </ssd:Annotations>\n",
            "  </ssd:DefaultExperiment>\n",
            "</ssd:SystemStructureDescription>\n"
        ),
        stop = STOP_TIME,
        step = STEP_SIZE
    );
    Ok(xml)
}

fn component_xml(xml: &mut String, component: &Component) -> Result<(), String> {
    let table = component.table;
    let model = table.model_identifier;
    let _ = writeln!(
        xml,
        "      <ssd:Component name=\"{}\" type=\"application/x-fmu-sharedlibrary\" source=\"resources/{model}.fmu\">\n        <ssd:Connectors>",
        component.name
    );
    for (from, output, to, input) in CONNECTIONS {
        let (name, kind) = if *from == component.name {
            (output, "output")
        } else if *to == component.name {
            (input, "input")
        } else {
            continue;
        };
        if table.by_name(name).is_none() {
            return Err(format!("{model} has no variable {name}"));
        }
        let _ = writeln!(
            xml,
            "          <ssd:Connector name=\"{name}\" kind=\"{kind}\"><ssc:Real/></ssd:Connector>"
        );
    }
    xml.push_str("        </ssd:Connectors>\n");
    if !component.values.is_empty() {
        xml.push_str(concat!(
            "        <ssd:ParameterBindings>\n",
            "          <ssd:ParameterBinding>\n",
            "            <ssd:ParameterValues>\n",
            "              <ssv:ParameterSet version=\"1.0\" name=\"initialValues\">\n",
            "                <ssv:Parameters>\n",
        ));
        for &(name, value) in component.values {
            let _ = writeln!(
                xml,
                "                  <ssv:Parameter name=\"{name}\">{}</ssv:Parameter>",
                parameter_value(table, name, value)?
            );
        }
        xml.push_str(concat!(
            "                </ssv:Parameters>\n",
            "              </ssv:ParameterSet>\n",
            "            </ssd:ParameterValues>\n",
            "          </ssd:ParameterBinding>\n",
            "        </ssd:ParameterBindings>\n",
        ));
    }
    xml.push_str("      </ssd:Component>\n");
    Ok(())
}

/// A value as SSV writes it, checked against the model's table.
fn parameter_value(table: &ModelTable, name: &str, value: Value) -> Result<String, String> {
    let (kind, value) = typed_value(table, name, value)?;
    Ok(format!("<ssv:{kind} value=\"{value}\"/>"))
}

/// A value's type as the engines read it (a switch by its item's number, as `Integer`) and its
/// text, checked against the model's table.
pub fn typed_value(
    table: &ModelTable,
    name: &str,
    value: Value,
) -> Result<(&'static str, String), String> {
    let model = table.model_identifier;
    let var = table
        .by_name(name)
        .ok_or_else(|| format!("{model} has no variable {name}"))?;
    match (var.kind, value) {
        (Kind::Switch { type_name, .. }, Value::Item(item)) => table
            .enum_type(type_name)
            .and_then(|t| t.value_of(item))
            .map(|number| ("Integer", number.to_string()))
            .ok_or_else(|| format!("{model}.{name} has no item {item}")),
        (Kind::Real { min, max, .. }, Value::Real(x)) if (min..=max).contains(&x) => {
            Ok(("Real", format!("{x:?}")))
        }
        _ => Err(format!("{model}.{name} cannot take {value:?}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_system_names_only_variables_its_models_have() {
        let xml = system_structure(&[&DRIVE, &FRICTION]).unwrap();
        assert!(xml.contains(
            "<ssv:Parameter name=\"drive_source\"><ssv:Integer value=\"2\"/></ssv:Parameter>"
        ));
        assert!(xml.contains("startElement=\"drive\" startConnector=\"v_nut\""));
        assert_eq!(xml.matches("<ssd:Connector ").count(), 4);
        assert_eq!(
            crate::variables::variable::communication_grid(0.0, STOP_TIME, STEP_SIZE),
            Ok(400)
        );
        let wrong = Component {
            name: "friction",
            table: &transverse::TABLE,
            values: &[("drive_source", Value::Item("belt"))],
        };
        assert!(system_structure(&[&DRIVE, &wrong])
            .unwrap_err()
            .contains("no item belt"));
    }
}
