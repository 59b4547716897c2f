//! What an asset's triangles look like, for `generator render`: per triangle its corners
//! (in the same frame as the link's mesh), texture coordinates and material, kept as an
//! unwelded soup beside the mesh (welding merges vertices across texture seams). Read from
//! OBJ files with their MTL (`Kd` colour, `map_Kd` texture, PNG or JPEG), glTF materials
//! (base colour factor and texture, `TEXCOORD_0`) and URDF `<material>` colours.

use std::path::Path;
use std::sync::Arc;

use pairs::math::Point3;

/// A material: a diffuse colour, times a texture where it has one.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceMaterial {
    /// Its name in the file.
    pub name: String,
    /// Diffuse colour (`Kd`, or a URDF `rgba`), linear RGB in [0, 1].
    pub colour: [f32; 3],
    /// Diffuse texture (`map_Kd`), if any.
    pub texture: Option<Arc<image::RgbImage>>,
}

impl SurfaceMaterial {
    /// Colour at texture coordinates `uv` (OBJ convention: v up from the image's bottom;
    /// wrapped; nearest texel).
    pub fn albedo(&self, uv: Option<[f32; 2]>) -> [f32; 3] {
        let (Some(texture), Some([u, v])) = (&self.texture, uv) else {
            return self.colour;
        };
        let (w, h) = texture.dimensions();
        let x = ((u.rem_euclid(1.0) * w as f32) as u32).min(w - 1);
        let y = (((1.0 - v.rem_euclid(1.0)) * h as f32) as u32).min(h - 1);
        let t = texture.get_pixel(x, y).0;
        std::array::from_fn(|c| self.colour[c] * f32::from(t[c]) / 255.0)
    }
}

/// The styled triangles of one link: parallel lists, one entry per triangle.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Surface {
    /// Corners, counter-clockwise.
    pub corners: Vec<[Point3; 3]>,
    /// Texture coordinates of the corners, where the file gives them.
    pub uv: Vec<Option<[[f32; 2]; 3]>>,
    /// Material, where the file names one.
    pub material: Vec<Option<Arc<SurfaceMaterial>>>,
}

impl Surface {
    /// Whether any triangle has a material.
    pub fn is_styled(&self) -> bool {
        self.material.iter().any(Option::is_some)
    }

    /// Appends another surface's triangles.
    pub fn append(&mut self, other: Surface) {
        self.corners.extend(other.corners);
        self.uv.extend(other.uv);
        self.material.extend(other.material);
    }

    /// Every corner moved by `f`; `mirror` reverses the winding (a mirroring scale).
    pub fn map(mut self, f: impl Fn(&Point3) -> Point3, mirror: bool) -> Self {
        for (t, uv) in self.corners.iter_mut().zip(&mut self.uv) {
            *t = t.map(|p| f(&p));
            if mirror {
                t.swap(1, 2);
                if let Some(uv) = uv {
                    uv.swap(1, 2);
                }
            }
        }
        self
    }

    /// Gives every triangle without a material `material`.
    pub fn with_default(mut self, material: &Arc<SurfaceMaterial>) -> Self {
        for m in &mut self.material {
            if m.is_none() {
                *m = Some(material.clone());
            }
        }
        self
    }

    /// A surface of plain triangles (no texture coordinates or materials).
    pub fn plain(positions: &[Point3], triangles: &[[u32; 3]]) -> Self {
        let corners: Vec<[Point3; 3]> =
            triangles.iter().map(|t| t.map(|i| positions[i as usize])).collect();
        let n = corners.len();
        Self { corners, uv: vec![None; n], material: vec![None; n] }
    }
}

/// The materials of an OBJ's `mtllib` files (relative to the OBJ's folder), with their
/// textures; a file or texture that cannot be read is left out (the triangles then get the
/// renderer's own material), and `warn` is told why.
pub fn load_mtl(obj: &Path, mtl: &Path, warn: &mut dyn FnMut(String)) -> tobj::MTLLoadResult {
    let dir = obj.parent().unwrap_or(Path::new("."));
    let path = dir.join(mtl);
    let text = std::fs::read(&path).map_err(|e| {
        warn(format!("{}: {e}", path.display()));
        tobj::LoadError::OpenFileFailed
    })?;
    tobj::load_mtl_buf(&mut std::io::Cursor::new(text))
}

/// The materials tobj read, as surface materials (textures loaded relative to the OBJ).
pub fn materials(
    obj: &Path,
    materials: &[tobj::Material],
    warn: &mut dyn FnMut(String),
) -> Vec<Arc<SurfaceMaterial>> {
    let dir = obj.parent().unwrap_or(Path::new("."));
    materials
        .iter()
        .map(|m| {
            let texture = m.diffuse_texture.as_ref().and_then(|t| {
                let path = dir.join(t.trim());
                match image::open(&path) {
                    Ok(image) => Some(Arc::new(image.into_rgb8())),
                    Err(e) => {
                        warn(format!("texture {}: {e}", path.display()));
                        None
                    }
                }
            });
            let colour = m.diffuse.map_or([1.0; 3], |d| d.map(|c| c.clamp(0.0, 1.0)));
            Arc::new(SurfaceMaterial { name: m.name.clone(), colour, texture })
        })
        .collect()
}

/// The corners' texture coordinates of triangle `t` of a tobj mesh (single index).
pub fn corner_uv(texcoords: &[f32], t: &[u32]) -> Option<[[f32; 2]; 3]> {
    let at = |i: u32| -> Option<[f32; 2]> {
        let i = i as usize * 2;
        Some([*texcoords.get(i)?, *texcoords.get(i + 1)?])
    };
    Some([at(t[0])?, at(t[1])?, at(t[2])?])
}
