//! Writes every field of every pair of a dataset, as this crate reads it, to one JSON file:
//! `dump_pairs <dataset> <out.json> [N]` prints "wrote N pairs to <out.json>". For a set
//! dataset it writes every set (its views' arrays, joints and provenance) with every pair
//! of two of its views that `Set::pair` gives.
//!
//! The Python package's tests (`python/tests/`) compare their reader against this dump, so
//! the Rust and Python readers of docs/FORMAT.md cannot drift apart. Floats are f32 values
//! written exactly; compare them after a cast to f32.

use std::error::Error;
use std::path::PathBuf;

use pairs::dataset::Dataset;
use pairs::math::{Matrix3, Point3, Vector3};
use pairs::{Cloud, Pair, Scan, Set};
use serde_json::{json, Value};

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [dataset, out, rest @ ..] = args.as_slice() else {
        return Err("usage: dump_pairs <dataset folder> <out.json> [max pairs]".into());
    };
    let limit = match rest {
        [] => usize::MAX,
        [n] => n.parse()?,
        _ => return Err("usage: dump_pairs <dataset folder> <out.json> [max pairs]".into()),
    };
    let dataset = Dataset::open(dataset)?;
    if dataset.holds_sets() {
        let sets = dataset
            .sets()?
            .take(limit)
            .map(|set| set.map(|s| dump_set(&s)))
            .collect::<Result<Vec<Value>, _>>()?;
        let out = PathBuf::from(out);
        std::fs::write(&out, serde_json::to_vec(&sets)?)?;
        println!("wrote {} sets to {}", sets.len(), out.display());
        return Ok(());
    }
    let pairs = dataset
        .pairs()?
        .take(limit)
        .map(|pair| pair.map(|p| dump(&p)))
        .collect::<Result<Vec<Value>, _>>()?;
    let out = PathBuf::from(out);
    std::fs::write(&out, serde_json::to_vec(&pairs)?)?;
    println!("wrote {} pairs to {}", pairs.len(), out.display());
    Ok(())
}

fn dump(pair: &Pair) -> Value {
    let (input, truth) = (pair.input(), pair.truth());
    let scale = truth.motions.first().map_or(1.0, |m| m.scale);
    json!({
        "id": pair.id(),
        "kind": input.kind.as_str(),
        "p": cloud(&input.p),
        "q": cloud(&input.q),
        "num_parts": truth.num_parts(),
        "part_p": truth.part_p,
        "part_q": truth.part_q,
        "scale": scale,
        "rotations": truth.motions.iter().map(|m| rows(&m.rotation)).collect::<Vec<_>>(),
        "translations": truth.motions.iter().map(|m| vector(&m.translation)).collect::<Vec<_>>(),
        "flow": truth.flow.as_ref().map(|f| f.iter().map(vector).collect::<Vec<_>>()),
        "corr_mask": truth.corr_mask,
        "corr_index": truth.corr_index,
        "joints": truth.joints.iter().map(|j| json!({
            "part": j.part,
            "kind": j.kind.as_str(),
            "axis_p": vector(&j.axis_p),
            "pivot_p": point(&j.pivot_p),
            "axis_q": vector(&j.axis_q),
            "pivot_q": point(&j.pivot_q),
            "value_p": j.value_p,
            "value_q": j.value_q,
        })).collect::<Vec<_>>(),
        "provenance": pair.provenance(),
        "scan_p": pair.scans().p.as_ref().map(scan),
        "scan_q": pair.scans().q.as_ref().map(scan),
    })
}

fn dump_set(set: &Set) -> Value {
    let (input, truth) = (set.input(), set.truth());
    let views: Vec<Value> = input
        .views
        .iter()
        .enumerate()
        .map(|(k, view)| {
            json!({
                "kind": view.kind.as_str(),
                "cloud": cloud(&view.cloud),
                "parts": truth.parts[k],
                "scale": truth.motions[k].first().map_or(1.0, |m| m.scale),
                "rotations": truth.motions[k].iter().map(|m| rows(&m.rotation)).collect::<Vec<_>>(),
                "translations":
                    truth.motions[k].iter().map(|m| vector(&m.translation)).collect::<Vec<_>>(),
                "flow": truth.flows[k].iter().map(vector).collect::<Vec<_>>(),
                "presence": truth.presence[k],
                "pair_parts": truth.pair_parts[k],
                "scan": set.scans()[k].as_ref().map(scan),
            })
        })
        .collect();
    let n = set.len();
    let pairs: Vec<Value> = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .filter_map(|(i, j)| set.pair(i, j).ok())
        .map(|pair| dump(&pair))
        .collect();
    json!({
        "id": set.id(),
        "num_parts": truth.num_parts(),
        "views": views,
        "joints": truth.joints.iter().map(|j| json!({
            "name": j.name,
            "part": j.part,
            "parent": j.parent,
            "kind": j.kind.as_str(),
            "axis": j.axis.iter().map(vector).collect::<Vec<_>>(),
            "pivot": j.pivot.iter().map(point).collect::<Vec<_>>(),
            "value": j.value,
        })).collect::<Vec<_>>(),
        "provenance": set.provenance(),
        "pairs": pairs,
    })
}

fn cloud(c: &Cloud) -> Value {
    json!({
        "points": c.points.iter().map(point).collect::<Vec<_>>(),
        "centre": vector(&c.normalisation.centre),
        "scale": c.normalisation.scale,
    })
}

fn scan(s: &Scan) -> Value {
    let k = &s.intrinsics;
    json!({
        "width": k.width,
        "height": k.height,
        "intrinsics": [k.fx, k.fy, k.cx, k.cy],
        "rotation": rows(&s.rotation),
        "translation": vector(&s.translation),
        "depth_scale": s.depth_scale,
        "depth": s.images.depth,
        "labels": s.images.labels,
        "colour": s.images.colour,
    })
}

fn vector(v: &Vector3) -> [f32; 3] {
    [v.x, v.y, v.z]
}

fn point(p: &Point3) -> [f32; 3] {
    vector(&p.coords)
}

fn rows(r: &Matrix3) -> [[f32; 3]; 3] {
    [[r.m11, r.m12, r.m13], [r.m21, r.m22, r.m23], [r.m31, r.m32, r.m33]]
}
