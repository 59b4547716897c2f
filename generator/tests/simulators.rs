//! Simulator-ready object folders (`generator export-objects`, issue 38): every format
//! names the same collision hulls, which exist and keep to the budget; masses follow the
//! density and the meshes' volumes; a degenerate or open link falls back to its hull with
//! a note, never a crash or a missing link; the folder is the same byte for byte on a
//! second export. (The simulators themselves load the folders in
//! `python/tests/test_simulators.py`.)

use std::path::Path;

use articulated::mesh::Mesh;
use assets::{Source, SourcedObject};
use generator::config::GeneratorConfig;
use generator::generate::build_object;
use pairs::math::Point3;
use simulators::collision::{Budget, FLAT_THICKNESS};
use simulators::physics::PhysicsOptions;
use simulators::{write_object, ExportOptions, ExportedObject, ObjectFormat};

fn cabinet() -> (GeneratorConfig, SourcedObject) {
    let config =
        GeneratorConfig { categories: vec!["cabinet".into()], seed: 5, ..Default::default() };
    let object = build_object(&config, 0).expect("a cabinet");
    let item = SourcedObject {
        object_id: 0,
        object,
        source: Source::BuiltIn { split: "test".into() },
        surfaces: Vec::new(),
    };
    (config, item)
}

fn export(item: &SourcedObject, options: &ExportOptions) -> (tempfile::TempDir, ExportedObject) {
    let (config, _) = cabinet();
    let dir = tempfile::tempdir().expect("temp dir");
    let written = write_object(&generator::objects::state_draw(&config), item, dir.path(), options)
        .expect("exported");
    (dir, written)
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn meta(folder: &Path) -> serde_json::Value {
    serde_json::from_str(&read(&folder.join("meta.json"))).expect("meta.json parses")
}

/// Every `attribute="…"` value in `text` that ends in `.obj`.
fn obj_references(text: &str, attribute: &str) -> Vec<String> {
    let key = format!("{attribute}=\"");
    text.match_indices(&key)
        .filter_map(|(i, _)| {
            let rest = &text[i + key.len()..];
            let value = &rest[..rest.find('"')?];
            value.ends_with(".obj").then(|| value.to_string())
        })
        .collect()
}

#[test]
fn every_format_names_the_same_hulls_which_exist_within_the_budget() {
    let (_, item) = cabinet();
    let budget = Budget { max_hulls: 4, max_vertices: 12 };
    let options = ExportOptions {
        physics: PhysicsOptions { budget, ..Default::default() },
        ..Default::default()
    };
    let (dir, written) = export(&item, &options);
    let folder = dir.path().join(&written.folder);
    let urdf: Vec<String> = obj_references(&read(&folder.join("mobility.urdf")), "filename")
        .into_iter()
        .filter(|f| f.starts_with("collision/"))
        .collect();
    let mjcf: Vec<String> = obj_references(&read(&folder.join("mobility.xml")), "file")
        .into_iter()
        .filter(|f| f.starts_with("collision/"))
        .collect();
    assert_eq!(urdf, mjcf, "URDF and MJCF name the same hulls, in the same order");
    let usd_hulls = read(&folder.join("mobility.usda")).matches("def Mesh \"hull_").count();
    assert_eq!(usd_hulls, urdf.len());
    assert_eq!(written.collision.hulls, urdf.len());
    let on_disk = std::fs::read_dir(folder.join("collision")).expect("collision/").count();
    assert_eq!(on_disk, urdf.len());
    let meta = meta(&folder);
    for (i, link) in item.object.links.iter().enumerate() {
        let prefix = format!("collision/link_{i}_hull_");
        let hulls: Vec<&String> = urdf.iter().filter(|f| f.starts_with(&prefix)).collect();
        assert!(!hulls.is_empty() && hulls.len() <= budget.max_hulls, "{}", link.name);
        assert_eq!(meta["link_physics"][format!("link_{i}")]["hulls"], hulls.len());
        for hull in hulls {
            let text = read(&folder.join(hull));
            let vertices = text.lines().filter(|l| l.starts_with("v ")).count();
            assert!((4..=budget.max_vertices).contains(&vertices), "{hull}: {vertices}");
        }
    }
}

#[test]
fn masses_follow_the_density_and_the_closed_meshes_volume() {
    let (_, item) = cabinet();
    let light = ExportOptions::default();
    let heavy = ExportOptions {
        physics: PhysicsOptions { density: 3.0 * light.physics.density, ..Default::default() },
        ..Default::default()
    };
    let (a, written) = export(&item, &light);
    let (b, _) = export(&item, &heavy);
    let (ma, mb) = (meta(&a.path().join(&written.folder)), meta(&b.path().join(&written.folder)));
    for i in 0..item.object.links.len() {
        let link = format!("link_{i}");
        let (pa, pb) = (&ma["link_physics"][&link], &mb["link_physics"][&link]);
        assert_eq!(pa["mass_from"], "mesh", "built-in links are closed");
        let mass = pa["mass"].as_f64().expect("a mass");
        let volume = pa["fit"]["visual_volume"].as_f64().expect("a volume");
        assert!(volume > 0.0);
        assert!((mass / (light.physics.density * volume) - 1.0).abs() < 1e-3, "{link}: {pa}");
        let tripled = pb["mass"].as_f64().expect("a mass");
        assert!((tripled / mass - 3.0).abs() < 1e-4, "{link}");
    }
    // The inertial is the mesh's: about its centre of mass, not a unit box.
    let urdf = read(&a.path().join(&written.folder).join("mobility.urdf"));
    assert!(!urdf.contains(r#"<mass value="1"/>"#), "no link keeps the old unit mass");
}

#[test]
fn a_flat_or_open_link_falls_back_to_its_hull_with_a_note() {
    let (_, mut item) = cabinet();
    assert!(item.object.links.len() >= 3);
    // Link 1: a square without thickness (degenerate); link 2: a box missing a face (open).
    item.object.links[1].mesh = Mesh {
        vertices: vec![
            Point3::new(0.0, 0.5, 0.3),
            Point3::new(0.2, 0.5, 0.3),
            Point3::new(0.2, 0.7, 0.3),
            Point3::new(0.0, 0.7, 0.3),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        pieces: vec![0],
    };
    let mut open = Mesh::cuboid(Point3::new(-0.1, 0.1, 0.0), Point3::new(0.1, 0.3, 0.2));
    open.triangles.truncate(open.triangles.len() - 2);
    item.object.links[2].mesh = open;
    let (dir, written) = export(&item, &ExportOptions::default());
    let folder = dir.path().join(&written.folder);
    assert!(written.notes.iter().any(|n| n.starts_with("link_1: ") && n.contains("flat")));
    assert!(written.notes.iter().any(|n| n.starts_with("link_2: ") && n.contains("open")));
    let meta = meta(&folder);
    assert_eq!(meta["link_physics"]["link_1"]["hulls"], 1);
    assert_eq!(meta["link_physics"]["link_2"]["hulls"], 1);
    assert_eq!(meta["link_physics"]["link_2"]["mass_from"], "hulls");
    let flat = meta["link_physics"]["link_1"]["fit"]["hull_volume"].as_f64().expect("volume");
    assert!((flat - 0.04 * f64::from(FLAT_THICKNESS)).abs() < 1e-6, "{flat}");
    // No link goes missing from any format.
    let usd = read(&folder.join("mobility.usda"));
    for link in ["link_1", "link_2"] {
        for file in ["mobility.urdf", "mobility.xml"] {
            let hull = format!("collision/{link}_hull_0.obj");
            assert!(read(&folder.join(file)).contains(&hull), "{file}: {hull}");
        }
        assert!(usd.contains(&format!("def Xform \"{link}\"")), "{link}");
    }
    assert_eq!(usd.matches("def Mesh \"hull_").count(), written.collision.hulls);
    for link in ["link_1", "link_2"] {
        assert!(folder.join(format!("collision/{link}_hull_0.obj")).exists());
        let mass = meta["link_physics"][link]["mass"].as_f64().expect("a mass");
        assert!(mass > 0.0 && mass.is_finite(), "{link}: {mass}");
    }
}

#[test]
fn a_second_export_is_the_same_byte_for_byte_and_formats_can_be_left_out() {
    let (_, item) = cabinet();
    let (a, written) = export(&item, &ExportOptions::default());
    let (b, _) = export(&item, &ExportOptions::default());
    let (fa, fb) = (a.path().join(&written.folder), b.path().join(&written.folder));
    for file in ["mobility.urdf", "mobility.xml", "mobility.usda", "meta.json"] {
        assert_eq!(read(&fa.join(file)), read(&fb.join(file)), "{file}");
    }
    for entry in std::fs::read_dir(fa.join("collision")).expect("collision/") {
        let name = entry.expect("an entry").file_name();
        let (x, y) = (fa.join("collision").join(&name), fb.join("collision").join(&name));
        assert_eq!(read(&x), read(&y), "{name:?}");
    }
    let mjcf_only = ExportOptions { formats: vec![ObjectFormat::Mjcf], ..Default::default() };
    let (c, _) = export(&item, &mjcf_only);
    let fc = c.path().join(&written.folder);
    assert!(fc.join("mobility.xml").exists() && fc.join("collision").exists());
    assert!(!fc.join("mobility.urdf").exists() && !fc.join("mobility.usda").exists());
    assert_eq!(read(&fc.join("mobility.xml")), read(&fa.join("mobility.xml")));
}
