//! Writes, into OUT_DIR only, every model's modelDescription.xml for FMI 2.0 and FMI 3.0 (from
//! its variable table, `src/models/<model>/table.rs`) and the GUIDs (a hash of the FMI 2.0 XML)
//! that `fmi2Instantiate` checks and that the FMI 3.0 XML names as its instantiationToken, so
//! the binary and its XML can never drift apart. The XML comes from
//! `src/model_description`, the writer the library uses for variants. `friction-fmu build` copies
//! the XML to `modelDescription/` and `modelDescription/fmi3/`, where a test checks that the
//! committed copies are current.

#[allow(dead_code)]
#[path = "src/variables/mod.rs"]
mod variables;

// What the variables' checks return.
#[allow(dead_code)]
#[path = "src/error.rs"]
mod error;

// Each model's variable table, as src/models/list.rs lists the models.
macro_rules! models {
    ($($module:ident => $constant:ident),* $(,)?) => {
        $(
            #[allow(dead_code)]
            mod $module {
                // Relative to src/models/list.rs, where the macro is invoked.
                include!(concat!(stringify!($module), "/table.rs"));
            }
        )*
        const TABLES: &[&variables::variable::ModelTable] = &[$(&$module::TABLE),*];
    };
}
include!("src/models/list.rs");

#[allow(dead_code, unused_imports)]
#[path = "src/model_description/mod.rs"]
mod model_description;

use model_description::Description;
use std::fmt::Write as _;
use std::path::Path;
use variables::variable::Variable;

fn write_if_changed(path: &Path, text: &str) {
    if std::fs::read_to_string(path).ok().as_deref() != Some(text) {
        std::fs::write(path, text)
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    }
}

fn main() {
    println!("cargo:rerun-if-changed=src/variables");
    println!("cargo:rerun-if-changed=src/models");
    println!("cargo:rerun-if-changed=src/model_description");
    println!("cargo:rerun-if-changed=build.rs");
    let out_dir = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let mut guids = String::from("/// GUID of each model: a hash of its modelDescription.xml.\npub const GUIDS: &[(&str, &str)] = &[\n");
    let mut xmls = String::from("/// Each model's modelDescription.xml, as packed into its FMU.\npub const XMLS: &[(&str, &str)] = &[\n");
    let mut xmls3 = String::from("/// Each model's FMI 3.0 modelDescription.xml, as packed into its FMI 3.0 FMU.\npub const FMI3_XMLS: &[(&str, &str)] = &[\n");
    for table in TABLES {
        let variables: Vec<&Variable> = table.variables.iter().collect();
        let description = Description::full(table, &variables);
        let (guid, xml) = description.write();
        let xml3 = description.write_fmi3(&guid);
        let _ = writeln!(guids, "    ({:?}, {:?}),", table.model_identifier, guid);
        let _ = writeln!(xmls, "    ({:?}, {:?}),", table.model_identifier, xml);
        let _ = writeln!(xmls3, "    ({:?}, {:?}),", table.model_identifier, xml3);
    }
    guids.push_str("];\n");
    xmls.push_str("];\n");
    xmls3.push_str("];\n");
    write_if_changed(&Path::new(&out_dir).join("guids.rs"), &guids);
    write_if_changed(&Path::new(&out_dir).join("model_descriptions.rs"), &xmls);
    write_if_changed(
        &Path::new(&out_dir).join("model_descriptions_fmi3.rs"),
        &xmls3,
    );
}
