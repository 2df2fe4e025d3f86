//! Scene files loaded by fmi2Instantiate, kept for the life of the process: each distinct
//! (path, content) is parsed once and leaked once, so instances can borrow it as `'static` and a
//! master that instantiates thousands of times does not parse or leak thousands of times.

use super::SceneFile;
use crate::scenes::{Model, Scope};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// A checked scene file with what its instances need, computed once.
pub struct Loaded {
    pub scene: SceneFile,
    /// The GUID of the interface the file describes.
    pub guid: String,
    pub scope: Scope,
}

struct Entry {
    path: PathBuf,
    loaded: &'static Loaded,
}

static LOADED: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// The scene file at `path`, parsed on first sight of this (path, content).
pub fn load(path: &Path, models: &'static [Model]) -> Result<&'static Loaded, String> {
    let file = path.display().to_string();
    let text =
        std::fs::read_to_string(path).map_err(|e| format!("{file}: cannot read the file: {e}"))?;
    // A panic elsewhere while holding the lock cannot leave the list inconsistent: recover it.
    let mut loaded = LOADED.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(entry) = loaded
        .iter()
        .find(|e| e.path == path && e.loaded.scene.text == text)
    {
        return Ok(entry.loaded);
    }
    let scene = super::parse_for(&file, &text, models)?;
    let (guid, _) = scene.model_description();
    let scope = scene.scope();
    let entry: &'static Loaded = Box::leak(Box::new(Loaded { scene, guid, scope }));
    loaded.push(Entry {
        path: path.to_path_buf(),
        loaded: entry,
    });
    Ok(entry)
}

/// The scene file behind a GUID that is no full model's: `resources/scene.toml` under the
/// fmuResourceLocation, accepted only if the interface it describes hashes to `guid`. The error
/// says what is missing or does not match, for fmi2Instantiate's log.
pub fn for_guid(
    guid: &str,
    resource_location: Option<&str>,
    models: &'static [Model],
) -> Result<&'static Loaded, String> {
    let location = resource_location.filter(|l| !l.is_empty()).ok_or_else(|| {
        "fmuResourceLocation is NULL or empty, so no resources/scene.toml of a scene FMU can confirm it".to_string()
    })?;
    let path = super::uri::file_path(location)
        .map_err(|e| format!("fmuResourceLocation {e}"))?
        .join(super::RESOURCE);
    if !path.is_file() {
        return Err(format!(
            "there is no scene file {}: expected a full model's GUID or a scene FMU's resources/scene.toml",
            path.display()
        ));
    }
    let loaded = load(&path, models)?;
    if loaded.guid != guid {
        return Err(format!(
            "{} describes an interface with GUID {}, not this one: expected the scene file the FMU was packed with (was it edited after packing?)",
            path.display(),
            loaded.guid
        ));
    }
    Ok(loaded)
}

#[cfg(test)]
mod tests {
    use super::for_guid;
    use crate::scenes::MODELS;

    const SCENE: &str = "name = \"Cached\"\nmodel = \"DryFrictionOscillator\"\nlaw = \"exact\"\nsolver = \"rk4\"\noutputs = [\"u\"]\n[experiment]\nstart = 0\nstop = 1\nstep = 0.1\n";

    /// Oracle: the GUID of the packed XML (`model_description`); the registry hands out one
    /// leaked entry per (path, content), and a changed file is a new entry with another GUID.
    #[test]
    fn scene_resources_are_checked_against_the_guid_and_parsed_once() {
        let dir = std::env::temp_dir().join(format!("scene registry {}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("scene.toml");
        std::fs::write(&file, SCENE).unwrap();
        let guid = crate::scene_file::parse("x", SCENE)
            .unwrap()
            .model_description()
            .0;
        let uri = format!("file://{}", dir.display()).replace(' ', "%20");
        let first = for_guid(&guid, Some(&uri), MODELS).unwrap();
        let second = for_guid(&guid, Some(&format!("{uri}/")), MODELS).unwrap();
        assert!(std::ptr::eq(first, second));
        assert_eq!(first.scene.name, "Cached");
        assert!(first.scope.fixes(crate::interface::oscillator::vr::P));

        let wrong = for_guid("{0}", Some(&uri), MODELS).err().unwrap();
        assert!(
            wrong.contains(&format!("describes an interface with GUID {guid}")),
            "{wrong}"
        );
        std::fs::write(&file, SCENE.replace("stop = 1", "stop = 2")).unwrap();
        let edited = for_guid(&guid, Some(&uri), MODELS).err().unwrap();
        assert!(edited.contains("was it edited after packing?"), "{edited}");
        assert!(for_guid(&guid, None, MODELS)
            .err()
            .unwrap()
            .contains("NULL or empty"));
        std::fs::remove_file(&file).unwrap();
        assert!(for_guid(&guid, Some(&uri), MODELS)
            .err()
            .unwrap()
            .contains("there is no scene file"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
