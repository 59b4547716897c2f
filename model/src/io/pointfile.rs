//! Reading a user's point cloud or mesh and writing coloured point clouds, for `model infer`
//! and `model animate`: PLY (ASCII or binary little-endian; the vertex element's `x y z`,
//! any other properties skipped) and Wavefront OBJ, read by the generator's OBJ reader (its
//! faces' surface sampled by `pairs`' area-weighted sampler from a fixed seed; a file
//! without faces is the cloud of its `v` lines). Clouds larger than the network's input are
//! reduced by farthest-point sampling.

use std::path::{Path, PathBuf};

use assets::mesh_files::parse_obj;
use pairs::atomic::{at, replace_bytes, FileError};
use pairs::math::{Point3, Real};
use pairs::sampling::{point_on_triangle, triangle_area, AreaSampler};
use rand::SeedableRng;

/// Why a point file could not be read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PointFileError {
    /// The file could not be opened, read or written.
    #[error(transparent)]
    Io(#[from] FileError),
    /// The file is not a PLY or OBJ file this reader understands.
    #[error("{path}: {message}")]
    Malformed {
        /// The file.
        path: PathBuf,
        /// What is wrong (line or field named).
        message: String,
    },
    /// An OBJ file the generator's OBJ reader refused (its message names the file).
    #[error(transparent)]
    Obj(#[from] assets::ImportError),
}

fn malformed(path: &Path, message: impl Into<String>) -> PointFileError {
    PointFileError::Malformed { path: path.to_path_buf(), message: message.into() }
}

/// The points of a `.ply` or `.obj` file (by extension); meshes in OBJ files are sampled
/// to `samples` surface points. Every coordinate must be finite and the cloud non-empty.
pub fn read_points(path: &Path, samples: usize) -> Result<Vec<Point3>, PointFileError> {
    let bytes = std::fs::read(path).map_err(at(path))?;
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let points = match ext.as_deref() {
        Some("ply") => read_ply(path, &bytes)?,
        Some("obj") => read_obj(path, &bytes, samples)?,
        _ => return Err(malformed(path, "expected a .ply or .obj file")),
    };
    if points.is_empty() {
        return Err(malformed(path, "no points"));
    }
    if let Some(i) = points.iter().position(|p| !p.coords.iter().all(|v| v.is_finite())) {
        return Err(malformed(path, format!("point {i} is not finite")));
    }
    Ok(points)
}

/// Byte size of a PLY scalar type, `None` for an unknown name.
fn ply_size(kind: &str) -> Option<usize> {
    match kind {
        "char" | "uchar" | "int8" | "uint8" => Some(1),
        "short" | "ushort" | "int16" | "uint16" => Some(2),
        "int" | "uint" | "float" | "int32" | "uint32" | "float32" => Some(4),
        "double" | "float64" => Some(8),
        _ => None,
    }
}

fn read_ply(path: &Path, bytes: &[u8]) -> Result<Vec<Point3>, PointFileError> {
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .ok_or_else(|| malformed(path, "no end_header line"))?;
    let header = String::from_utf8_lossy(&bytes[..end]);
    let body = &bytes[end + 11..];
    let mut lines = header.lines();
    if lines.next().map(str::trim) != Some("ply") {
        return Err(malformed(path, "does not start with `ply`"));
    }
    let (mut format, mut count, mut in_vertex, mut first_element) = ("", 0usize, false, true);
    let mut properties: Vec<(String, String)> = Vec::new();
    for line in lines {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["format", f, ..] => format = if *f == "ascii" { "ascii" } else { f },
            ["element", name, n] => {
                in_vertex = *name == "vertex";
                if in_vertex {
                    if !first_element {
                        return Err(malformed(path, "the vertex element must come first"));
                    }
                    count = n.parse().map_err(|_| malformed(path, format!("vertex count {n}")))?;
                }
                first_element = false;
            }
            ["property", "list", ..] if in_vertex => {
                return Err(malformed(path, "list properties on vertices are not supported"))
            }
            ["property", kind, name] if in_vertex => {
                properties.push(((*kind).to_owned(), (*name).to_owned()))
            }
            _ => {}
        }
    }
    let column = |axis: &str| {
        properties
            .iter()
            .position(|(_, n)| n == axis)
            .ok_or_else(|| malformed(path, format!("no vertex property {axis}")))
    };
    let (x, y, z) = (column("x")?, column("y")?, column("z")?);
    match format {
        "ascii" => {
            let text = String::from_utf8_lossy(body);
            text.lines()
                .take(count)
                .enumerate()
                .map(|(i, line)| {
                    let v: Vec<f64> =
                        line.split_whitespace().filter_map(|w| w.parse().ok()).collect();
                    match (v.get(x), v.get(y), v.get(z)) {
                        (Some(&a), Some(&b), Some(&c)) => {
                            Ok(Point3::new(a as Real, b as Real, c as Real))
                        }
                        _ => Err(malformed(path, format!("vertex {i}: too few values"))),
                    }
                })
                .collect()
        }
        "binary_little_endian" => {
            let sizes: Vec<usize> = properties
                .iter()
                .map(|(k, _)| ply_size(k).ok_or_else(|| malformed(path, format!("type {k}"))))
                .collect::<Result<_, _>>()?;
            let stride: usize = sizes.iter().sum();
            if body.len() < stride * count {
                return Err(malformed(
                    path,
                    format!("{count} vertices need {} bytes", stride * count),
                ));
            }
            let offset = |c: usize| sizes[..c].iter().sum::<usize>();
            let read = |row: &[u8], c: usize| -> Result<Real, PointFileError> {
                let b = &row[offset(c)..offset(c) + sizes[c]];
                match properties[c].0.as_str() {
                    "float" | "float32" => Ok(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                    "double" | "float64" => {
                        Ok(f64::from_le_bytes(b.try_into().expect("8 bytes")) as Real)
                    }
                    other => Err(malformed(path, format!("coordinate type {other}"))),
                }
            };
            body.chunks_exact(stride.max(1))
                .take(count)
                .map(|row| Ok(Point3::new(read(row, x)?, read(row, y)?, read(row, z)?)))
                .collect()
        }
        other => Err(malformed(path, format!("format {other} (ascii or binary_little_endian)"))),
    }
}

/// An OBJ's surface through the generator's OBJ reader (`tobj`, fuzzed): every group's
/// triangles sampled by area; an OBJ without faces is a point cloud of its `v` lines.
fn read_obj(path: &Path, bytes: &[u8], samples: usize) -> Result<Vec<Point3>, PointFileError> {
    let text = String::from_utf8_lossy(bytes);
    let groups = parse_obj(path, &text)?;
    let corners = groups.iter().flat_map(|g| &g.positions);
    if let Some(i) = corners.clone().position(|p| !p.coords.iter().all(|v| v.is_finite())) {
        return Err(malformed(path, format!("vertex {} is not finite", i + 1)));
    }
    let triangles: Vec<[Point3; 3]> = groups
        .iter()
        .flat_map(|g| g.triangles.iter().map(|t| t.map(|v| g.positions[v as usize])))
        .collect();
    if triangles.is_empty() {
        return obj_vertices(path, &text);
    }
    Ok(sample_surface(&triangles, samples, 0))
}

/// The `v` lines of an OBJ without faces.
fn obj_vertices(path: &Path, text: &str) -> Result<Vec<Point3>, PointFileError> {
    let mut vertices = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() == Some("v") {
            let v: Vec<Real> = words.take(3).filter_map(|w| w.parse().ok()).collect();
            if v.len() != 3 {
                return Err(malformed(path, format!("line {}: a vertex needs x y z", n + 1)));
            }
            vertices.push(Point3::new(v[0], v[1], v[2]));
        }
    }
    Ok(vertices)
}

/// `n` points sampled uniformly on the triangles' surface (area-weighted, `pairs`'
/// [`AreaSampler`]) from `seed`; the triangles' first corners when none has an area.
pub fn sample_surface(triangles: &[[Point3; 3]], n: usize, seed: u64) -> Vec<Point3> {
    let areas = AreaSampler::new(triangles.iter().map(triangle_area));
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    if areas.total_area() <= 0.0 {
        return triangles.iter().take(n).map(|t| t[0]).collect();
    }
    (0..n)
        .filter_map(|_| {
            let t = areas.draw(&mut rng)?;
            Some(point_on_triangle(&mut rng, triangles[t]))
        })
        .collect()
}

/// Writes an ASCII PLY of coloured points.
pub fn write_ply(
    path: &Path,
    points: &[Point3],
    colours: &[[u8; 3]],
) -> Result<(), PointFileError> {
    use std::fmt::Write as _;
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n",
        points.len()
    );
    for (p, c) in points.iter().zip(colours.iter().chain(std::iter::repeat(&[200, 200, 200]))) {
        writeln!(text, "{} {} {} {} {} {}", p.x, p.y, p.z, c[0], c[1], c[2])
            .expect("writing to a String");
    }
    // Whole or not at all: an old file of that name survives a failed write.
    Ok(replace_bytes(path, text.as_bytes())?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ply_round_trip_and_binary() {
        let dir = tempfile::tempdir().expect("a temp dir");
        let path = dir.path().join("a.ply");
        let points = vec![Point3::new(0.5, -1.0, 2.0), Point3::new(0.0, 0.25, 1.0)];
        write_ply(&path, &points, &[[255, 0, 0]]).expect("written");
        assert_eq!(read_points(&path, 0).expect("read"), points);
        let mut binary =
            b"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty uchar k\n\
            property double x\nproperty float y\nproperty float z\nend_header\n"
                .to_vec();
        binary.push(7);
        binary.extend(1.5f64.to_le_bytes());
        binary.extend(2.0f32.to_le_bytes());
        binary.extend((-3.0f32).to_le_bytes());
        let path = dir.path().join("b.ply");
        std::fs::write(&path, binary).expect("written");
        assert_eq!(read_points(&path, 0).expect("read"), vec![Point3::new(1.5, 2.0, -3.0)]);
    }

    #[test]
    fn obj_meshes_are_sampled_on_their_surface() {
        let dir = tempfile::tempdir().expect("a temp dir");
        let path = dir.path().join("square.obj");
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").expect("written");
        let points = read_points(&path, 100).expect("read");
        assert_eq!(points.len(), 100);
        assert!(points
            .iter()
            .all(|p| p.z == 0.0 && (0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y)));
    }

    #[test]
    fn bad_files_are_errors_naming_the_problem() {
        let dir = tempfile::tempdir().expect("a temp dir");
        let cases = [
            (
                "a.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n",
                "no vertex property y",
            ),
            ("b.obj", "v 1 2\n", "not valid OBJ"),
            ("c.obj", "v 0 0 0\nf 1 2 3\n", "index out of bounds"),
            ("d.obj", "v nan 0 0\n", "not finite"),
            ("d2.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", "vertex 3 is not finite"),
            ("e.obj", "# nothing\n", "no points"),
            ("f.xyz", "", "expected a .ply or .obj"),
        ];
        for (name, text, expected) in cases {
            let path = dir.path().join(name);
            std::fs::write(&path, text).expect("written");
            let err = read_points(&path, 10).expect_err(name).to_string();
            assert!(err.contains(expected), "{name}: {err}");
        }
    }
}
