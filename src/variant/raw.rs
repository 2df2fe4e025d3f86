//! The variant as TOML gives it: keys and types, no meaning yet. Unknown keys are refused.

use super::Refused;
use crate::error::Error;
use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Raw {
    pub name: String,
    pub model: String,
    pub description: Option<String>,
    pub law: String,
    pub solver: String,
    #[serde(default)]
    pub tunable: Vec<String>,
    #[serde(default)]
    pub inputs: Vec<String>,
    pub outputs: Vec<String>,
    #[serde(default)]
    pub parameters: toml::Table,
    pub experiment: RawExperiment,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawExperiment {
    pub start: f64,
    pub stop: f64,
    pub step: f64,
    pub tolerance: Option<f64>,
}

/// Deserialises, turning TOML's message into one line naming the file and the offending line.
pub fn parse(file: &str, text: &str) -> Result<Raw, Refused> {
    toml::from_str(text).map_err(|e: toml::de::Error| {
        let message = e.message().trim_end();
        // A missing key is reported with the span of the table it is missing from, from the
        // file's start for a top-level key: no line to point at then.
        let whole = message.starts_with("missing") && e.span().is_some_and(|s| s.start == 0);
        let found = match e.span().and_then(|span| text.get(..span.start)) {
            Some(before) if !whole && !text.is_empty() && before.len() < text.len() => {
                let line = before.matches('\n').count() + 1;
                let content = text.lines().nth(line - 1).unwrap_or("").trim();
                format!("line {line} (`{content}`): {message}")
            }
            _ => message.to_string(),
        };
        Refused::file(
            file,
            Error::refused(found, "TOML with a variant's keys, each of its type"),
        )
    })
}
