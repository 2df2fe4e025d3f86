//! The drive-coupled system for libcosim's ECCO algorithm: `OspSystemStructure.xml` beside
//! `DriveFriction.ssp` in the output directory, naming the same two FMUs, values and connections
//! ([`super::ssp`]), with v_nut and Fd declared the power bond whose energy residual ECCO's
//! step-size controller holds to its tolerance. libcosim reads it from the directory:
//! `CosimExecution.from_osp_config_file("fmu-out")` (ECCO reads the bond's inputs after each
//! step, which libcosim allows only once an observer exposes them: docs/coupling.md, "ECCO").
//! libcosim's SSP reader takes no algorithm but the fixed step, so the archive cannot carry
//! this.

use super::ssp::{typed_value, Component, CONNECTIONS, DRIVE, FRICTION, STEP_SIZE};
use std::fmt::Write as _;
use std::io;
use std::path::{Path, PathBuf};

/// The file libcosim looks for in a directory it is given.
pub const FILE: &str = "OspSystemStructure.xml";

/// The power bond's name (both connections carry it).
const BOND: &str = "nut";

/// ECCO's parameters: the first step is the archive's, then steps between 1 us and 1 ms as the
/// power bond's energy residual allows at a relative and absolute tolerance of 1e-10
/// (docs/coupling.md, "ECCO": fewer steps at looser tolerances, and a larger error).
const ECCO: &[(&str, f64)] = &[
    ("SafetyFactor", 0.8),
    ("StepSize", STEP_SIZE),
    ("MinimumStepSize", 1e-6),
    ("MaximumStepSize", 1e-3),
    ("MinimumChangeRate", 0.2),
    ("MaximumChangeRate", 1.5),
    ("ProportionalGain", 0.2),
    ("IntegralGain", 0.15),
    ("RelativeTolerance", 1e-10),
    ("AbsoluteTolerance", 1e-10),
];

/// Writes `<out_dir>/OspSystemStructure.xml`, for the FMUs packed in `out_dir`.
pub fn write(out_dir: &Path) -> io::Result<PathBuf> {
    let xml = system_structure(&[&DRIVE, &FRICTION])
        .map_err(|message| io::Error::new(io::ErrorKind::InvalidData, message))?;
    let path = out_dir.join(FILE);
    std::fs::write(&path, xml)?;
    Ok(path)
}

pub fn system_structure(components: &[&Component]) -> Result<String, String> {
    let mut xml = format!(
        concat!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n",
            "<OspSystemStructure xmlns=\"http://opensimulationplatform.com/MSMI/OSPSystemStructure\" version=\"0.1\">\n",
            "    <StartTime>0.0</StartTime>\n",
            "    <BaseStepSize>{:?}</BaseStepSize>\n",
            "    <Algorithm>ecco</Algorithm>\n",
            "    <Simulators>\n"
        ),
        STEP_SIZE
    );
    for component in components {
        let table = component.table;
        let _ = writeln!(
            xml,
            "        <Simulator name=\"{}\" source=\"{}.fmu\">\n            <InitialValues>",
            component.name, table.model_identifier
        );
        for &(name, value) in component.values {
            let (kind, value) = typed_value(table, name, value)?;
            let _ = writeln!(
                xml,
                "                <InitialValue variable=\"{name}\"><{kind} value=\"{value}\"/></InitialValue>"
            );
        }
        xml.push_str("            </InitialValues>\n        </Simulator>\n");
    }
    xml.push_str("    </Simulators>\n    <Connections>\n");
    for (from, output, to, input) in CONNECTIONS {
        let _ = write!(
            xml,
            concat!(
                "        <VariableConnection powerBond=\"{bond}\">\n",
                "            <Variable simulator=\"{to}\" name=\"{input}\" causality=\"input\"/>\n",
                "            <Variable simulator=\"{from}\" name=\"{output}\" causality=\"output\"/>\n",
                "        </VariableConnection>\n"
            ),
            bond = BOND,
            to = to,
            input = input,
            from = from,
            output = output
        );
    }
    xml.push_str("    </Connections>\n    <EccoConfiguration>\n");
    for (name, value) in ECCO {
        let _ = writeln!(xml, "        <{name}>{value:?}</{name}>");
    }
    xml.push_str("    </EccoConfiguration>\n</OspSystemStructure>\n");
    Ok(xml)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_power_bond_pairs_each_connection_with_its_partner() {
        let xml = system_structure(&[&DRIVE, &FRICTION]).unwrap();
        assert_eq!(xml.matches("powerBond=\"nut\"").count(), 2);
        assert!(
            xml.contains("<Variable simulator=\"friction\" name=\"vd_in\" causality=\"input\"/>")
        );
        assert!(xml.contains(
            "<InitialValue variable=\"input_scheme\"><Integer value=\"3\"/></InitialValue>"
        ));
        assert!(xml.contains("<RelativeTolerance>1e-10</RelativeTolerance>"));
    }
}
