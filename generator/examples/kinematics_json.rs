//! The generator's own forward kinematics of the objects `generator export-objects` writes,
//! as JSON on stdout, so that a URDF reader's poses can be checked against it
//! (`python/tests/test_export_objects.py` does so with yourdfpy).
//!
//! ```text
//! cargo run -p generator --example kinematics_json -- --seed 3 --split test -n 26 > fk.json
//! ```
//!
//! For each object (same selection flags and defaults as `generator export-objects`): its
//! folder name, its joints (name, kind, limits, axis, mimic), and for several joint
//! configurations (every joint at its lower limit, at its upper limit, at mid-range, and
//! the object's first drawn states) each URDF link's world transform (row-major 4x4, the
//! `base` frame to the link frame) and the bounds of its posed mesh.

use anyhow::{Context, Result};
use articulated::categories::Split;
use articulated::kinematics::link_poses;
use articulated::objects::ArticulatedObject;
use assets::sourced::folder_name;
use clap::Parser;
use generator::config::GeneratorConfig;
use generator::generate::{build_object, object_states};
use pairs::math::{Isometry3, Point3, Real, Translation3};
use pairs::JointKind;
use serde_json::{json, Value};
use simulators::urdf::{link_name, link_origins};

/// Prints the generator's forward kinematics of exported objects as JSON.
#[derive(Debug, Parser)]
struct Args {
    /// Dataset seed.
    #[arg(short, long, default_value_t = 0)]
    seed: u64,
    /// Category split.
    #[arg(long, default_value = "test")]
    split: Split,
    /// Comma-separated categories (default: every category of the split).
    #[arg(long, value_delimiter = ',')]
    categories: Vec<String>,
    /// Number of objects.
    #[arg(short = 'n', long, default_value_t = 1)]
    objects: u32,
    /// Drawn states to include per object, besides the three limit configurations.
    #[arg(long, default_value_t = 2)]
    states: usize,
}

fn main() -> Result<()> {
    let args = Args::parse();
    let config = GeneratorConfig {
        seed: args.seed,
        split: args.split,
        categories: args.categories.clone(),
        objects: args.objects,
        ..Default::default()
    };
    config.validate().context("checking the selection")?;
    let mut objects = Vec::new();
    for index in 0..config.objects {
        let object = build_object(&config, index).context("building an object")?;
        objects.push(object_json(&config, index, &object, args.states));
    }
    println!("{}", serde_json::to_string(&Value::Array(objects))?);
    Ok(())
}

fn object_json(
    config: &GeneratorConfig,
    index: u32,
    object: &ArticulatedObject,
    drawn: usize,
) -> Value {
    let joints: Vec<Value> = object
        .joints
        .iter()
        .enumerate()
        .map(|(j, joint)| {
            let mimic = object.mimics.iter().find(|m| m.joint == j).map(|m| {
                json!({
                    "joint": object.joints[m.leader].name,
                    "multiplier": m.multiplier,
                    "offset": m.offset,
                })
            });
            json!({
                "name": joint.name,
                "type": if joint.kind == JointKind::Revolute { "revolute" } else { "prismatic" },
                "parent": link_name(joint.parent),
                "child": link_name(joint.child),
                "lower": joint.limits.0,
                "upper": joint.limits.1,
                "axis": [joint.axis.x, joint.axis.y, joint.axis.z],
                "mimic": mimic,
            })
        })
        .collect();
    let at = |f: &dyn Fn(Real, Real) -> Real| -> Vec<Real> {
        let mut values: Vec<Real> =
            object.joints.iter().map(|j| f(j.limits.0, j.limits.1)).collect();
        object.follow_mimics(&mut values);
        values
    };
    let mut configurations = vec![at(&|lo, _| lo), at(&|_, hi| hi), at(&|lo, hi| 0.5 * (lo + hi))];
    configurations.extend(object_states(config, object, index).into_iter().take(drawn));
    let origins = link_origins(object);
    let states: Vec<Value> = configurations
        .iter()
        .map(|values| {
            let poses = link_poses(object, values);
            let links: serde_json::Map<String, Value> = poses
                .iter()
                .enumerate()
                .map(|(l, pose)| {
                    let frame = pose * Translation3::from(origins[l].coords);
                    let posed: Vec<_> =
                        object.links[l].mesh.vertices.iter().map(|v| pose * v).collect();
                    let (lo, hi) =
                        pairs::math::bounds(&posed).unwrap_or((Point3::origin(), Point3::origin()));
                    let value = json!({
                        "transform": matrix(&frame),
                        "bounds": [[lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z]],
                    });
                    (link_name(l), value)
                })
                .collect();
            json!({ "values": object.configuration(values), "links": links })
        })
        .collect();
    json!({
        "folder": folder_name(index, &object.category),
        "category": object.category,
        "joints": joints,
        "states": states,
    })
}

/// A row-major 4x4 matrix.
fn matrix(pose: &Isometry3) -> Vec<Vec<f64>> {
    let m = pose.to_homogeneous();
    (0..4).map(|r| (0..4).map(|c| f64::from(m[(r, c)])).collect()).collect()
}
