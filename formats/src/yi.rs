//! `yi-mat`: the `.mat` files of the paper authors' code (ericyi/articulated-part-induction).
//!
//! Their loaders `scipy.io.loadmat` one file per split and index `data[name][sample]`,
//! points as rows. Written into the output folder:
//!
//! - `pairs.mat` (their `SynTestDataset` and `SegDataset` layout): `pc1` (K, N, 3) single,
//!   P normalised; `pc2` and `pc2_partial` (K, M, 3) single, Q normalised; `flow12`
//!   (K, N, 3) single; `seg1` (K, N) int32, P's parts plus 1; `seg2` (K, M) int32, Q's parts
//!   plus 1; `momasks` (K, N) int32, P's parts (0-based); `vismask` (K, N) single, the
//!   correspondence mask as 0/1;
//! - `flow.mat` (their `FlowDataset` layout, flow = `pc2 - pc1`): `pc1` (K, N, 3),
//!   `pc2` (K, N, 3) = `pc1 + flow12`, `pc2_partial` (K, M, 3) = Q, `vismask` (K, N);
//! - `ids.txt`: the pair ids, one a line, in the order of the first axis.
//!
//! Every pair must have the same N (P's point count) and M (Q's).

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use pairs::Pair;

use crate::{mat, FormatError};
use pairs::atomic::{write_file, OutputError};

/// What the pairs' arrays are stacked into, row-major (pair, point, coordinate).
#[derive(Debug, Default)]
pub(super) struct YiExport {
    /// (N, M) and the id of the first pair, once a pair was added.
    shape: Option<(usize, usize, String)>,
    ids: Vec<String>,
    pc1: Vec<f32>,
    pc2: Vec<f32>,
    moved: Vec<f32>,
    flow12: Vec<f32>,
    seg1: Vec<i32>,
    seg2: Vec<i32>,
    momasks: Vec<i32>,
    vismask: Vec<f32>,
}

impl YiExport {
    /// Appends a pair; refuses one whose point counts differ from the first pair's.
    pub(super) fn add(&mut self, pair: &Pair) -> Result<(), FormatError> {
        let (input, truth) = (pair.input(), pair.truth());
        let (n, m) = (input.p.len(), input.q.len());
        let (first_n, first_m, first_id) =
            self.shape.get_or_insert_with(|| (n, m, pair.id().to_string()));
        for (cloud, count, first) in [("P", n, *first_n), ("Q", m, *first_m)] {
            if count != first {
                return Err(FormatError::Shape {
                    pair: pair.id().into(),
                    reason: format!(
                        "{cloud} has {count} points, earlier pairs {first} (first pair \
                         {first_id}); yi-mat needs one point count per cloud across the dataset"
                    ),
                });
            }
        }
        let Some(flow) = &truth.flow else {
            return Err(FormatError::Shape {
                pair: pair.id().into(),
                reason: format!(
                    "a {} pair has no flow (two different objects); yi-mat's flow12 and \
                     flow.mat need one",
                    input.kind.as_str()
                ),
            });
        };
        self.ids.push(pair.id().into());
        for (p, f) in input.p.points.iter().zip(flow) {
            self.pc1.extend_from_slice(p.coords.as_slice());
            self.flow12.extend_from_slice(f.as_slice());
            self.moved.extend_from_slice((p.coords + f).as_slice());
        }
        for q in &input.q.points {
            self.pc2.extend_from_slice(q.coords.as_slice());
        }
        self.seg1.extend(truth.part_p.iter().map(|&k| i32::from(k) + 1));
        self.momasks.extend(truth.part_p.iter().map(|&k| i32::from(k)));
        self.seg2.extend(truth.part_q.iter().map(|&k| i32::from(k) + 1));
        self.vismask.extend(truth.corr_mask.iter().map(|&c| if c { 1.0f32 } else { 0.0 }));
        Ok(())
    }

    /// Writes `pairs.mat`, `flow.mat` and `ids.txt` into `dir`; returns the files written
    /// with their sizes.
    pub(super) fn write(&self, dir: &Path) -> Result<Vec<u64>, FormatError> {
        let k = self.ids.len();
        let (n, m) = self.shape.as_ref().map_or((0, 0), |s| (s.0, s.1));
        let (cloud_p, cloud_q, mask_p, mask_q) = ([k, n, 3], [k, m, 3], [k, n], [k, m]);
        for (name, dims) in [("pc1", &cloud_p[..]), ("pc2", &cloud_q[..])] {
            mat::check_fits(name, dims).map_err(|bytes| FormatError::TooLarge {
                path: dir.join("pairs.mat"),
                reason: format!(
                    "variable {name} of shape {dims:?} takes {bytes} bytes; a MAT v5 variable \
                     holds at most 4 GiB (export fewer or smaller pairs)"
                ),
            })?;
        }
        let mut sizes = Vec::new();
        sizes.push(write_mat(&dir.join("pairs.mat"), |w| {
            mat::write_array(w, "pc1", &cloud_p, &self.pc1)?;
            mat::write_array(w, "pc2", &cloud_q, &self.pc2)?;
            mat::write_array(w, "pc2_partial", &cloud_q, &self.pc2)?;
            mat::write_array(w, "flow12", &cloud_p, &self.flow12)?;
            mat::write_array(w, "seg1", &mask_p, &self.seg1)?;
            mat::write_array(w, "seg2", &mask_q, &self.seg2)?;
            mat::write_array(w, "momasks", &mask_p, &self.momasks)?;
            mat::write_array(w, "vismask", &mask_p, &self.vismask)
        })?);
        sizes.push(write_mat(&dir.join("flow.mat"), |w| {
            mat::write_array(w, "pc1", &cloud_p, &self.pc1)?;
            mat::write_array(w, "pc2", &cloud_p, &self.moved)?;
            mat::write_array(w, "pc2_partial", &cloud_q, &self.pc2)?;
            mat::write_array(w, "vismask", &mask_p, &self.vismask)
        })?);
        let ids: String = self.ids.iter().map(|id| format!("{id}\n")).collect();
        sizes.push(write_file(&dir.join("ids.txt"), ids.as_bytes())?);
        Ok(sizes)
    }
}

/// Writes a MAT file: the header, then what `body` writes; returns its size.
fn write_mat(
    path: &Path,
    body: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> Result<u64, FormatError> {
    let io = |source| FormatError::Output(OutputError::Io { path: path.into(), source });
    let mut w = BufWriter::with_capacity(1 << 20, File::create(path).map_err(io)?);
    mat::write_header(
        &mut w,
        "MATLAB 5.0 MAT-file, written by the part-induction generator (generator export \
         --format yi-mat)",
    )
    .map_err(io)?;
    body(&mut w).map_err(io)?;
    let file = w.into_inner().map_err(|e| io(e.into_error()))?;
    Ok(file.metadata().map_err(io)?.len())
}
