//! What one FMU's library carries: which models, and which GUIDs (FMI 2.0) or instantiation
//! tokens (FMI 3.0, the same strings) it accepts.
//!
//! The crate's own cdylib carries every model ([`Binary::ALL`], for the in-process driver, the
//! Rust tests and the report). The library packed into an FMU is built from `binary/`, a crate
//! that names one model and whether it reads variants: the linker then leaves every other
//! model out, and instantiation refuses any GUID but its FMU's, or, in a variant FMU's library
//! (one for every variant of its model), any GUID but the one the variant in the resources it
//! is handed hashes to.

use crate::error::Error;
use crate::models::{Model, MODELS};
use crate::variant::registry::{self, Loaded};
use std::sync::Arc;

/// Finds the variant behind a GUID (see [`registry::for_guid`]).
pub type Variants = fn(&str, Option<&str>, &'static [Model]) -> Result<Arc<Loaded>, Error>;

/// The models a library carries and which GUIDs it accepts.
pub struct Binary {
    pub models: &'static [Model],
    /// Accept the full models' GUIDs (a full model's FMU).
    pub full_models: bool,
    /// Accept a variant FMU's GUID, checked against its resources/variant.toml; None leaves the
    /// variant reader out of the library.
    pub variants: Option<Variants>,
}

impl Binary {
    pub const ALL: Binary = Binary {
        models: MODELS,
        full_models: true,
        variants: Some(registry::for_guid),
    };

    /// The model and GUID a GUID names among what the library carries: a full model's, or else
    /// a variant FMU's, whose resources/variant.toml must describe an interface with that GUID.
    /// `argument` is the standard's name for the GUID, for the message.
    #[allow(clippy::type_complexity)]
    pub fn model_of(
        &self,
        guid: &str,
        resource_location: Option<&str>,
        argument: &str,
    ) -> Result<(&'static Model, &'static str, Option<Arc<Loaded>>), Error> {
        let binary = self;
        let full: Vec<(&'static Model, &'static str)> = if binary.full_models {
            binary
                .models
                .iter()
                .filter_map(|m| crate::fmi2::guid(m.table.model_identifier).map(|g| (m, g)))
                .collect()
        } else {
            Vec::new()
        };
        if let Some(&(model, guid)) = full.iter().find(|(_, g)| *g == guid) {
            return Ok((model, guid, None));
        }
        let known: Vec<String> = full
            .iter()
            .map(|(m, g)| format!("{g} ({})", m.table.model_identifier))
            .collect();
        let expected = if known.is_empty() {
            "the GUID of the variant in its resources (this binary is a variant FMU's)".to_string()
        } else {
            format!(
                "{} (is the modelDescription.xml from another build, or another FMU's?)",
                known.join(" or ")
            )
        };
        let found = format!("{argument} \"{guid}\" matches no model of this binary");
        let Some(variants) = binary.variants else {
            return Err(Error::refused(found, expected));
        };
        variants(guid, resource_location, binary.models)
            // A variant's instance takes its GUID from the file.
            .map(|loaded| (loaded.variant.model, "", Some(loaded)))
            .map_err(|why| Error {
                found: format!("{found}, nor a variant's: {}", why.found),
                expected: format!("{expected}; or {}", why.expected),
                ..why
            })
    }
}

/// Exports the FMI 2.0 and FMI 3.0 functions of one FMU's library (the same library goes into
/// both standards' FMUs): `$model` names a model constant of
/// [`crate::models`]; `full` accepts its GUID, `variant` a variant's (and carries the reader).
#[macro_export]
macro_rules! export_fmu_library {
    ($model:ident, full) => {
        static BINARY: $crate::instance::library::Binary = $crate::instance::library::Binary {
            models: &[$crate::models::$model],
            full_models: true,
            variants: None,
        };
        $crate::export_fmi2!(&BINARY);
        $crate::export_fmi3!(&BINARY);
    };
    ($model:ident, variant) => {
        static BINARY: $crate::instance::library::Binary = $crate::instance::library::Binary {
            models: &[$crate::models::$model],
            full_models: false,
            variants: Some($crate::variant::registry::for_guid),
        };
        $crate::export_fmi2!(&BINARY);
        $crate::export_fmi3!(&BINARY);
    };
}
