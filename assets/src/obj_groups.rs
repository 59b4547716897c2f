//! An OBJ asset: one group (or object) per part, and joints from its sidecar.

use std::path::{Path, PathBuf};

use super::mesh_build::build_mesh;
use super::mesh_files::parse_obj;
use super::sidecar::{read_sidecar, sidecar_path, Sidecar};
use super::skeleton::{RawLink, Skeleton};
use super::{text, ImportError};

/// The skeleton of the OBJ at `path` with its sidecar, and the files read besides the OBJ.
pub fn read_obj_asset(path: &Path) -> Result<(Skeleton, Vec<PathBuf>), ImportError> {
    let sidecar = sidecar_path(path);
    if !sidecar.is_file() {
        return Err(ImportError::MissingSidecar { path: path.into(), sidecar });
    }
    let spec = read_sidecar(&sidecar)?;
    let skeleton = obj_skeleton(path, &text::read_text(path)?, &spec)?;
    Ok((skeleton, vec![sidecar]))
}

/// The skeleton of OBJ text and a parsed sidecar (`path` names the OBJ in errors and
/// gives the default category).
pub fn obj_skeleton(path: &Path, text: &str, spec: &Sidecar) -> Result<Skeleton, ImportError> {
    let groups = parse_obj(path, text)?;
    if groups.is_empty() {
        return Err(ImportError::EmptyMesh { link: path.display().to_string() });
    }
    let links = groups
        .into_iter()
        .map(|g| {
            let mesh = build_mesh(&g.name, &g.positions, &g.triangles)?;
            Ok(RawLink { name: g.name, mesh, surface: g.surface })
        })
        .collect::<Result<_, ImportError>>()?;
    let joints = spec.joints.iter().map(|j| j.to_raw(None, None)).collect::<Result<_, _>>()?;
    Ok(Skeleton { category: category(path, spec.category.as_deref()), links, joints })
}

/// The category: the one given, else the file stem.
pub fn category(path: &Path, given: Option<&str>) -> String {
    given.map(String::from).unwrap_or_else(|| {
        path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default()
    })
}
