//! Writes the example asset set of `generator/examples/assets/`: one desk lamp (a base with
//! a welded pole, an arm that swivels without limits, a shade that tilts) as an OBJ with a
//! joints sidecar, as a URDF with OBJ and STL meshes, and as a glTF with joints in node
//! extras. This should print the eight files it wrote; the committed set is its output:
//! `cargo run -p generator --example example_assets -- generator/examples/assets`.
//!
//! Every coordinate is a multiple of 1/64 (and every scale a power of two), so that the
//! three formats give bit-identical meshes after each importer's own transforms.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use articulated::mesh::Mesh;
use base64::Engine as _;
use pairs::math::{Point3, Vector3};
use serde_json::json;

/// One link of the lamp: its box in its own frame, and its frame's origin in its parent's.
struct Part {
    name: &'static str,
    min: [f32; 3],
    max: [f32; 3],
    offset: [f32; 3],
}

const PARTS: [Part; 4] = [
    Part { name: "base", min: [-0.25, 0.0, -0.25], max: [0.25, 0.0625, 0.25], offset: [0.0; 3] },
    Part {
        name: "pole",
        min: [-0.03125, 0.0, -0.03125],
        max: [0.03125, 0.4375, 0.03125],
        offset: [0.0, 0.0625, 0.0],
    },
    Part {
        name: "arm",
        min: [-0.03125, 0.0, -0.03125],
        max: [0.5, 0.0625, 0.03125],
        offset: [0.0, 0.4375, 0.0],
    },
    Part {
        name: "shade",
        min: [0.0, -0.25, -0.0625],
        max: [0.125, 0.0, 0.0625],
        offset: [0.5, 0.0625, 0.0],
    },
];

/// The joints as sidecar records (origins and axes in the lamp's frame).
fn joints() -> serde_json::Value {
    json!([
        { "name": "mount", "type": "fixed", "parent": "base", "child": "pole" },
        { "name": "swivel", "type": "continuous", "parent": "pole", "child": "arm",
          "origin": [0.0, 0.5, 0.0], "axis": [0.0, 1.0, 0.0] },
        { "name": "tilt", "type": "revolute", "parent": "arm", "child": "shade",
          "origin": [0.5, 0.5625, 0.0], "axis": [0.0, 0.0, 1.0], "lower": 0.0, "upper": 1.5 }
    ])
}

fn main() -> anyhow::Result<()> {
    let root = PathBuf::from(std::env::args().nth(1).unwrap_or("generator/examples/assets".into()));
    let mut written = Vec::new();
    let mut write = |path: PathBuf, text: String| -> anyhow::Result<()> {
        std::fs::create_dir_all(path.parent().unwrap_or(Path::new(".")))?;
        std::fs::write(&path, text)?;
        written.push(path);
        Ok(())
    };
    let local: Vec<Mesh> = PARTS.iter().map(|p| Mesh::cuboid(p.min.into(), p.max.into())).collect();
    // Frames in the lamp's frame: each part's offset added to its parent's (a chain).
    let mut frames = Vec::new();
    let mut at = Vector3::zeros();
    for p in &PARTS {
        at += Vector3::from(p.offset);
        frames.push(at);
    }
    let world =
        |i: usize| -> Vec<Point3> { local[i].vertices.iter().map(|v| v + frames[i]).collect() };

    // OBJ: one group per part, in the lamp's frame.
    let mut obj = String::from("# A desk lamp, one group per part (generator example asset).\n");
    let mut first = 1;
    for (i, p) in PARTS.iter().enumerate() {
        writeln!(obj, "g {}", p.name)?;
        for v in world(i) {
            writeln!(obj, "v {} {} {}", v.x, v.y, v.z)?;
        }
        for t in &local[i].triangles {
            writeln!(obj, "f {} {} {}", t[0] + first, t[1] + first, t[2] + first)?;
        }
        first += local[i].vertices.len() as u32;
    }
    write(root.join("obj/lamp.obj"), obj)?;
    let sidecar = json!({ "category": "lamp", "joints": joints() });
    write(root.join("obj/lamp.joints.json"), serde_json::to_string_pretty(&sidecar)? + "\n")?;

    // URDF: meshes in link frames; the base as an STL shifted by its visual origin, the
    // shade as an STL at twice its size scaled by one half, the others as OBJ.
    let shift = Vector3::new(0.0, 0.03125, 0.0);
    let base_mesh: Vec<Point3> = local[0].vertices.iter().map(|v| v - shift).collect();
    write(root.join("urdf/meshes/base.stl"), stl("base", &base_mesh, &local[0].triangles)?)?;
    let pole_obj = obj_text("pole", &local[1].vertices, &local[1].triangles)?;
    write(root.join("urdf/meshes/pole.obj"), pole_obj)?;
    write(
        root.join("urdf/meshes/arm.obj"),
        obj_text("arm", &local[2].vertices, &local[2].triangles)?,
    )?;
    let shade_mesh: Vec<Point3> = local[3].vertices.iter().map(|v| v * 2.0).collect();
    write(root.join("urdf/meshes/shade.stl"), stl("shade", &shade_mesh, &local[3].triangles)?)?;
    write(root.join("urdf/lamp.urdf"), URDF.into())?;

    // glTF: a node per part, meshes in node frames, one base64 buffer.
    write(root.join("gltf/lamp.gltf"), gltf(&local)?)?;
    for path in written {
        println!("{}", path.display());
    }
    Ok(())
}

fn obj_text(name: &str, vertices: &[Point3], triangles: &[[u32; 3]]) -> anyhow::Result<String> {
    let mut text = format!("o {name}\n");
    for v in vertices {
        writeln!(text, "v {} {} {}", v.x, v.y, v.z)?;
    }
    for t in triangles {
        writeln!(text, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
    }
    Ok(text)
}

fn stl(name: &str, vertices: &[Point3], triangles: &[[u32; 3]]) -> anyhow::Result<String> {
    let mut text = format!("solid {name}\n");
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        // A degenerate triangle gets the zero normal, which STL readers recompute.
        let n = pairs::math::unit_or(&(b - a).cross(&(c - a)), pairs::math::Vector3::zeros());
        writeln!(text, "facet normal {} {} {}\n outer loop", n.x, n.y, n.z)?;
        for v in [a, b, c] {
            writeln!(text, "  vertex {} {} {}", v.x, v.y, v.z)?;
        }
        writeln!(text, " endloop\nendfacet")?;
    }
    writeln!(text, "endsolid {name}")?;
    Ok(text)
}

fn gltf(local: &[Mesh]) -> anyhow::Result<String> {
    let mut buffer: Vec<u8> = Vec::new();
    let (mut views, mut accessors, mut meshes) = (Vec::new(), Vec::new(), Vec::new());
    for (i, mesh) in local.iter().enumerate() {
        let (lo, hi) = mesh.vertices.iter().fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), v| {
            (std::array::from_fn(|k| lo[k].min(v[k])), std::array::from_fn(|k| hi[k].max(v[k])))
        });
        let start = buffer.len();
        mesh.vertices
            .iter()
            .flat_map(|v| v.iter().copied())
            .for_each(|c| buffer.extend(c.to_le_bytes()));
        views.push(json!({ "buffer": 0, "byteOffset": start, "byteLength": buffer.len() - start }));
        accessors.push(
            json!({ "bufferView": 2 * i, "componentType": 5126, "count": mesh.vertices.len(),
                               "type": "VEC3", "min": lo, "max": hi }),
        );
        let start = buffer.len();
        let count = mesh.triangles.len() * 3;
        mesh.triangles.iter().flatten().for_each(|&k| buffer.extend((k as u16).to_le_bytes()));
        buffer.resize(buffer.len().next_multiple_of(4), 0);
        views.push(json!({ "buffer": 0, "byteOffset": start, "byteLength": 2 * count }));
        accessors.push(json!({ "bufferView": 2 * i + 1, "componentType": 5123, "count": count, "type": "SCALAR" }));
        meshes.push(json!({ "name": PARTS[i].name,
                            "primitives": [{ "attributes": { "POSITION": 2 * i }, "indices": 2 * i + 1 }] }));
    }
    let joint_of = |child: &str| {
        joints().as_array().and_then(|all| {
            all.iter().find(|j| j["child"] == child && j["type"] != "fixed").cloned()
        })
    };
    let nodes: Vec<_> = PARTS
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut node = json!({ "name": p.name, "mesh": i, "translation": p.offset });
            if i + 1 < PARTS.len() {
                node["children"] = json!([i + 1]);
            }
            if let Some(mut joint) = joint_of(p.name) {
                // The node is the child and its hierarchy parent the parent: both implied.
                let fields = joint.as_object_mut().expect("a joint record is an object");
                fields.remove("child");
                fields.remove("parent");
                node["extras"] = json!({ "joint": joint });
            }
            node
        })
        .collect();
    let data = base64::engine::general_purpose::STANDARD.encode(&buffer);
    let document = json!({
        "asset": { "version": "2.0", "generator": "part-induction example_assets" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": nodes,
        "meshes": meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{ "byteLength": buffer.len(),
                      "uri": format!("data:application/octet-stream;base64,{data}") }]
    });
    Ok(serde_json::to_string_pretty(&document)? + "\n")
}

const URDF: &str = r#"<?xml version="1.0"?>
<!-- A desk lamp (generator example asset): the pole is welded to the base, the arm
     swivels without limits, the shade tilts. Meshes are in link frames. -->
<robot name="lamp">
  <link name="base">
    <visual>
      <origin xyz="0 0.03125 0" rpy="0 0 0"/>
      <geometry><mesh filename="meshes/base.stl"/></geometry>
    </visual>
  </link>
  <link name="pole">
    <visual>
      <geometry><mesh filename="package://lamp/meshes/pole.obj"/></geometry>
    </visual>
  </link>
  <link name="arm">
    <visual>
      <geometry><mesh filename="meshes/arm.obj"/></geometry>
    </visual>
  </link>
  <link name="shade">
    <visual>
      <geometry><mesh filename="meshes/shade.stl" scale="0.5 0.5 0.5"/></geometry>
    </visual>
  </link>
  <joint name="mount" type="fixed">
    <parent link="base"/>
    <child link="pole"/>
    <origin xyz="0 0.0625 0"/>
  </joint>
  <joint name="swivel" type="continuous">
    <parent link="pole"/>
    <child link="arm"/>
    <origin xyz="0 0.4375 0"/>
    <axis xyz="0 1 0"/>
  </joint>
  <joint name="tilt" type="revolute">
    <parent link="arm"/>
    <child link="shade"/>
    <origin xyz="0.5 0.0625 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="0" upper="1.5" effort="1" velocity="1"/>
  </joint>
</robot>
"#;
