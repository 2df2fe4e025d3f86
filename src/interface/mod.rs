//! The models' interfaces as data: one variable table per model.
//!
//! `build.rs` includes this module too (with `#[path]`) to write modelDescription.xml, so nothing
//! here may refer to the rest of the crate.

pub mod longitudinal;
pub mod oscillator;
pub mod table;
pub mod transverse;
pub mod values;
pub mod variable;

/// Every model this crate exports, in the order the CLI builds them.
pub const MODELS: &[&variable::ModelTable] =
    &[&longitudinal::TABLE, &transverse::TABLE, &oscillator::TABLE];
