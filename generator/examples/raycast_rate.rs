//! Rays per second of the renderer's ray caster (`RenderScene`, obvhs) and the scanner's
//! (`PosedScene`, parry3d) on the meshes and cameras of a `generator render --layout dta`
//! folder: one ray per pixel of every camera, every state mesh, the whole image.
//! `generator/benches/open3d_raycast.py` runs Open3D's `RaycastingScene` on the same rays
//! and this beside it.
//!
//!     cargo run --release -p generator --example raycast_rate -- renders/dta

use std::path::Path;
use std::time::Instant;

use articulated::mesh::Mesh;
use articulated::objects::{ArticulatedObject, Link};
use pairs::math::{Isometry3, Matrix3, Point3, Real, Vector3};
use rayon::prelude::*;
use renderer::scene::RenderScene;
use scanner::scene::PosedScene;

fn main() -> anyhow::Result<()> {
    let root = std::env::args()
        .nth(1)
        .ok_or_else(|| anyhow::anyhow!("usage: raycast_rate <dta render folder>"))?;
    for caster in ["renderer", "scanner"] {
        rate(&root, caster)?;
    }
    Ok(())
}

/// Either scene, cast the same way.
enum Scene {
    Renderer(RenderScene),
    Scanner(PosedScene),
}

impl Scene {
    fn hits(&self, origin: &Point3, d: &Vector3) -> bool {
        match self {
            Scene::Renderer(s) => s.cast(origin, d, 1e3).is_some(),
            Scene::Scanner(s) => s.cast(origin, d, 1e3).is_some(),
        }
    }
}

fn rate(root: &str, caster: &str) -> anyhow::Result<()> {
    let mut rays = 0u64;
    let mut hits = 0u64;
    let mut seconds = 0.0;
    let mut folders: Vec<_> = std::fs::read_dir(root)?
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.join("cam_K.txt").exists())
        .collect();
    folders.sort();
    for dir in folders {
        let k: Vec<Real> = std::fs::read_to_string(dir.join("cam_K.txt"))?
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()?;
        let poses = read_poses(&dir.join("init_keyframes.yml"))?;
        let size = image::image_dimensions(dir.join("mask").join(format!("{}.png", poses[0].0)))?;
        for (state, name) in ["start", "end"].iter().enumerate() {
            let object = read_object(&dir.join(format!("gt/{name}/{name}_rotate.ply")))?;
            let scene = match caster {
                "renderer" => Scene::Renderer(RenderScene::new(&object, &[Isometry3::identity()])?),
                _ => Scene::Scanner(PosedScene::new(&object, &[Isometry3::identity()])?),
            };
            let cameras: Vec<&Isometry3> =
                poses.iter().filter(|p| p.1 == state).map(|p| &p.2).collect();
            // The rays are made before the clock starts, as the Open3D script's are.
            let rays_of: Vec<Vec<(Point3, Vector3)>> = cameras
                .iter()
                .map(|c2w| {
                    let origin = Point3::from(c2w.translation.vector);
                    (0..size.1)
                        .flat_map(|v| (0..size.0).map(move |u| (u, v)))
                        .map(|(u, v)| {
                            let d = Vector3::new(
                                (u as Real - k[2]) / k[0],
                                -(v as Real - k[5]) / k[4],
                                -1.0,
                            );
                            (origin, pairs::math::unit_or(&(c2w.rotation * d), Vector3::z()))
                        })
                        .collect()
                })
                .collect();
            let started = Instant::now();
            let found: u64 = rays_of
                .iter()
                .map(|rays| {
                    rays.par_chunks(size.0 as usize)
                        .map(|row| row.iter().filter(|(o, d)| scene.hits(o, d)).count() as u64)
                        .sum::<u64>()
                })
                .sum();
            seconds += started.elapsed().as_secs_f64();
            hits += found;
            rays += cameras.len() as u64 * u64::from(size.0) * u64::from(size.1);
        }
    }
    println!(
        "{caster:<9} rays {rays} hits {hits} seconds {seconds:.3} rays_per_second {:.0}",
        rays as f64 / seconds
    );
    Ok(())
}

/// `(stem, state, camera to object)` of each frame of `init_keyframes.yml` as we write it.
fn read_poses(path: &Path) -> anyhow::Result<Vec<(String, usize, Isometry3)>> {
    let text = std::fs::read_to_string(path)?;
    let lines: Vec<&str> = text.lines().collect();
    lines
        .chunks(3)
        .map(|c| {
            let stem = c[0].trim_start_matches("frame_").trim_end_matches(':').to_string();
            let m: Vec<Real> = c[1]
                .trim()
                .trim_start_matches("cam_in_ob: [")
                .trim_end_matches(']')
                .split(", ")
                .map(str::parse)
                .collect::<Result<_, _>>()?;
            let time: usize = c[2].trim().trim_start_matches("time: ").parse()?;
            let r = Matrix3::new(m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]);
            let rotation = nalgebra::UnitQuaternion::from_matrix(&r);
            Ok((
                stem,
                time,
                Isometry3::from_parts(Vector3::new(m[3], m[7], m[11]).into(), rotation),
            ))
        })
        .collect()
}

/// One link holding an ASCII PLY's triangles, at rest.
fn read_object(path: &Path) -> anyhow::Result<ArticulatedObject> {
    let text = std::fs::read_to_string(path)?;
    let (header, body) = text
        .split_once("end_header\n")
        .ok_or_else(|| anyhow::anyhow!("{}: no header", path.display()))?;
    let count = |what: &str| -> anyhow::Result<usize> {
        Ok(header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("element {what} ")))
            .ok_or_else(|| anyhow::anyhow!("no {what}"))?
            .parse()?)
    };
    let mut lines = body.lines();
    let mut mesh = Mesh::default();
    for _ in 0..count("vertex")? {
        let v: Vec<Real> = lines
            .next()
            .unwrap_or_default()
            .split(' ')
            .map(str::parse)
            .collect::<Result<_, _>>()?;
        mesh.vertices.push(Point3::new(v[0], v[1], v[2]));
    }
    for _ in 0..count("face")? {
        let f: Vec<u32> = lines
            .next()
            .unwrap_or_default()
            .split(' ')
            .map(str::parse)
            .collect::<Result<_, _>>()?;
        mesh.triangles.push([f[1], f[2], f[3]]);
    }
    mesh.pieces.push(0);
    Ok(ArticulatedObject::new("ply", Link { name: "mesh".into(), mesh }))
}
