//! Reading a user's point cloud or mesh and writing coloured point clouds, for `model infer`
//! and `model animate`: PLY (ASCII or binary little-endian; the vertex element's `x y z`,
//! any other properties skipped) and Wavefront OBJ (`v` lines; with `f` lines the surface is
//! sampled, area-weighted, from a fixed seed). Clouds larger than the network's input are
//! reduced by farthest-point sampling.

use std::path::{Path, PathBuf};

use pairs::math::{Point3, Real};
use rand::{Rng, SeedableRng};

/// Why a point file could not be read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PointFileError {
    /// The file could not be opened, read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The file is not a PLY or OBJ file this reader understands.
    #[error("{path}: {message}")]
    Malformed {
        /// The file.
        path: PathBuf,
        /// What is wrong (line or field named).
        message: String,
    },
}

fn malformed(path: &Path, message: impl Into<String>) -> PointFileError {
    PointFileError::Malformed { path: path.to_path_buf(), message: message.into() }
}

/// The points of a `.ply` or `.obj` file (by extension); meshes in OBJ files are sampled
/// to `samples` surface points. Every coordinate must be finite and the cloud non-empty.
pub fn read_points(path: &Path, samples: usize) -> Result<Vec<Point3>, PointFileError> {
    let bytes = std::fs::read(path)
        .map_err(|source| PointFileError::Io { path: path.to_path_buf(), source })?;
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

fn read_obj(path: &Path, bytes: &[u8], samples: usize) -> Result<Vec<Point3>, PointFileError> {
    let text = String::from_utf8_lossy(bytes);
    let (mut vertices, mut faces) = (Vec::new(), Vec::new());
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let v: Vec<Real> = words.take(3).filter_map(|w| w.parse().ok()).collect();
                if v.len() != 3 {
                    return Err(malformed(path, format!("line {}: a vertex needs x y z", n + 1)));
                }
                vertices.push(Point3::new(v[0], v[1], v[2]));
            }
            Some("f") => {
                let ids: Vec<usize> = words
                    .map(|w| {
                        let first = w.split('/').next().unwrap_or_default();
                        let i: i64 = first.parse().map_err(|_| {
                            malformed(path, format!("line {}: face index {w}", n + 1))
                        })?;
                        let k = if i < 0 { vertices.len() as i64 + i } else { i - 1 };
                        usize::try_from(k).ok().filter(|&k| k < vertices.len()).ok_or_else(|| {
                            malformed(path, format!("line {}: face index {w} out of range", n + 1))
                        })
                    })
                    .collect::<Result<_, _>>()?;
                // A polygon as a fan of triangles.
                for k in 1..ids.len().saturating_sub(1) {
                    faces.push([ids[0], ids[k], ids[k + 1]]);
                }
            }
            _ => {}
        }
    }
    if faces.is_empty() {
        return Ok(vertices);
    }
    Ok(sample_surface(&vertices, &faces, samples, 0))
}

/// `n` points sampled uniformly on the triangles' surface (area-weighted) from `seed`.
pub fn sample_surface(
    vertices: &[Point3],
    faces: &[[usize; 3]],
    n: usize,
    seed: u64,
) -> Vec<Point3> {
    let mut cumulative = Vec::with_capacity(faces.len());
    let mut total = 0.0f64;
    for f in faces {
        let (a, b, c) = (vertices[f[0]], vertices[f[1]], vertices[f[2]]);
        total += f64::from((b - a).cross(&(c - a)).norm() / 2.0);
        cumulative.push(total);
    }
    if total <= 0.0 {
        return faces.iter().take(n).map(|f| vertices[f[0]]).collect();
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let pick = rng.random::<f64>() * total;
            let f = faces[cumulative.partition_point(|&c| c < pick).min(faces.len() - 1)];
            let (mut u, mut v): (Real, Real) = (rng.random(), rng.random());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            let (a, b, c) = (vertices[f[0]], vertices[f[1]], vertices[f[2]]);
            a + (b - a) * u + (c - a) * v
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
    std::fs::write(path, text)
        .map_err(|source| PointFileError::Io { path: path.to_path_buf(), source })
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
            ("b.obj", "v 1 2\n", "line 1"),
            ("c.obj", "v 0 0 0\nf 1 2 3\n", "out of range"),
            ("d.obj", "v nan 0 0\n", "not finite"),
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
