//! The bytes behind a glTF: the GLB container split with checked lengths, the JSON
//! validated into a document, buffers resolved (GLB `BIN` chunk, base64 `data:` URIs,
//! files), and accessors read, every length checked against the bytes actually present so
//! that a file claiming a 2 GB buffer is an error rather than an allocation.

use std::path::{Path, PathBuf};

use ::gltf::buffer::Source;
use base64::Engine as _;

use super::ImportError;

/// Reads a buffer that a URI names: (bytes, the file read).
pub type ExternalLoader<'a> = dyn Fn(&str) -> Result<(Vec<u8>, PathBuf), ImportError> + 'a;

/// The glTF document of JSON bytes, validated.
pub fn document(path: &Path, json: &[u8]) -> Result<::gltf::Document, ImportError> {
    let root: ::gltf::json::Root = ::gltf::json::deserialize::from_slice(json)
        .map_err(|e| parse(path, "glTF", e.to_string()))?;
    // gltf-json 1.4.1 looks up a primitive's POSITION accessor while validating, before it
    // checks the index, and panics on one out of range: check every attribute first.
    // Found by fuzzing: generator/tests/fuzz_regressions/gltf/.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for primitive in &mesh.primitives {
            if primitive.attributes.values().any(|a| a.value() >= root.accessors.len()) {
                let reason = format!("mesh {m} names an accessor that does not exist");
                return Err(parse(path, "glTF", reason));
            }
        }
    }
    ::gltf::Document::from_json(root).map_err(|e| parse(path, "glTF", e.to_string()))
}

/// A parse error of a glTF or GLB file.
pub fn parse(path: &Path, format: &'static str, reason: String) -> ImportError {
    ImportError::Parse { path: path.into(), format, reason }
}

/// The JSON chunk and BIN chunk of a GLB (checked lengths), or the bytes as JSON.
pub fn split_glb<'a>(
    path: &Path,
    bytes: &'a [u8],
) -> Result<(&'a [u8], Option<&'a [u8]>), ImportError> {
    if !bytes.starts_with(b"glTF") {
        return Ok((bytes, None));
    }
    let fail = |reason: &str| parse(path, "GLB", reason.into());
    let word = |at: usize| -> Option<usize> {
        let b = bytes.get(at..at.checked_add(4)?)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let (version, length) = (word(4), word(8));
    if version != Some(2) {
        return Err(fail("only GLB version 2 is supported"));
    }
    let end = match length {
        Some(n) if (12..=bytes.len()).contains(&n) => n,
        _ => return Err(fail("the header's length is outside the file")),
    };
    let chunk = |at: usize| -> Option<(&'a [u8], &'a [u8], usize)> {
        let length = word(at)?;
        let kind = bytes.get(at + 4..at + 8)?;
        let start = at.checked_add(8)?;
        let stop = start.checked_add(length)?;
        (stop <= end).then(|| (kind, &bytes[start..stop], stop))
    };
    let (kind, json, next) = chunk(12).ok_or_else(|| fail("the JSON chunk is cut short"))?;
    if kind != b"JSON" {
        return Err(fail("the first chunk is not JSON"));
    }
    let bin = match next.checked_add(8) {
        Some(n) if n <= end => {
            let (kind, data, _) = chunk(next).ok_or_else(|| fail("the BIN chunk is cut short"))?;
            (kind == b"BIN\0").then_some(data)
        }
        _ => None,
    };
    Ok((json, bin))
}

/// Every buffer's bytes, checked to hold at least the length the buffer claims.
pub fn load_buffers(
    document: &::gltf::Document,
    bin: Option<&[u8]>,
    external: &ExternalLoader,
    files: &mut Vec<PathBuf>,
) -> Result<Vec<Vec<u8>>, ImportError> {
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let index = buffer.index();
        let fail = |reason: String| ImportError::Buffer { index, reason };
        let data = match buffer.source() {
            Source::Bin => {
                bin.ok_or_else(|| fail("refers to a BIN chunk the file lacks".into()))?.to_vec()
            }
            Source::Uri(uri) if uri.starts_with("data:") => {
                let (head, payload) =
                    uri.split_once(',').ok_or_else(|| fail("a data URI without a comma".into()))?;
                if !head.ends_with(";base64") {
                    return Err(fail("only base64 data URIs are supported".into()));
                }
                base64::engine::general_purpose::STANDARD
                    .decode(payload)
                    .map_err(|e| fail(format!("bad base64: {e}")))?
            }
            Source::Uri(uri) => {
                let (data, file) = external(uri)?;
                files.push(file);
                data
            }
        };
        if data.len() < buffer.length() {
            return Err(fail(format!("claims {} bytes but holds {}", buffer.length(), data.len())));
        }
        buffers.push(data);
    }
    Ok(buffers)
}

/// An accessor's elements packed tightly (`count * element size` bytes), after checking
/// that the accessor fits its view and the view fits the buffer's real bytes.
pub fn read_accessor(accessor: &::gltf::Accessor, buffers: &[Vec<u8>]) -> Result<Vec<u8>, String> {
    if accessor.sparse().is_some() {
        return Err("sparse accessors are not supported".into());
    }
    let view = accessor.view().ok_or("an accessor without a buffer view")?;
    let buffer = buffers.get(view.buffer().index()).ok_or("a view of a missing buffer")?;
    let element = accessor.size();
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!("byteStride {stride} is smaller than an element ({element} bytes)"));
    }
    let view_end = view.offset().checked_add(view.length());
    let data = match view_end {
        Some(end) if end <= buffer.len() => &buffer[view.offset()..end],
        _ => return Err("a buffer view reaches past its buffer's bytes".into()),
    };
    let count = accessor.count();
    let needed = match count {
        0 => Some(0),
        n => stride
            .checked_mul(n - 1)
            .and_then(|b| b.checked_add(element))
            .and_then(|b| b.checked_add(accessor.offset())),
    };
    match needed {
        Some(n) if n <= data.len() => {}
        _ => return Err(format!("{count} elements do not fit the buffer view")),
    }
    let mut packed = Vec::with_capacity(count * element);
    for i in 0..count {
        let start = accessor.offset() + i * stride;
        packed.extend_from_slice(&data[start..start + element]);
    }
    Ok(packed)
}

/// The document's materials as surface materials: the base colour factor, times the base
/// colour texture where its image can be read (a buffer view, a base64 `data:` URI or a
/// file beside the asset); an image that cannot be read is logged and left out.
pub fn materials(
    document: &::gltf::Document,
    buffers: &[Vec<u8>],
    external: &ExternalLoader,
) -> Vec<std::sync::Arc<super::surface::SurfaceMaterial>> {
    document
        .materials()
        .map(|m| {
            let pbr = m.pbr_metallic_roughness();
            let [r, g, b, _] = pbr.base_color_factor();
            let texture = pbr.base_color_texture().and_then(|info| {
                let bytes = image_bytes(&info.texture().source(), buffers, external);
                let decoded =
                    bytes.and_then(|b| image::load_from_memory(&b).map_err(|e| e.to_string()));
                match decoded {
                    Ok(image) => Some(std::sync::Arc::new(image.into_rgb8())),
                    Err(e) => {
                        tracing::warn!("glTF material {:?}: base colour texture: {e}", m.name());
                        None
                    }
                }
            });
            std::sync::Arc::new(super::surface::SurfaceMaterial {
                name: m.name().unwrap_or("material").to_string(),
                colour: [r, g, b].map(|c| c.clamp(0.0, 1.0)),
                texture,
            })
        })
        .collect()
}

/// The encoded bytes of a glTF image.
fn image_bytes(
    image: &::gltf::image::Image,
    buffers: &[Vec<u8>],
    external: &ExternalLoader,
) -> Result<Vec<u8>, String> {
    match image.source() {
        ::gltf::image::Source::View { view, .. } => {
            let buffer = buffers.get(view.buffer().index()).ok_or("a view of a missing buffer")?;
            let end = view.offset().checked_add(view.length()).filter(|&e| e <= buffer.len());
            let end = end.ok_or("the image's view reaches past its buffer")?;
            Ok(buffer[view.offset()..end].to_vec())
        }
        ::gltf::image::Source::Uri { uri, .. } if uri.starts_with("data:") => {
            let (_, data) = uri.split_once(";base64,").ok_or("only base64 data URIs are read")?;
            base64::engine::general_purpose::STANDARD.decode(data).map_err(|e| e.to_string())
        }
        ::gltf::image::Source::Uri { uri, .. } => {
            external(uri).map(|(bytes, _)| bytes).map_err(|e| e.to_string())
        }
    }
}
