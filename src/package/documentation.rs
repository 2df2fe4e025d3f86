//! documentation/index.html: the model's equations and source (hand-written, per model) and its
//! variables (generated from the same table as modelDescription.xml).

use crate::interface::variable::{Causality, Kind, ModelTable};

fn equations(model_identifier: &str) -> &'static str {
    match model_identifier {
        "LongitudinalFriction" => include_str!("docs/LongitudinalFriction.html"),
        "TransverseFriction" => include_str!("docs/TransverseFriction.html"),
        "DryFrictionOscillator" => include_str!("docs/DryFrictionOscillator.html"),
        "DriveTrain" => include_str!("docs/DriveTrain.html"),
        _ => "",
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn variable_rows(table: &ModelTable, causality: Causality) -> String {
    let mut rows = String::new();
    for v in table.variables.iter().filter(|v| v.causality == causality) {
        let (start, unit) = match v.kind {
            Kind::Real { start, unit, .. } => {
                let start = if causality == Causality::Output {
                    String::new()
                } else {
                    start.to_string()
                };
                (start, unit.to_string())
            }
            Kind::Integer { start, .. } => (start.to_string(), String::new()),
            Kind::Enumeration { type_name, start } => {
                let items = table.enum_type(type_name).map(|e| e.items).unwrap_or(&[]);
                let all: Vec<&str> = items.iter().map(|(n, _)| *n).collect();
                let default = table
                    .enum_type(type_name)
                    .and_then(|e| e.item(start))
                    .unwrap_or("");
                (format!("{default} (of {})", all.join(", ")), String::new())
            }
        };
        rows.push_str(&format!(
            "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            escape(v.name),
            escape(&start),
            escape(&unit),
            escape(v.description)
        ));
    }
    rows
}

pub fn page(table: &ModelTable) -> String {
    let mut sections = String::new();
    for (title, causality) in [
        ("Parameters", Causality::Parameter),
        ("Inputs", Causality::Input),
        ("Outputs", Causality::Output),
    ] {
        let rows = variable_rows(table, causality);
        if !rows.is_empty() {
            sections.push_str(&format!(
                "<h2>{title}</h2>\n<table>\n<tr><th>name</th><th>default</th><th>unit</th><th>meaning</th></tr>\n{rows}</table>\n"
            ));
        }
    }
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{id}</title>\n<style>body{{font-family:sans-serif;max-width:50em;margin:auto}}table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:2px 6px;text-align:left}}</style></head>\n<body>\n<h1>{id}</h1>\n<p>{description}</p>\n{equations}\n{sections}</body></html>\n",
        id = table.model_identifier,
        description = escape(table.description),
        equations = equations(table.model_identifier),
    )
}

#[cfg(test)]
mod tests {
    use super::{equations, page};

    /// Every model ships a written description, and its page lists every variable.
    #[test]
    fn every_model_has_a_documentation_page() {
        for model in crate::scenes::MODELS {
            let id = model.table.model_identifier;
            assert!(
                equations(id).contains("<h2>Source</h2>"),
                "{id} has no description"
            );
            let html = page(model.table);
            for v in model.table.variables {
                assert!(
                    html.contains(&format!("<code>{}</code>", v.name)),
                    "{id}: {}",
                    v.name
                );
            }
        }
    }
}
