//! `mbs-npz`: the dataset layout of MultiBodySync (huangjh-pub/multibody-sync).
//!
//! - `meta.json`: `{"train": [...], "val": [...], "test": [...]}`, the sample numbers of
//!   each split; every pair goes under the dataset's split, the other two lists are empty;
//! - `data/%06d.npz`, one per pair in file order (a ZIP of stored `.npy` entries, as
//!   `numpy.savez` writes): `pc` (2, N, 3) float32, the two views in one frame (P's
//!   normalised frame: view 0 is P, view 1 is Q mapped into it); `segm` (2, N) int64, part ids
//!   plus 1; `trans`, a 0-d object array holding `{'cam': [I, I], k: [I, T_k], ...}` with
//!   `T_k` the rigid motion of part k - 1 from view 0 to view 1 (4x4 float64, column-vector
//!   convention);
//! - `ids.txt`: the pair ids, one a line; line i is `data/%06d.npz` of i.
//!
//! MultiBodySync computes the flow of a point of part k as
//! `inv(cam1) · T[k][1] · inv(T[k][0]) · cam0 · p`, which here is `T_k p`.

use std::io::{Cursor, Write};

use nalgebra::{Matrix3, Matrix4, Rotation3, Vector3};
use pairs::{Pair, Set};
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

use crate::npy;
use crate::pickle::{self, Key};
use crate::FormatError;

/// How far the scale of a part motion mapped into the common frame may be from 1 before
/// the motion is refused as not rigid (it is 1 up to rounding by construction).
const RIGID_SCALE_TOLERANCE: f64 = 1e-3;

/// The map from Q's normalised frame to the common frame (P's normalised frame),
/// `x -> a x + b`: back to the object frame with Q's normalisation, then into P's.
pub(super) fn q_to_common(pair: &Pair) -> (f64, Vector3<f64>) {
    let (p, q) = (&pair.input().p.normalisation, &pair.input().q.normalisation);
    let (s_p, s_q) = (f64::from(p.scale), f64::from(q.scale));
    let b = (q.centre.cast::<f64>() - p.centre.cast::<f64>()) / s_p;
    (s_q / s_p, b)
}

/// `T_k` for every part k: the part's motion (P's normalised frame to Q's) followed by the
/// map of Q's normalised frame into the common frame, a rigid motion whose rotation is
/// re-orthonormalised in f64.
pub(super) fn part_transforms(pair: &Pair) -> Result<Vec<Matrix4<f64>>, FormatError> {
    let (a, b) = q_to_common(pair);
    pair.truth()
        .motions
        .iter()
        .enumerate()
        .map(|(k, motion)| {
            let scale = a * f64::from(motion.scale);
            if (scale - 1.0).abs() > RIGID_SCALE_TOLERANCE {
                return Err(FormatError::Shape {
                    pair: pair.id().into(),
                    reason: format!(
                        "motion of part {k} has scale {scale} in P's normalised frame (not \
                         rigid); mbs-npz needs rigid part motions"
                    ),
                });
            }
            let rotation: Matrix3<f64> = motion.rotation.cast::<f64>();
            let rotation = Rotation3::from_matrix(&rotation).into_inner();
            let translation = motion.translation.cast::<f64>() * a + b;
            let mut t = Matrix4::identity();
            t.fixed_view_mut::<3, 3>(0, 0).copy_from(&rotation);
            t.fixed_view_mut::<3, 1>(0, 3).copy_from(&translation);
            Ok(t)
        })
        .collect()
}

fn rows(m: &Matrix4<f64>) -> pickle::Matrix4 {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// The `.npz` file of one pair.
pub(super) fn npz(pair: &Pair) -> Result<Vec<u8>, FormatError> {
    let (input, truth) = (pair.input(), pair.truth());
    if input.kind.cross_instance() {
        return Err(FormatError::Shape {
            pair: pair.id().into(),
            reason: format!(
                "a {} pair holds two different objects; mbs-npz's `trans` would give \
                 MultiBodySync a flow between them, and none is defined",
                input.kind.as_str()
            ),
        });
    }
    let n = input.p.len();
    if input.q.len() != n {
        return Err(FormatError::Shape {
            pair: pair.id().into(),
            reason: format!(
                "P has {n} points and Q {}; mbs-npz needs one point count for both views",
                input.q.len()
            ),
        });
    }
    let (a, b) = q_to_common(pair);
    let mut pc = Vec::with_capacity(6 * n);
    for p in &input.p.points {
        pc.extend_from_slice(p.coords.as_slice());
    }
    for q in &input.q.points {
        let common = q.coords.cast::<f64>() * a + b;
        pc.extend(common.iter().map(|&c| c as f32));
    }
    let segm: Vec<i64> =
        truth.part_p.iter().chain(&truth.part_q).map(|&k| i64::from(k) + 1).collect();
    let identity = rows(&Matrix4::identity());
    let mut trans = vec![(Key::Text("cam".into()), vec![identity, identity])];
    for (k, t) in part_transforms(pair)?.iter().enumerate() {
        let key = i32::try_from(k + 1).expect("at most 256 parts");
        trans.push((Key::Int(key), vec![identity, rows(t)]));
    }
    let entries = [
        ("pc.npy", npy::f32_array(&[2, n, 3], &pc)),
        ("segm.npy", npy::i64_array(&[2, n], &segm)),
        ("trans.npy", npy::object_scalar(&pickle::numpy_dict_of_matrix_lists(&trans))),
    ];
    Ok(zip_stored(&entries).expect("writing a ZIP into memory cannot fail"))
}

/// The `.npz` file of one set of K views: `pc` (K, N, 3), every view mapped into view 0's
/// normalised frame; `segm` (K, N), set parts plus 1 (one labelling for all K views);
/// `trans`: `cam` K identities and, for set part s, K transforms: the identity, then each
/// view k's motion of the part from view 0 (`Set::pair(0, k)`'s motion of the pair part
/// holding s, mapped into the common frame). MultiBodySync's flow from view i to view j is
/// then `T[s][j] · inv(T[s][i])`.
pub(super) fn set_npz(set: &Set) -> Result<Vec<u8>, FormatError> {
    let shape = |reason: String| FormatError::Shape { pair: set.id().into(), reason };
    let (input, truth) = (set.input(), set.truth());
    let n = input.views[0].cloud.len();
    if let Some(k) = input.views.iter().position(|v| v.cloud.len() != n) {
        return Err(shape(format!(
            "view 0 has {n} points and view {k} {}; mbs-npz needs one point count for all views",
            input.views[k].cloud.len()
        )));
    }
    let k = set.len();
    let mut pc = Vec::with_capacity(3 * n * k);
    for p in &input.views[0].cloud.points {
        pc.extend_from_slice(p.coords.as_slice());
    }
    let identity = rows(&Matrix4::identity());
    let mut per_part: Vec<Vec<pickle::Matrix4>> = vec![vec![identity]; truth.num_parts()];
    for view in 1..k {
        let pair = set.pair(0, view).map_err(|e| shape(e.to_string()))?;
        let (a, b) = q_to_common(&pair);
        for q in &input.views[view].cloud.points {
            let common = q.coords.cast::<f64>() * a + b;
            pc.extend(common.iter().map(|&c| c as f32));
        }
        let transforms = part_transforms(&pair)?;
        for (s, views) in per_part.iter_mut().enumerate() {
            views.push(rows(&transforms[usize::from(truth.pair_parts[0][view][s])]));
        }
    }
    let segm: Vec<i64> = truth.parts.iter().flatten().map(|&s| i64::from(s) + 1).collect();
    let mut trans = vec![(Key::Text("cam".into()), vec![identity; k])];
    for (s, views) in per_part.into_iter().enumerate() {
        let key = i32::try_from(s + 1).expect("at most 256 parts");
        trans.push((Key::Int(key), views));
    }
    let entries = [
        ("pc.npy", npy::f32_array(&[k, n, 3], &pc)),
        ("segm.npy", npy::i64_array(&[k, n], &segm)),
        ("trans.npy", npy::object_scalar(&pickle::numpy_dict_of_matrix_lists(&trans))),
    ];
    Ok(zip_stored(&entries).expect("writing a ZIP into memory cannot fail"))
}

/// A ZIP of stored (uncompressed) entries with fixed times and permissions, so that the
/// same entries give the same bytes.
fn zip_stored(entries: &[(&str, Vec<u8>)]) -> zip::result::ZipResult<Vec<u8>> {
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .last_modified_time(DateTime::default())
        .unix_permissions(0o644)
        .large_file(false);
    let size: usize = entries.iter().map(|(name, data)| data.len() + 2 * name.len() + 128).sum();
    let mut zip = ZipWriter::new(Cursor::new(Vec::with_capacity(size + 64)));
    for (name, data) in entries {
        zip.start_file(*name, options)?;
        zip.write_all(data)?;
    }
    Ok(zip.finish()?.into_inner())
}

/// `meta.json`: every one of `count` samples under `split` (`train`, `val` or `test`), the
/// other two splits empty; keys in MultiBodySync's order.
pub(super) fn meta_json(split: &str, count: usize) -> String {
    let list = |name: &str| {
        let ids: Vec<usize> = if name == split { (0..count).collect() } else { Vec::new() };
        serde_json::to_string(&ids).expect("a list of integers serialises")
    };
    format!(
        "{{\"train\": {}, \"val\": {}, \"test\": {}}}\n",
        list("train"),
        list("val"),
        list("test")
    )
}
