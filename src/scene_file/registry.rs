//! Scene files loaded by fmi2Instantiate, kept for the life of the process: each distinct
//! (path, content) is parsed once and leaked once, so instances can borrow it as `'static` and a
//! master that instantiates thousands of times does not parse or leak thousands of times.

use super::SceneFile;
use crate::scenes::Scope;
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
pub fn load(path: &Path) -> Result<&'static Loaded, String> {
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
    let scene = super::parse(&file, &text)?;
    let (guid, _) = scene.model_description();
    let scope = scene.scope();
    let entry: &'static Loaded = Box::leak(Box::new(Loaded { scene, guid, scope }));
    loaded.push(Entry {
        path: path.to_path_buf(),
        loaded: entry,
    });
    Ok(entry)
}
