//! `generator render`: the appearance never encodes the part, renders repeat exactly, and
//! each method's layout reads back the way its loader reads it (PARIS
//! `datasets/blender_paris.py` and `models/ray_utils.py`; DigitalTwinArt `main.py:58-91`
//! and `nerf_utils.py:20`; ArtGS `scene/dataset_readers.py:116-199`), reproduced here from
//! their documented conventions: every object pixel's ray meets the ground-truth mesh at
//! the stored depth, and the ground-truth joint carries the start meshes onto the end ones.

use std::path::Path;

use articulated::mesh::Mesh;
use articulated::objects::{ArticulatedObject, Joint, Link};
use assets::{Source, SourcedObject};
use generator::config::GeneratorConfig;
use generator::objects::built_in_objects;
use nalgebra::{Isometry3, Matrix3, Matrix4, Point3, Vector3};
use pairs::math::Real;
use pairs::Intrinsics;
use parry3d::query::{PointQuery, Ray, RayCast};
use parry3d::shape::TriMesh;
use renderer::appearance::{Appearance, Lighting, Material};
use renderer::layout::gt::entry_motion;
use renderer::layout::{write_render, Layout};
use renderer::scene::RenderScene;
use renderer::shade::{shade, Shading};
use renderer::{RenderConfig, RenderJob};
use scanner::camera::Camera;
use serde_json::Value;

fn small_config() -> RenderConfig {
    RenderConfig { width: 96, height: 72, views: 4, ..RenderConfig::default() }
}

fn render(layout: Layout, objects: u32, dir: &Path) -> Vec<String> {
    let config = GeneratorConfig { objects, ..GeneratorConfig::default() };
    let render = RenderConfig { states: 2, ..small_config() };
    let jobs = built_in_objects(&config)
        .expect("objects")
        .into_iter()
        .map(|o| RenderJob::new(&render, 0, o, None, layout));
    write_render(&render, 0, jobs, layout, dir, false, &|_| {}).expect("render").objects
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("read")).expect("json")
}

fn matrix4(v: &Value) -> Matrix4<Real> {
    Matrix4::from_fn(|r, c| v[r][c].as_f64().expect("number") as Real)
}

/// Vertices and triangles of an ASCII PLY as we write it.
fn read_ply(path: &Path) -> TriMesh {
    let text = std::fs::read_to_string(path).expect("ply");
    let (header, body) = text.split_once("end_header\n").expect("header");
    let count = |what: &str| -> usize {
        header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("element {what} ")))
            .expect("element")
            .parse()
            .expect("count")
    };
    let mut lines = body.lines();
    let vertices: Vec<Point3<Real>> = (0..count("vertex"))
        .map(|_| {
            let v: Vec<Real> =
                lines.next().expect("vertex").split(' ').map(|x| x.parse().expect("f")).collect();
            Point3::new(v[0], v[1], v[2])
        })
        .collect();
    let triangles: Vec<[u32; 3]> = (0..count("face"))
        .map(|_| {
            let f: Vec<u32> =
                lines.next().expect("face").split(' ').map(|x| x.parse().expect("i")).collect();
            assert_eq!(f[0], 3);
            [f[1], f[2], f[3]]
        })
        .collect();
    TriMesh::new(vertices, triangles).expect("mesh")
}

fn rgba(path: &Path) -> image::RgbaImage {
    image::open(path).expect("png").into_rgba8()
}

/// Object pixels whose ray (origin, direction) meets `mesh`, of those with alpha > 0; and
/// background pixels whose ray misses it, of the others.
fn agreement(
    mesh: &TriMesh,
    image: &image::RgbaImage,
    ray: impl Fn(u32, u32) -> (Point3<Real>, Vector3<Real>),
) -> f64 {
    let mut agree = 0usize;
    for (i, j, p) in image.enumerate_pixels() {
        let (o, d) = ray(i, j);
        let hit = mesh.intersects_local_ray(&Ray::new(o, d), 100.0);
        agree += usize::from(hit == (p[3] > 0));
    }
    agree as f64 / (image.width() * image.height()) as f64
}

#[test]
fn rgb_never_depends_on_the_part_label() {
    // One object with two boxes in one link, and the same boxes as two links of two parts:
    // the same material and light give the same colours; only the label image differs.
    let boxes = |x: Real| Mesh::cuboid(Point3::new(x, 0.0, 0.0), Point3::new(x + 0.4, 0.3, 0.5));
    let mut together = boxes(0.0);
    let other = boxes(0.6);
    let offset = together.vertices.len() as u32;
    together.vertices.extend(other.vertices.iter().copied());
    together.triangles.extend(other.triangles.iter().map(|t| t.map(|i| i + offset)));
    together.pieces.push(offset);
    let one = ArticulatedObject::new("t", Link { name: "a".into(), mesh: together });
    let mut two = ArticulatedObject::new("t", Link { name: "a".into(), mesh: boxes(0.0) });
    two.attach(
        0,
        Link { name: "b".into(), mesh: boxes(0.6) },
        Joint::hinge(Point3::origin(), Vector3::y(), 1.0),
    );
    let k = Intrinsics::with_fov(120, 90, 0.9);
    let camera = Camera::look_at(k, &Point3::new(0.5, 1.2, 2.0), &Point3::new(0.5, 0.15, 0.25));
    let lighting = Lighting::default();
    for material in [
        Material::uniform([0.6, 0.5, 0.4]),
        Material { frequency: 7.0, ..Material::uniform([0.6, 0.5, 0.4]) },
        {
            use rand::SeedableRng;
            Material::draw(&mut articulated::seed::Rng::seed_from_u64(9), 1.0)
        },
    ] {
        let image = |object: &ArticulatedObject, parts: &[u8]| {
            let scene = RenderScene::new(object, &vec![Isometry3::identity(); object.links.len()])
                .expect("scene");
            let appearance = Appearance::single(material.clone(), object.links.len());
            let shading = Shading {
                appearance: &appearance,
                lighting: &lighting,
                part_of_link: parts,
                background: [1.0; 3],
            };
            shade(&scene, &camera, &shading)
        };
        let a = image(&one, &[0]);
        let b = image(&two, &[0, 1]);
        assert!(a.hits() > 300, "{} pixels see the boxes", a.hits());
        assert_eq!(a.rgb, b.rgb, "the colour does not see the part");
        assert_eq!(a.depth, b.depth);
        assert_ne!(a.part, b.part, "the labels do");
    }
    // Under a uniform material, two faces of two parts facing the same way have one colour.
    let scene = RenderScene::new(&two, &[Isometry3::identity(); 2]).expect("scene");
    let appearance = Appearance::single(Material::uniform([0.6, 0.5, 0.4]), 2);
    let shading = Shading {
        appearance: &appearance,
        lighting: &lighting,
        part_of_link: &[0, 1],
        background: [1.0; 3],
    };
    let view = shade(&scene, &camera, &shading);
    let top = |part: u8| -> Vec<[Real; 3]> {
        (0..view.rgb.len())
            .filter(|&i| view.part[i] == Some(part) && view.normal[i].y > 0.999)
            .map(|i| view.rgb[i])
            .collect()
    };
    let (t0, t1) = (top(0), top(1));
    assert!(t0.len() > 50 && t1.len() > 50);
    assert!(t0
        .iter()
        .chain(&t1)
        .all(|c| (c[0] - t0[0][0]).abs() < 1e-6 && (c[2] - t0[0][2]).abs() < 1e-6));
}

#[test]
fn renders_repeat_byte_for_byte_whatever_the_threads() {
    let a = tempfile::tempdir().expect("tmp");
    let b = tempfile::tempdir().expect("tmp");
    render(Layout::Native, 2, &a.path().join("r"));
    rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool").install(|| {
        render(Layout::Native, 2, &b.path().join("r"));
    });
    let files = |root: &Path| {
        let mut out = Vec::new();
        let mut stack = vec![root.to_path_buf()];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).expect("dir") {
                let p = e.expect("entry").path();
                if p.is_dir() {
                    stack.push(p)
                } else {
                    out.push((
                        p.strip_prefix(root).expect("under").to_path_buf(),
                        std::fs::read(&p).expect("read"),
                    ))
                }
            }
        }
        out.sort();
        out
    };
    let (fa, fb) = (files(&a.path().join("r")), files(&b.path().join("r")));
    assert_eq!(
        fa.len(),
        2 * (2 + 2 * 4 * 4) + 2,
        "per object 2 JSON and 32 images; render.json, ground_truth.json"
    );
    assert!(fa == fb, "same files, same bytes");
}

#[test]
fn native_depth_and_labels_match_the_cameras() {
    let dir = tempfile::tempdir().expect("tmp");
    let root = dir.path().join("r");
    let objects = render(Layout::Native, 1, &root);
    let obj = root.join(&objects[0]);
    let record = json(&obj.join("object.json"));
    let scale = record["depth_scale"].as_f64().expect("scale") as Real;
    let cameras = renderer::cameras::read(&obj.join("cameras.json")).expect("cameras");
    assert_eq!(cameras.len(), 4);
    let labels = image::open(obj.join("state_0/label/0002.png")).expect("png").into_luma8();
    let depth = image::open(obj.join("state_0/depth/0002.png")).expect("png").into_luma16();
    let mut parts = std::collections::BTreeSet::new();
    for (u, v, l) in labels.enumerate_pixels() {
        let z = depth.get_pixel(u, v)[0];
        assert_eq!(l[0] > 0, z > 0, "label and depth agree on the background at {u},{v}");
        parts.insert(l[0]);
        if z > 0 {
            let p = cameras[2].intrinsics.back_project(u as Real, v as Real, Real::from(z) * scale);
            assert!(p.z > 0.0);
        }
    }
    assert_eq!(parts.len(), 1 + record["parts"].as_u64().expect("parts") as usize);
}

#[test]
fn paris_layout_reads_back_like_its_loader() {
    let dir = tempfile::tempdir().expect("tmp");
    let root = dir.path().join("r");
    let objects = render(Layout::Paris, 3, &root);
    for source in &objects {
        let load = root.join("load").join(source);
        let data = root.join("data").join(source).join("textured_objs");
        let trans = json(&data.join("trans.json"));
        assert!(
            entry_motion(&trans["trans_info"]).is_some(),
            "{source}: one joint, rotate or translate"
        );
        let mesh = read_ply(&data.join("start/start_rotate.ply"));
        let aabb = mesh.local_aabb();
        assert!(
            aabb.mins.iter().chain(aabb.maxs.iter()).all(|x| x.abs() <= 1.0 + 1e-4),
            "inside [-1.3, 1.3]^3"
        );
        for split in ["train", "val", "test"] {
            let cameras = json(&load.join(format!("start/camera_{split}.json")));
            assert_eq!(cameras, json(&load.join(format!("end/camera_{split}.json"))));
            let map = cameras.as_object().expect("object");
            let focal = map["K"][0][0].as_f64().expect("K") as Real;
            let keys: Vec<&String> = map.keys().filter(|k| *k != "K").collect();
            assert!(keys.iter().all(|k| k.len() == 4 && k.parse::<u32>().is_ok()));
            for key in keys {
                let image = rgba(&load.join(format!("start/{split}/{key}.png")));
                let c2w = matrix4(&map[key.as_str()]);
                let (w, h) = (image.width() as Real, image.height() as Real);
                let origin = Point3::from(c2w.fixed_view::<3, 1>(0, 3).into_owned());
                assert!(origin.coords.amax() > 1.5, "the camera stands outside the scene box");
                let rotation: Matrix3<Real> = c2w.fixed_view::<3, 3>(0, 0).into_owned();
                // models/ray_utils.py: pixel centres, OpenGL axes, c2w rotation, normalised.
                let score = agreement(&mesh, &image, |i, j| {
                    let d = Vector3::new(
                        (i as Real + 0.5 - w / 2.0) / focal,
                        -(j as Real + 0.5 - h / 2.0) / focal,
                        -1.0,
                    );
                    (origin, pairs::math::unit_or(&(rotation * d), Vector3::z()))
                });
                assert!(score > 0.995, "{source} {split}/{key}: alpha and rays agree on {score}");
            }
        }
    }
}

/// Back-projects a depth image the way DigitalTwinArt and ArtGS do (pixel grid, OpenGL
/// camera, c2w) and returns the largest distance of an object point from `mesh`.
fn worst_depth_error(
    mesh: &TriMesh,
    depth: &image::ImageBuffer<image::Luma<u16>, Vec<u16>>,
    c2w: &Matrix4<Real>,
    k: [Real; 4],
    per_unit: Real,
) -> (Real, usize) {
    let [fx, fy, cx, cy] = k;
    let mut worst: Real = 0.0;
    let mut n = 0;
    for (u, v, d) in depth.enumerate_pixels() {
        if d[0] == 0 {
            continue;
        }
        let z = Real::from(d[0]) / per_unit;
        let p =
            nalgebra::Vector4::new((u as Real - cx) / fx * z, -(v as Real - cy) / fy * z, -z, 1.0);
        let world = c2w * p;
        let distance = mesh.distance_to_local_point(&Point3::new(world.x, world.y, world.z), true);
        worst = worst.max(distance);
        n += 1;
    }
    (worst, n)
}

#[test]
fn dta_layout_reads_back_like_its_loader() {
    let dir = tempfile::tempdir().expect("tmp");
    let root = dir.path().join("r");
    // Six objects: the desk lamp (object 5) has parts on moving parts.
    for name in render(Layout::Dta, 6, &root) {
        let obj = root.join(&name);
        let k: Vec<Real> = std::fs::read_to_string(obj.join("cam_K.txt"))
            .expect("K")
            .split_whitespace()
            .map(|x| x.parse().expect("f"))
            .collect();
        assert_eq!(k.len(), 9);
        let yml = std::fs::read_to_string(obj.join("init_keyframes.yml")).expect("yml");
        let mut frames = Vec::new();
        let mut lines = yml.lines();
        while let Some(key) = lines.next() {
            let stem = key.strip_prefix("frame_").and_then(|k| k.strip_suffix(':')).expect("key");
            let numbers = lines
                .next()
                .expect("pose")
                .trim()
                .strip_prefix("cam_in_ob: [")
                .and_then(|l| l.strip_suffix(']'))
                .expect("list");
            assert!(
                numbers.split(", ").all(|x| x.contains('.')),
                "every number has a decimal point"
            );
            let m: Vec<Real> = numbers.split(", ").map(|x| x.parse().expect("f")).collect();
            let time: usize = lines
                .next()
                .expect("time")
                .trim()
                .strip_prefix("time: ")
                .expect("time")
                .parse()
                .expect("int");
            assert_eq!(stem.split('_').next().expect("T").parse::<usize>().expect("T"), time);
            frames.push((stem.to_string(), Matrix4::from_row_slice(&m), time));
        }
        assert_eq!(frames.len(), 8);
        let meshes = [
            read_ply(&obj.join("gt/start/start_rotate.ply")),
            read_ply(&obj.join("gt/end/end_rotate.ply")),
        ];
        for (stem, c2w, time) in &frames {
            let depth = image::open(obj.join(format!("depth_filtered/{stem}.png")))
                .expect("png")
                .into_luma16();
            // nerf_utils.py:28 assumes K[1, 2] * 2 == H (and the same of x).
            assert_eq!((k[2] * 2.0, k[5] * 2.0), (depth.width() as Real, depth.height() as Real));
            let mask = image::open(obj.join(format!("mask/{stem}.png"))).expect("png").into_luma8();
            assert!(depth.pixels().zip(mask.pixels()).all(|(d, m)| (d[0] > 0) == (m[0] == 255)));
            // main.py:84 reads millimetres; nerf_utils.py:20 casts (u - cx)/fx, -(v - cy)/fy, -1.
            let (worst, n) =
                worst_depth_error(&meshes[*time], &depth, c2w, [k[0], k[4], k[2], k[5]], 1000.0);
            assert!(n > 100 && worst < 2e-3, "{name} {stem}: {n} points, {worst} m off the mesh");
        }
        check_gt(&obj.join("gt"), &truth_of(&root, &name));
    }
}

/// The record of the object in `folder` in the render's `ground_truth.json`.
fn truth_of(root: &Path, folder: &str) -> Value {
    let truth = json(&root.join("ground_truth.json"));
    let objects = truth["objects"].as_array().expect("objects");
    objects.iter().find(|o| o["folder"] == folder).expect("the object's truth").clone()
}

/// The joints of `gt/trans.json` carry each start dynamic mesh onto the end one, and
/// `ground_truth.json` (`truth`, the object's record) holds the same joints.
fn check_gt(gt: &Path, truth: &Value) {
    let trans = json(&gt.join("trans.json"));
    let entries: Vec<Value> = match &trans["trans_info"] {
        Value::Array(a) => a.clone(),
        one => vec![one.clone()],
    };
    let joints = truth["joints"].as_array().expect("joints");
    assert_eq!(joints.len(), entries.len());
    for (entry, joint) in entries.iter().zip(joints) {
        let j: pairs::renders::RenderJoint =
            serde_json::from_value(serde_json::json!({"type": joint["type"], "axis": joint["axis"], "pivot": joint["pivot"], "state": joint["state"]})).expect("joint");
        let kind = if j.kind == pairs::JointKind::Revolute { "rotate" } else { "translate" };
        let change = if kind == "rotate" { j.state.to_degrees() } else { j.state };
        let same = serde_json::json!({"type": kind, "axis": {"o": j.pivot, "d": j.axis}, kind: {"l": 0.0, "r": change}});
        let (a, b) = (entry_motion(entry).expect("motion"), entry_motion(&same).expect("motion"));
        assert!((a.to_homogeneous() - b.to_homogeneous()).abs().max() < 1e-4, "{entry} vs {joint}");
    }
    for (i, entry) in entries.iter().enumerate() {
        let file = |state: &str| match entries.len() {
            1 => gt.join(format!("{state}/{state}_dynamic_rotate.ply")),
            _ => gt.join(format!("{state}/{state}_dynamic_{i}_rotate.ply")),
        };
        let (start, end) = (read_ply(&file("start")), read_ply(&file("end")));
        let motion = entry_motion(entry).expect("motion");
        for (a, b) in start.vertices().iter().zip(end.vertices()) {
            assert!(
                (motion * a - b).norm() < 1e-3,
                "{}: joint {i} maps start onto end",
                gt.display()
            );
        }
    }
}

#[test]
fn artgs_layout_reads_back_like_its_loader() {
    let dir = tempfile::tempdir().expect("tmp");
    let root = dir.path().join("r");
    let objects = render(Layout::Artgs, 3, &root);
    let slots = json(&root.join("arguments/num_slots.json"));
    for folder in objects {
        let obj = root.join(&folder);
        let name = folder.rsplit('/').next().expect("name");
        assert!(slots["part_induction"]["render"][name].as_u64().expect("slots") >= 2);
        assert!(obj.join("transforms_train.json").exists());
        let meshes = [
            read_ply(&obj.join("gt/start/start_rotate.ply")),
            read_ply(&obj.join("gt/end/end_rotate.ply")),
        ];
        for state in ["start", "end"] {
            let t = json(&obj.join(format!("transforms_train_{state}.json")));
            let ax = t["camera_angle_x"].as_f64().expect("x") as Real;
            let ay = t["camera_angle_y"].as_f64().expect("y") as Real;
            for frame in t["frames"].as_array().expect("frames") {
                let path = frame["file_path"].as_str().expect("path");
                let time = frame["time"].as_f64().expect("time") as usize;
                assert_eq!(path.starts_with("start/"), time == 0);
                let image = rgba(&obj.join(path));
                let depth = image::open(obj.join(path.replace("rgba", "depth")))
                    .expect("png")
                    .into_luma16();
                assert!(image.pixels().zip(depth.pixels()).all(|(c, d)| (c[3] > 0) == (d[0] > 0)));
                let (w, h) = (image.width() as Real, image.height() as Real);
                let (fx, fy) = (w / (2.0 * (ax / 2.0).tan()), h / (2.0 * (ay / 2.0).tan()));
                // Field of view only: the principal point at the centre, pixel centres at +1/2.
                let c2w = matrix4(&frame["transform_matrix"]);
                let (worst, n) = worst_depth_error(
                    &meshes[time],
                    &depth,
                    &c2w,
                    [fx, fy, w / 2.0 - 0.5, h / 2.0 - 0.5],
                    1000.0,
                );
                assert!(
                    n > 100 && worst < 3e-3,
                    "{folder} {path}: {n} points, {worst} off the mesh"
                );
            }
        }
        check_gt(&obj.join("gt"), &truth_of(&root, &folder));
    }
}

#[test]
fn a_camera_file_is_used_as_given_and_bad_settings_are_refused() {
    let config = small_config();
    assert!(RenderConfig { states: 1, ..small_config() }.validate().is_err());
    assert!(RenderConfig { width: 0, ..small_config() }.validate().is_err());
    let object = built_in_objects(&GeneratorConfig { objects: 1, ..GeneratorConfig::default() })
        .expect("objects")
        .remove(0);
    let k = Intrinsics::with_fov(50, 40, 0.7);
    let cameras = vec![Camera::look_at(k, &Point3::new(0.0, 0.5, 3.0), &Point3::origin())];
    let job =
        RenderJob::new(&config, 0, object.clone(), Some(&cameras), Layout::Native).expect("job");
    assert_eq!(job.cameras, cameras);
    assert_eq!(job.view(&config, 1, 0).width, 50);
    let built = SourcedObject {
        object_id: 7,
        object: object.object,
        source: Source::BuiltIn { split: "test".into() },
        surfaces: Vec::new(),
    };
    let job = RenderJob::new(&config, 0, built, None, Layout::Paris).expect("job");
    assert_eq!(job.parts, 2, "PARIS renders move one part");
}

/// A 2 x 2 checker texture `checker.png` in `root` whose top-left texel is blue.
fn write_checker(root: &Path) {
    let mut texture = image::RgbImage::new(2, 2);
    for (x, y, p) in texture.enumerate_pixels_mut() {
        *p = if (x + y) % 2 == 0 { image::Rgb([20, 30, 230]) } else { image::Rgb([20, 230, 30]) };
    }
    texture.save(root.join("checker.png")).expect("png");
}

/// Loads the asset `file` in `root` (a `body` and a `lid` hinged to it, given a sidecar
/// here) and checks that it renders with its own materials: the body red, the lid the
/// texture's blue texel, under six views.
fn assert_red_body_and_blue_lid(root: &Path, file: &str) {
    let joints = r#"{"category": "box", "joints": [{"name": "hinge", "type": "revolute", "parent": "body", "child": "lid", "origin": [0.0, 0.4, -0.3], "axis": [1.0, 0.0, 0.0], "lower": 0.0, "upper": 1.2}]}"#;
    std::fs::write(root.join("box.joints.json"), joints).expect("sidecar");
    let imported =
        assets::load_asset(&root.join(file), &assets::ImportOptions::default()).expect("asset");
    assert!(imported.surfaces.iter().all(|s| s.is_styled()));
    let object = SourcedObject {
        object_id: 0,
        object: imported.object,
        source: Source::Asset { path: file.into() },
        surfaces: imported.surfaces,
    };
    let config = RenderConfig {
        width: 120,
        height: 90,
        views: 6,
        placement: renderer::cameras::Placement::Hemisphere,
        ..RenderConfig::default()
    };
    let job = RenderJob::new(&config, 0, object, None, Layout::Native).expect("job");
    assert_eq!(
        job.appearance.asset_materials,
        vec![vec!["red".to_string()], vec!["checker".to_string()]]
    );
    let (mut body, mut lid) = (0, 0);
    for view in 0..6 {
        let images = job.view(&config, 0, view);
        for (rgb, part) in images.rgb.iter().zip(&images.part) {
            match part {
                Some(0) => {
                    assert!(
                        rgb[0] > 3.0 * rgb[1] && rgb[0] > 3.0 * rgb[2],
                        "the body is red: {rgb:?}"
                    );
                    body += 1;
                }
                Some(_) => {
                    assert!(
                        rgb[2] > 3.0 * rgb[0] && rgb[2] > 3.0 * rgb[1],
                        "the lid is the blue texel: {rgb:?}"
                    );
                    lid += 1;
                }
                None => {}
            }
        }
    }
    assert!(body > 500 && lid > 200, "{file}: {body} body and {lid} lid pixels");
}

/// An OBJ box from `lo` to `hi` (group `name`, material `material`, every corner at
/// texture coordinates `uv`), its vertices numbered from `first`.
fn obj_box(
    name: &str,
    material: &str,
    lo: [f32; 3],
    hi: [f32; 3],
    first: usize,
    uv: [f32; 2],
) -> String {
    let mut s = format!("g {name}\nusemtl {material}\nvt {} {}\n", uv[0], uv[1]);
    for i in 0..8 {
        let p = [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ];
        s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    // Faces counter-clockwise from outside: -x, +x, -y, +y, -z, +z.
    let quads =
        [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];
    let t = first / 8 + 1;
    for q in quads {
        let v: Vec<usize> = q.iter().map(|i| first + i + 1).collect();
        s += &format!(
            "f {}/{t} {}/{t} {}/{t}\nf {}/{t} {}/{t} {}/{t}\n",
            v[0], v[1], v[2], v[0], v[2], v[3]
        );
    }
    s
}

#[test]
fn an_asset_renders_with_its_own_materials_and_textures() {
    let dir = tempfile::tempdir().expect("tmp");
    let root = dir.path();
    // A red body (MTL Kd) and a lid textured by a 2 x 2 image whose top-left texel is blue.
    write_checker(root);
    std::fs::write(
        root.join("box.mtl"),
        "newmtl red\nKd 0.9 0.1 0.1\nnewmtl checker\nKd 1 1 1\nmap_Kd checker.png\n",
    )
    .expect("mtl");
    let obj = format!(
        "mtllib box.mtl\n{}{}",
        obj_box("body", "red", [-0.5, 0.0, -0.3], [0.5, 0.4, 0.3], 0, [0.0, 0.0]),
        obj_box("lid", "checker", [-0.5, 0.4, -0.3], [0.5, 0.45, 0.3], 8, [0.25, 0.75])
    );
    std::fs::write(root.join("box.obj"), obj).expect("obj");
    assert_red_body_and_blue_lid(root, "box.obj");
}

#[test]
fn back_projected_clouds_lie_on_the_states_and_move_with_their_parts() {
    let dir = tempfile::tempdir().expect("tmp");
    let root = dir.path().join("r");
    render(Layout::Native, 2, &root);
    let pairs = renderer::backproject::render_pairs(&root, 256).expect("pairs");
    assert_eq!(pairs.len(), 2);
    let config = GeneratorConfig { objects: 2, ..GeneratorConfig::default() };
    let render_config = RenderConfig { states: 2, ..small_config() };
    for (object, pair) in built_in_objects(&config).expect("objects").into_iter().zip(&pairs) {
        let job = RenderJob::new(&render_config, 0, object, None, Layout::Native).expect("job");
        let mesh = |s: usize| {
            let (v, t) = renderer::job::posed_mesh(&job, s, None);
            TriMesh::new(v, t).expect("mesh")
        };
        let (m0, m1) = (mesh(0), mesh(1));
        assert_eq!((pair.p.len(), pair.q.len()), (256, 256));
        let tolerance = 2e-3 * job.scenes[0].diagonal();
        for (x, &k) in pair.p.iter().zip(&pair.part_p) {
            assert!(
                m0.distance_to_local_point(x, true) < tolerance,
                "{}: P on state 0",
                pair.folder
            );
            let moved = pair.motions[usize::from(k)] * x;
            assert!(
                m1.distance_to_local_point(&moved, true) < tolerance,
                "{}: part {k} moves onto state 1",
                pair.folder
            );
        }
        for y in &pair.q {
            assert!(
                m1.distance_to_local_point(y, true) < tolerance,
                "{}: Q on state 1",
                pair.folder
            );
        }
        let parts: std::collections::BTreeSet<_> = pair.part_p.iter().collect();
        assert_eq!(parts.len(), job.parts, "every part is seen");
    }
}

/// A glTF box's positions (8 corners) and triangles (12, counter-clockwise from outside).
fn gltf_box(lo: [f32; 3], hi: [f32; 3]) -> (Vec<[f32; 3]>, Vec<u32>) {
    let corners = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { lo[0] } else { hi[0] },
                if i & 2 == 0 { lo[1] } else { hi[1] },
                if i & 4 == 0 { lo[2] } else { hi[2] },
            ]
        })
        .collect();
    let quads =
        [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];
    let triangles = quads.iter().flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]]).collect();
    (corners, triangles)
}

#[test]
fn a_gltf_asset_renders_with_its_base_colours_and_textures() {
    use base64::Engine as _;
    let dir = tempfile::tempdir().expect("tmp");
    let root = dir.path();
    write_checker(root);
    // One buffer: per box 8 positions, 36 u32 indices, 8 texture coordinates.
    let mut buffer = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    for (lo, hi) in
        [([-0.5f32, 0.0, -0.3], [0.5f32, 0.4, 0.3]), ([-0.5, 0.4, -0.3], [0.5, 0.45, 0.3])]
    {
        let (positions, indices) = gltf_box(lo, hi);
        let mut add = |bytes: Vec<u8>, accessor: serde_json::Value| {
            views.push(serde_json::json!({"buffer": 0, "byteOffset": buffer.len(), "byteLength": bytes.len()}));
            buffer.extend(bytes);
            let mut a = accessor;
            a["bufferView"] = serde_json::json!(views.len() - 1);
            accessors.push(a);
        };
        add(
            positions.iter().flatten().flat_map(|f| f.to_le_bytes()).collect(),
            serde_json::json!({"componentType": 5126, "count": 8, "type": "VEC3", "min": lo, "max": hi}),
        );
        add(
            indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
            serde_json::json!({"componentType": 5125, "count": 36, "type": "SCALAR"}),
        );
        add(
            (0..8).flat_map(|_| [0.25f32, 0.25]).flat_map(|f| f.to_le_bytes()).collect(),
            serde_json::json!({"componentType": 5126, "count": 8, "type": "VEC2"}),
        );
    }
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&buffer)
    );
    let prim = |k: usize, material: usize| serde_json::json!({"primitives": [{"attributes": {"POSITION": 3 * k, "TEXCOORD_0": 3 * k + 2}, "indices": 3 * k + 1, "material": material}]});
    let gltf = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"name": "body", "mesh": 0}, {"name": "lid", "mesh": 1}],
        "meshes": [prim(0, 0), prim(1, 1)],
        "materials": [
            {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.1, 0.1, 1.0]}},
            {"name": "checker", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}
        ],
        "textures": [{"source": 0}],
        "images": [{"uri": "checker.png"}],
        "buffers": [{"byteLength": buffer.len(), "uri": uri}],
        "bufferViews": views,
        "accessors": accessors,
    });
    std::fs::write(root.join("box.gltf"), gltf.to_string()).expect("gltf");
    assert_red_body_and_blue_lid(root, "box.gltf");
}
