//! Finding assets in a folder tree.

use std::path::{Path, PathBuf};

use super::sidecar::sidecar_path;
use super::ImportError;

/// Deepest folder nesting searched (symbolic links to files are followed, to folders not,
/// so that a link cycle cannot loop).
const MAX_DEPTH: usize = 64;

/// Whether `path` is an asset's main file: a `.urdf`, `.gltf` or `.glb`, or an `.obj`
/// with its `<name>.joints.json` sidecar (an OBJ without one is taken to be a URDF's mesh).
pub fn is_asset(path: &Path) -> bool {
    match extension(path).as_str() {
        "urdf" | "gltf" | "glb" => true,
        "obj" => sidecar_path(path).is_file(),
        _ => false,
    }
}

/// The lower-case extension of a path.
pub fn extension(path: &Path) -> String {
    path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase()
}

/// The assets under `root`, sorted by path: `root` itself when it is a file, else every
/// asset file found recursively.
pub fn discover_assets(root: &Path) -> Result<Vec<PathBuf>, ImportError> {
    let meta =
        std::fs::metadata(root).map_err(|error| ImportError::Io { path: root.into(), error })?;
    if meta.is_file() {
        return Ok(vec![root.into()]);
    }
    let mut found = Vec::new();
    walk(root, 0, &mut found)?;
    found.sort();
    Ok(found)
}

fn walk(dir: &Path, depth: usize, found: &mut Vec<PathBuf>) -> Result<(), ImportError> {
    if depth > MAX_DEPTH {
        return Ok(());
    }
    let io = |error| ImportError::Io { path: dir.into(), error };
    let mut entries: Vec<_> =
        std::fs::read_dir(dir).map_err(io)?.collect::<Result<_, _>>().map_err(io)?;
    entries.sort_by_key(|e| e.file_name());
    for entry in entries {
        let path = entry.path();
        let kind = entry.file_type().map_err(io)?;
        if kind.is_dir() {
            walk(&path, depth + 1, found)?;
        } else if (kind.is_file() || kind.is_symlink() && path.is_file()) && is_asset(&path) {
            found.push(path);
        }
    }
    Ok(())
}
