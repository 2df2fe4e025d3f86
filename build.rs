//! Writes, into OUT_DIR only, every model's modelDescription.xml (from `src/interface`) and the
//! GUIDs (a hash of each XML) that `fmi2Instantiate` checks, so the binary and its XML can never
//! drift apart. The XML comes from `src/model_description`, the writer the library uses for
//! scene files. `friction-fmu build` copies the XML to `modelDescription/`, where a test checks
//! that the committed copy is current.

#[allow(dead_code)]
#[path = "src/interface/mod.rs"]
mod interface;

#[allow(dead_code)]
#[path = "src/model_description/mod.rs"]
mod model_description;

use interface::variable::Variable;
use model_description::Interface;
use std::fmt::Write as _;
use std::path::Path;

fn write_if_changed(path: &Path, text: &str) {
    if std::fs::read_to_string(path).ok().as_deref() != Some(text) {
        std::fs::write(path, text)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    }
}

fn main() {
    println!("cargo:rerun-if-changed=src/interface");
    println!("cargo:rerun-if-changed=src/model_description");
    println!("cargo:rerun-if-changed=build.rs");
    let out_dir = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let mut guids = String::from("/// GUID of each model: a hash of its modelDescription.xml.\npub const GUIDS: &[(&str, &str)] = &[\n");
    let mut xmls = String::from("/// Each model's modelDescription.xml, as packed into its FMU.\npub const XMLS: &[(&str, &str)] = &[\n");
    for table in interface::MODELS {
        let variables: Vec<&Variable> = table.variables.iter().collect();
        let (guid, xml) = Interface::full(table, &variables).write();
        let _ = writeln!(guids, "    ({:?}, {:?}),", table.model_identifier, guid);
        let _ = writeln!(xmls, "    ({:?}, {:?}),", table.model_identifier, xml);
    }
    guids.push_str("];\n");
    xmls.push_str("];\n");
    write_if_changed(&Path::new(&out_dir).join("guids.rs"), &guids);
    write_if_changed(&Path::new(&out_dir).join("model_descriptions.rs"), &xmls);
}
