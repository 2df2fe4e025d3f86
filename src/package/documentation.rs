//! documentation/index.html: the model's equations and source (hand-written, per model) and its
//! variables (generated from the same table as modelDescription.xml). A variant's page lists
//! the variables it keeps, with its start values, and the values it fixes. An FMI 3.0 FMU's page
//! opens with what its standard calls the functions the models' text names in FMI 2.0's words.

use super::Standard;
use crate::models::Model;
use crate::variables::variable::{Causality, Kind, ModelTable, Variable};
use crate::variant::Variant;

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A value as the page shows it; a switch's number and item with the items it could have been
/// (switches are set with fmi2SetInteger, by number).
fn value_text(table: &ModelTable, var: &Variable, value: f64) -> String {
    match var.kind {
        Kind::Real { .. } => crate::variables::values::number(value),
        Kind::Integer { .. } => (value as i64).to_string(),
        Kind::Switch { type_name, .. } => {
            let enum_type = table.enum_type(type_name);
            let all = enum_type.map(|e| e.listing()).unwrap_or_default();
            let item = enum_type.and_then(|e| e.item(value as i32)).unwrap_or("");
            format!("{} {item} (of {all})", value as i32)
        }
    }
}

fn table_start(var: &Variable) -> f64 {
    match var.kind {
        Kind::Real { start, .. } => start,
        Kind::Integer { start, .. } | Kind::Switch { start, .. } => f64::from(start),
    }
}

fn unit(var: &Variable) -> &'static str {
    match var.kind {
        Kind::Real { unit, .. } => unit,
        _ => "",
    }
}

/// One row per variable: name, value (none for outputs), unit, meaning.
fn rows<'a>(
    table: &ModelTable,
    variables: impl Iterator<Item = &'a Variable>,
    value: &dyn Fn(&Variable) -> f64,
) -> String {
    let mut rows = String::new();
    for v in variables {
        let shown = if v.causality == Causality::Output {
            String::new()
        } else {
            value_text(table, v, value(v))
        };
        rows.push_str(&format!(
            "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            escape(v.name),
            escape(&shown),
            escape(unit(v)),
            escape(v.description)
        ));
    }
    rows
}

fn section(title: &str, value_heading: &str, rows: &str) -> String {
    if rows.is_empty() {
        return String::new();
    }
    format!(
        "<h2>{title}</h2>\n<table>\n<tr><th>name</th><th>{value_heading}</th><th>unit</th><th>meaning</th></tr>\n{rows}</table>\n"
    )
}

/// Parameters, inputs and outputs among `variables`, each in its own table.
fn sections(
    table: &ModelTable,
    variables: &[&Variable],
    value: &dyn Fn(&Variable) -> f64,
) -> String {
    let mut sections = String::new();
    for (title, causality) in [
        ("Parameters", Causality::Parameter),
        ("Inputs", Causality::Input),
        ("Outputs", Causality::Output),
    ] {
        let of_kind = variables
            .iter()
            .copied()
            .filter(|v| v.causality == causality);
        sections.push_str(&section(title, "default", &rows(table, of_kind, value)));
    }
    sections
}

/// The FMI 3.0 names of what the models' hand-written text calls by FMI 2.0's.
const FMI3_NOTE: &str = "<p>This is the FMI 3.0 FMU; its FMI 2.0 twin carries the same library. \
Where the text below names FMI 2.0 functions: Reals are set with <code>fmi3SetFloat64</code>, switches \
and Integers with <code>fmi3SetInt32</code> (by number); <code>fmi3GetOutputDerivatives</code> gives the \
output derivatives; FMI 3.0 has no <code>fmi2SetRealInputDerivatives</code>: a master passes an input \
inside a step through the intermediate-update callback (the inputs marked \
<code>intermediateUpdate</code>), or the FMU moves it as <code>input_scheme</code> says.</p>\n";

fn html(standard: Standard, title: &str, description: &str, body: &str) -> String {
    let note = match standard {
        Standard::Fmi2 => "",
        Standard::Fmi3 => FMI3_NOTE,
    };
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{title}</title>\n<style>body{{font-family:sans-serif;max-width:50em;margin:auto}}table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:2px 6px;text-align:left}}</style></head>\n<body>\n<h1>{title}</h1>\n<p>{description}</p>\n{note}{body}</body></html>\n",
        description = escape(description),
    )
}

pub fn page(model: &Model, standard: Standard) -> String {
    let table = model.table;
    let variables: Vec<&Variable> = table.variables.iter().collect();
    let body = format!(
        "{}\n{}",
        model.documentation,
        sections(table, &variables, &table_start)
    );
    html(standard, table.model_identifier, table.description, &body)
}

/// A variant's page: what it keeps (start values from the file), what it fixes, then the
/// model's equations; the file itself is in resources/variant.toml.
pub fn variant_page(variant: &Variant, standard: Standard) -> String {
    let table = variant.model.table;
    let value = |v: &Variable| variant.values.real(v.value_reference);
    let fixed: Vec<&Variable> = variant.fixed().into_iter().map(|(v, _)| v).collect();
    let body = format!(
        "<p>A simulation of <code>{model}</code>: only the variables below are in the interface; every other \
         parameter and input is fixed at the value listed under <i>Fixed values</i>. The variant is \
         <code>resources/variant.toml</code>.</p>\n{kept}{fixed}<h2>Model {model}</h2>\n{equations}\n",
        model = table.model_identifier,
        kept = sections(table, &variant.kept_variables(), &value),
        fixed = section("Fixed values", "value", &rows(table, fixed.into_iter(), &value)),
        equations = variant.model.documentation,
    );
    html(standard, &variant.name, &variant.description, &body)
}

#[cfg(test)]
mod tests {
    use super::{page, variant_page, Standard, FMI3_NOTE};

    /// Every model ships a written description, and its page lists every variable.
    #[test]
    fn every_model_has_a_documentation_page() {
        for model in crate::models::MODELS {
            let id = model.table.model_identifier;
            assert!(
                model.documentation.contains("<h2>Source</h2>"),
                "{id} has no description"
            );
            let html = page(model, Standard::Fmi2);
            for v in model.table.variables {
                assert!(
                    html.contains(&format!("<code>{}</code>", v.name)),
                    "{id}: {}",
                    v.name
                );
            }
        }
    }

    /// A simulation's page shows each kept variable once with the file's value, and each fixed one.
    #[test]
    fn a_variant_page_lists_kept_and_fixed_values() {
        let text = "name = \"S\"\nmodel = \"LongitudinalFriction\"\nlaw = \"coulomb\"\nsolver = \"rk4\"\ntunable = [\"vc\"]\noutputs = [\"FT_mean\"]\n[parameters]\nvc = 0.146\nkt = 3e4\n[experiment]\nstart = 0\nstop = 1e-3\nstep = 1e-5\n";
        let variant = crate::variant::parse("s.toml", text).unwrap();
        let html = variant_page(&variant, Standard::Fmi2);
        assert!(html.contains("<tr><td><code>vc</code></td><td>0.146</td>"));
        assert!(html.contains("<tr><td><code>kt</code></td><td>30000</td>"));
        assert!(html.contains(
            "<tr><td><code>law</code></td><td>1 coulomb (of 1 coulomb, 2 dahl, 3 lugre)</td>"
        ));
        assert!(html.contains("<h2>Fixed values</h2>") && html.contains("<code>FT_mean</code>"));
        assert!(!html.contains("<code>FT</code>"));
    }

    /// The FMI 3.0 page is the FMI 2.0 one with the note on FMI 3.0's names after the
    /// description.
    #[test]
    fn the_fmi3_page_adds_its_note_alone() {
        for model in crate::models::MODELS {
            let (fmi2, fmi3) = (page(model, Standard::Fmi2), page(model, Standard::Fmi3));
            assert!(!fmi2.contains(FMI3_NOTE));
            assert_eq!(fmi3.replacen(FMI3_NOTE, "", 1), fmi2);
        }
    }
}
