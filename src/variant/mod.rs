//! Variants: a TOML file that fixes most of a model's parameters and packs an FMU exposing
//! only the rest (`friction-fmu build variants/fig4a.toml` writes `fmu-out/Fig4a.fmu`).
//!
//! ```toml
//! name = "Fig4a"              # modelIdentifier of the packed FMU: fmu-out/Fig4a.fmu
//! model = "TransverseFriction" # LongitudinalFriction, TransverseFriction or DryFrictionOscillator
//! description = "Paper T, Fig. 4a: ..."   # optional, else the model's
//! law = "split"               # required: the friction law (L: law, T: slip_law, O: law)
//! solver = "dopri5"           # required: the model's `solver`
//! tunable = ["vd"]            # parameters that stay in the interface, start = the value below
//! inputs = []                 # inputs that stay; a hidden input keeps its value
//! outputs = ["FF", "FFx"]     # outputs that stay (at least one)
//! [parameters]                # values of any other parameter or input (enumerations by item)
//! va = 0.0
//! vd = 0.5e-3
//! [experiment]                # the DefaultExperiment of the packed FMU
//! start = 0.0
//! stop = 0.015
//! step = 1.6666666666666667e-5  # stepSize
//! # tolerance: optional; the solver's own tolerance parameter, which it must equal
//! ```
//!
//! Everything not kept is fixed at its value (the variant's, else the model's default) and
//! absent from modelDescription.xml; the packed binary is the same library as the full models'.
//! It finds the file again in the FMU's `resources/variant.toml` at fmi2Instantiate and accepts it
//! only if the interface it describes hashes to the GUID it was instantiated with. Kept
//! parameters keep their variability (fixed ones can be set until initialisation ends).

mod check;
mod description;
mod raw;
pub mod refused;
pub mod registry;
pub mod uri;

use crate::error::Error;
use crate::model_description::Experiment;
use crate::models::Model;
use crate::variables::values::ValueSet;
pub use refused::Refused;
use std::path::Path;

/// Where a variant's FMU carries the file, under resources/.
pub const RESOURCE: &str = "variant.toml";

/// A checked variant: the model, every variable's value, and what the interface keeps.
#[derive(Clone)]
pub struct Variant {
    /// The FMU's modelIdentifier.
    pub name: String,
    pub description: String,
    pub model: &'static Model,
    /// Every variable of the model: its default, replaced by the variant's value.
    pub values: ValueSet,
    /// Value references of the variables the interface keeps, in table order.
    pub kept: Vec<u32>,
    pub experiment: Experiment,
    /// The file itself, as packed into `resources/variant.toml`.
    pub text: String,
}

/// Parses and checks a variant's text; `file` names it in the messages.
pub fn parse(file: &str, text: &str) -> Result<Variant, Refused> {
    parse_for(file, text, crate::models::MODELS)
}

/// Whether a variant can trim the model: those with a friction law (DriveTrain has nothing to
/// trim).
pub fn trimmable(model_identifier: &str) -> bool {
    crate::models::model(model_identifier).is_some_and(|m| m.table.law_parameter.is_some())
}

/// Parses and checks a variant of one of `models` (an FMU's library knows only its own).
pub fn parse_for(file: &str, text: &str, models: &'static [Model]) -> Result<Variant, Refused> {
    let raw = raw::parse(file, text)?;
    check::variant(file, raw, text, models)
}

/// Reads, parses and checks a variant.
pub fn read(path: &Path) -> Result<Variant, Refused> {
    let file = path.display().to_string();
    let text = read_text(path, &file)?;
    parse(&file, &text)
}

/// The text of the variant file at `path` (named `file` in the refusal).
fn read_text(path: &Path, file: &str) -> Result<String, Refused> {
    std::fs::read_to_string(path).map_err(|e| {
        Refused::file(
            file,
            Error::refused(
                format!("cannot read the file: {e}"),
                "a readable variant file",
            ),
        )
    })
}

#[cfg(test)]
mod tests;
