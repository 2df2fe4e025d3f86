//! Variants loaded by fmi2Instantiate. Each distinct (path, content) is parsed once while
//! instances made from it live, so a master that instantiates many times from one FMU parses it
//! once; the last instance to go frees it, so a process that loads ever other files (or the same
//! file edited) holds only what its live instances use.

use super::{Refused, Variant};
use crate::error::Error;
use crate::models::{Model, Scope};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, Weak};

/// A checked variant with what its instances need, computed once.
pub struct Loaded {
    pub variant: Variant,
    /// The GUID of the interface the file describes.
    pub guid: String,
    pub scope: Scope,
}

struct Entry {
    path: PathBuf,
    loaded: Weak<Loaded>,
}

static LOADED: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

fn loaded() -> MutexGuard<'static, Vec<Entry>> {
    // A panic elsewhere while holding the lock cannot leave the list inconsistent: recover it.
    LOADED.lock().unwrap_or_else(|e| e.into_inner())
}

/// The variant at `path`, parsed unless a live instance already uses this (path, content).
pub fn load(path: &Path, models: &'static [Model]) -> Result<Arc<Loaded>, Refused> {
    let file = path.display().to_string();
    let text = super::read_text(path, &file)?;
    let mut entries = loaded();
    let live = entries
        .iter()
        .filter(|e| e.path == path)
        .filter_map(|e| e.loaded.upgrade())
        .find(|l| l.variant.text == text);
    if let Some(live) = live {
        return Ok(live);
    }
    let variant = super::parse_for(&file, &text, models)?;
    let (guid, _) = variant.model_description();
    let scope = variant.scope();
    let loaded = Arc::new(Loaded {
        variant,
        guid,
        scope,
    });
    entries.push(Entry {
        path: path.to_path_buf(),
        loaded: Arc::downgrade(&loaded),
    });
    Ok(loaded)
}

/// Forgets the files no instance uses any more; called when an instance is freed. The list's
/// memory goes with its last entry, so unloading the library leaves nothing behind.
pub fn release_unused() {
    let mut entries = loaded();
    entries.retain(|e| e.loaded.strong_count() > 0);
    if entries.is_empty() {
        *entries = Vec::new();
    }
}

/// How many versions of the file at `path` the registry holds.
#[cfg(test)]
fn held(path: &Path) -> usize {
    loaded().iter().filter(|e| e.path == path).count()
}

/// The variant behind a GUID that is no full model's: `resources/variant.toml` under the
/// fmuResourceLocation, accepted only if the interface it describes hashes to `guid`. The error
/// says what is missing or does not match, for fmi2Instantiate's log.
pub fn for_guid(
    guid: &str,
    resource_location: Option<&str>,
    models: &'static [Model],
) -> Result<Arc<Loaded>, Error> {
    let location = resource_location.filter(|l| !l.is_empty()).ok_or_else(|| {
        Error::value_found(
            "fmuResourceLocation",
            "fmuResourceLocation is NULL or empty, so no resources/variant.toml of a variant FMU can confirm it",
            "the location of the FMU's resources",
        )
    })?;
    let path = super::uri::file_path(location)?.join(super::RESOURCE);
    if !path.is_file() {
        return Err(Error::refused(
            format!("there is no variant {}", path.display()),
            "a full model's GUID or a variant FMU's resources/variant.toml",
        ));
    }
    let loaded = load(&path, models)?;
    if loaded.guid != guid {
        return Err(Error::combination(
            format!(
                "{} describes an interface with GUID {}, not this one",
                path.display(),
                loaded.guid
            ),
            "the variant the FMU was packed with (was it edited after packing?)",
        ));
    }
    Ok(loaded)
}

#[cfg(test)]
mod tests {
    use super::{for_guid, held, load, release_unused};
    use crate::error::Kind;
    use crate::models::MODELS;
    use std::sync::Arc;

    const VARIANT: &str = "name = \"Cached\"\nmodel = \"DryFrictionOscillator\"\nlaw = \"exact\"\nsolver = \"rk4\"\noutputs = [\"u\"]\n[experiment]\nstart = 0\nstop = 1\nstep = 0.1\n";

    /// Oracle: the GUID of the packed XML (`model_description`); the registry hands out one
    /// entry per (path, content) while it is used, and a changed file is a new entry with
    /// another GUID.
    #[test]
    fn variant_resources_are_checked_against_the_guid_and_parsed_once() {
        let dir = std::env::temp_dir().join(format!("variant registry {}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("variant.toml");
        std::fs::write(&file, VARIANT).unwrap();
        let guid = crate::variant::parse("x", VARIANT)
            .unwrap()
            .model_description()
            .0;
        let uri = format!("file://{}", dir.display()).replace(' ', "%20");
        let first = for_guid(&guid, Some(&uri), MODELS).unwrap();
        let second = for_guid(&guid, Some(&format!("{uri}/")), MODELS).unwrap();
        assert!(Arc::ptr_eq(&first, &second));
        assert_eq!(first.variant.name, "Cached");
        assert!(first.scope.fixes(crate::models::oscillator::table::vr::P));

        // Another GUID, and the file edited after packing: the file and the GUID disagree.
        let wrong = for_guid("{0}", Some(&uri), MODELS).err().unwrap();
        assert_eq!(wrong.kind, Kind::Combination, "{wrong}");
        std::fs::write(&file, VARIANT.replace("stop = 1", "stop = 2")).unwrap();
        let edited = for_guid(&guid, Some(&uri), MODELS).err().unwrap();
        assert_eq!(edited.kind, Kind::Combination, "{edited}");
        let nowhere = for_guid(&guid, None, MODELS).err().unwrap();
        assert_eq!(
            nowhere.kind,
            Kind::Value {
                name: "fmuResourceLocation"
            }
        );
        std::fs::remove_file(&file).unwrap();
        let missing = for_guid(&guid, Some(&uri), MODELS).err().unwrap();
        assert_eq!(missing.kind, Kind::Refused, "{missing}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Oracle: counting. A file is held while something uses it and forgotten with its last
    /// user, so loading ever-changing files (a master instantiating and freeing for hours, an
    /// edited file, another path) holds at most what is live.
    #[test]
    fn files_nothing_uses_are_forgotten() {
        let dir = std::env::temp_dir().join(format!("variant release {}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("variant.toml");
        for cycle in 0..200 {
            std::fs::write(&file, format!("# cycle {cycle}\n{VARIANT}")).unwrap();
            let first = load(&file, MODELS).unwrap();
            let again = load(&file, MODELS).unwrap();
            assert!(Arc::ptr_eq(&first, &again));
            assert_eq!(held(&file), 1);
            drop((first, again));
            release_unused();
            assert_eq!(held(&file), 0, "cycle {cycle}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
