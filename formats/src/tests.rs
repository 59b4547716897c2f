use std::collections::BTreeMap;
use std::io::Read;

use nalgebra::{Matrix4, Vector4};
use pairs::dataset::{DatasetOrigin, DatasetWriter};
use pairs::{synthetic, Pair, PairInput};

use super::*;

fn origin(split: &str) -> DatasetOrigin {
    DatasetOrigin {
        generator_version: "test".into(),
        seed: 7,
        config: serde_json::json!({ "points": 32, "split": split }),
        splits: Default::default(),
        shard: None,
        assets: Vec::new(),
        left_out: Default::default(),
    }
}

fn hinges(sides: &[usize]) -> Vec<Pair> {
    sides
        .iter()
        .enumerate()
        .map(|(i, &side)| synthetic::hinge_pair(&format!("hinge-{i}"), side, 0.3 + 0.4 * i as f32))
        .collect()
}

fn write_dataset(dir: &Path, pairs: &[Pair], split: &str) {
    let mut writer = DatasetWriter::create(dir, false).expect("create");
    for pair in pairs {
        writer.write(pair).expect("write");
    }
    writer.finish(origin(split)).expect("finish");
}

/// Every file under `dir`, by relative path.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).expect("list") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path.strip_prefix(dir).expect("under").to_string_lossy().into();
                out.insert(rel, std::fs::read(&path).expect("read"));
            }
        }
    }
    out
}

/// The variables of a MAT v5 file this module wrote: name -> (dims, data words).
fn read_mat(bytes: &[u8]) -> BTreeMap<String, (Vec<usize>, Vec<u32>)> {
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4"));
    let mut vars = BTreeMap::new();
    let mut at = mat::HEADER_LEN;
    while at < bytes.len() {
        assert_eq!(word(at), 14, "miMATRIX");
        let end = at + 8 + word(at + 4) as usize;
        let dims_at = at + 24;
        let ndims = word(dims_at + 4) as usize / 4;
        let dims: Vec<usize> = (0..ndims).map(|i| word(dims_at + 8 + 4 * i) as usize).collect();
        let name_at = dims_at + 8 + (4 * ndims).div_ceil(8) * 8;
        let name_len = word(name_at + 4) as usize;
        let name =
            String::from_utf8(bytes[name_at + 8..name_at + 8 + name_len].to_vec()).expect("name");
        let data_at = name_at + 8 + name_len.div_ceil(8) * 8;
        let count = word(data_at + 4) as usize / 4;
        let data = (0..count).map(|i| word(data_at + 8 + 4 * i)).collect();
        vars.insert(name, (dims, data));
        at = end;
    }
    vars
}

/// The entries of a ZIP.
fn unzip(bytes: &[u8]) -> BTreeMap<String, Vec<u8>> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).expect("zip");
    let mut out = BTreeMap::new();
    for i in 0..archive.len() {
        let mut file = archive.by_index(i).expect("entry");
        assert_eq!(file.compression(), zip::CompressionMethod::Stored);
        let mut data = Vec::new();
        file.read_to_end(&mut data).expect("read");
        out.insert(file.name().expect("UTF-8 name").to_string(), data);
    }
    out
}

#[test]
fn format_names_parse_in_any_case() {
    for f in Format::ALL {
        assert_eq!(f.as_str().parse::<Format>(), Ok(f));
        assert_eq!(f.as_str().to_uppercase().parse::<Format>(), Ok(f));
    }
    let err = "mat".parse::<Format>().unwrap_err();
    assert!(err.contains("yi-mat") && err.contains("mbs-npz"), "{err}");
}

#[test]
fn yi_mat_holds_every_pair_column_major() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (dataset, out) = (dir.path().join("data"), dir.path().join("out"));
    let pairs = hinges(&[4, 4, 4]);
    write_dataset(&dataset, &pairs, "test");
    let mut seen = Vec::new();
    let summary =
        export_dataset(Format::YiMat, &dataset, &out, false, |n| seen.push(n)).expect("export");
    assert_eq!((summary.pairs, summary.files), (3, 3));
    assert_eq!(seen, [1, 2, 3]);
    let written = files(&out);
    assert_eq!(summary.bytes, written.values().map(|b| b.len() as u64).sum::<u64>());
    assert_eq!(written["ids.txt"], b"hinge-0\nhinge-1\nhinge-2\n");
    let vars = read_mat(&written["pairs.mat"]);
    let names: Vec<_> = vars.keys().map(String::as_str).collect();
    assert_eq!(
        names,
        ["flow12", "momasks", "pc1", "pc2", "pc2_partial", "seg1", "seg2", "vismask"]
    );
    let (k, n) = (3usize, 32usize);
    let f32_at = |name: &str, index: usize| f32::from_bits(vars[name].1[index]);
    assert_eq!(vars["pc1"].0, [k, n, 3]);
    assert_eq!(vars["seg1"].0, [k, n]);
    for (pk, pair) in pairs.iter().enumerate() {
        let (input, truth) = (pair.input(), pair.truth());
        for i in 0..n {
            for c in 0..3 {
                let at = pk + k * (i + n * c);
                assert_eq!(f32_at("pc1", at), input.p.points[i][c]);
                assert_eq!(f32_at("pc2", at), input.q.points[i][c]);
                assert_eq!(f32_at("pc2_partial", at), input.q.points[i][c]);
                assert_eq!(f32_at("flow12", at), truth.flow.as_ref().expect("a flow")[i][c]);
            }
            let at = pk + k * i;
            assert_eq!(vars["seg1"].1[at], u32::from(truth.part_p[i]) + 1);
            assert_eq!(vars["seg2"].1[at], u32::from(truth.part_q[i]) + 1);
            assert_eq!(vars["momasks"].1[at], u32::from(truth.part_p[i]));
            assert_eq!(f32_at("vismask", at), 1.0);
        }
    }
    let flow = read_mat(&written["flow.mat"]);
    assert_eq!(flow.keys().collect::<Vec<_>>(), ["pc1", "pc2", "pc2_partial", "vismask"]);
    for (index, (&p, &f)) in vars["pc1"].1.iter().zip(&vars["flow12"].1).enumerate() {
        let moved = f32::from_bits(p) + f32::from_bits(f);
        assert_eq!(f32::from_bits(flow["pc2"].1[index]), moved);
    }
}

#[test]
fn yi_mat_refuses_a_second_point_count_naming_the_pair() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (dataset, out) = (dir.path().join("data"), dir.path().join("out"));
    write_dataset(&dataset, &hinges(&[4, 4, 5]), "test");
    let err = export_dataset(Format::YiMat, &dataset, &out, false, |_| {}).unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, FormatError::Shape { .. }), "{err:?}");
    assert!(text.starts_with("pair hinge-2: P has 50 points, earlier pairs 32"), "{text}");
    assert!(text.contains("yi-mat needs one point count per cloud"), "{text}");
    assert!(!out.exists(), "a failed export leaves nothing");
    let left: Vec<_> = std::fs::read_dir(dir.path()).expect("list").collect();
    assert_eq!(left.len(), 1, "no staging folder is left behind");
}

#[test]
fn both_formats_refuse_a_cross_instance_pair_naming_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let data = dir.path().join("data");
    let cross = synthetic::cross_instance(synthetic::hinge_pair("x-0", 4, 0.5), 1.2);
    write_dataset(&data, &[cross], "test");
    for format in Format::ALL {
        let out = dir.path().join(format!("out-{format:?}"));
        let err = export_dataset(format, &data, &out, false, |_| {}).unwrap_err();
        let text = err.to_string();
        assert!(matches!(err, FormatError::Shape { .. }), "{err:?}");
        assert!(text.contains("x-0") && text.contains("XF2F"), "{text}");
        assert!(!out.exists(), "a failed export leaves nothing");
    }
}

/// `T_k` maps P's points onto their moved positions in the common frame:
/// `T_k p = A(p + flow)`, with `A` Q's normalised frame to P's.
#[test]
fn part_transforms_are_rigid_and_move_p_onto_its_flow() {
    for angle in [0.0, 0.4, 1.3, -2.0] {
        let pair = synthetic::hinge_pair("hinge", 5, angle);
        let (a, b) = mbs::q_to_common(&pair);
        let transforms = mbs::part_transforms(&pair).expect("rigid");
        assert_eq!(transforms.len(), 2);
        for t in &transforms {
            let r = t.fixed_view::<3, 3>(0, 0);
            assert!((r * r.transpose() - nalgebra::Matrix3::identity()).amax() < 1e-12);
            assert!((r.determinant() - 1.0).abs() < 1e-12);
            assert_eq!(t.row(3), Matrix4::<f64>::identity().row(3));
        }
        let (input, truth) = (pair.input(), pair.truth());
        for ((p, f), &k) in
            input.p.points.iter().zip(truth.flow.as_ref().expect("a flow")).zip(&truth.part_p)
        {
            let p64 = p.coords.cast::<f64>();
            let moved = transforms[usize::from(k)] * Vector4::new(p64.x, p64.y, p64.z, 1.0);
            let expected = (p.coords + f).cast::<f64>() * a + b;
            assert!((moved.xyz() - expected).amax() < 1e-5, "angle {angle}");
        }
    }
}

#[test]
fn mbs_npz_files_hold_both_views_segments_and_motions() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (dataset, out) = (dir.path().join("data"), dir.path().join("out"));
    let pairs = hinges(&[4, 5]);
    write_dataset(&dataset, &pairs, "validation");
    let summary = export_dataset(Format::MbsNpz, &dataset, &out, false, |_| {}).expect("export");
    assert_eq!((summary.pairs, summary.files), (2, 4));
    let written = files(&out);
    let names: Vec<_> = written.keys().map(String::as_str).collect();
    assert_eq!(names, ["data/000000.npz", "data/000001.npz", "ids.txt", "meta.json"]);
    assert_eq!(written["meta.json"], b"{\"train\": [], \"val\": [0,1], \"test\": []}\n");
    assert_eq!(written["ids.txt"], b"hinge-0\nhinge-1\n");
    let entries = unzip(&written["data/000001.npz"]);
    assert_eq!(entries.keys().collect::<Vec<_>>(), ["pc.npy", "segm.npy", "trans.npy"]);
    let pair = &pairs[1];
    let n = pair.input().p.len();
    let pc = &entries["pc.npy"];
    let h = npy::header("<f4", &[2, n, 3]);
    assert_eq!(pc[..h.len()], h[..]);
    let value = |at: usize| {
        f32::from_le_bytes(pc[h.len() + 4 * at..h.len() + 4 * (at + 1)].try_into().expect("4"))
    };
    let (a, b) = mbs::q_to_common(pair);
    for i in 0..n {
        for c in 0..3 {
            assert_eq!(value(3 * i + c), pair.input().p.points[i][c]);
            let q = f64::from(pair.input().q.points[i][c]) * a + b[c];
            assert_eq!(value(3 * (n + i) + c), q as f32);
        }
    }
    let segm = &entries["segm.npy"];
    let h = npy::header("<i8", &[2, n]).len();
    assert_eq!(segm.len(), h + 8 * 2 * n);
    let segm_at =
        |at: usize| i64::from_le_bytes(segm[h + 8 * at..h + 8 * (at + 1)].try_into().expect("8"));
    for i in 0..n {
        assert_eq!(segm_at(i), i64::from(pair.truth().part_p[i]) + 1);
        assert_eq!(segm_at(n + i), i64::from(pair.truth().part_q[i]) + 1);
    }
    let trans = &entries["trans.npy"];
    let h = npy::header("|O", &[]);
    assert_eq!(trans[..h.len()], h[..]);
    assert!(trans[h.len()..].starts_with(&[0x80, 2]) && trans.ends_with(b"."));
}

#[test]
fn mbs_npz_refuses_views_of_different_sizes() {
    let (input, mut truth, provenance) = synthetic::hinge_pair("short-q", 4, 0.5).into_parts();
    let PairInput { id, kind, p, mut q } = input;
    q.points.pop();
    truth.part_q.pop();
    let last = truth.corr_mask.len() - 1;
    truth.corr_mask[last] = false;
    truth.corr_index[last] = -1;
    let pair = Pair::new(PairInput { id, kind, p, q }, truth, provenance).expect("valid pair");
    let err = mbs::npz(&pair).unwrap_err().to_string();
    assert_eq!(
        err,
        "pair short-q: P has 32 points and Q 31; mbs-npz needs one point count for both views"
    );
}

#[test]
fn mbs_npz_needs_the_split() {
    let dir = tempfile::tempdir().expect("temp dir");
    let dataset = dir.path().join("data");
    let mut writer = DatasetWriter::create(&dataset, false).expect("create");
    writer.write(&hinges(&[4])[0]).expect("write");
    let mut no_split = origin("test");
    no_split.config = serde_json::json!({ "points": 32 });
    writer.finish(no_split).expect("finish");
    let out = dir.path().join("out");
    let err = export_dataset(Format::MbsNpz, &dataset, &out, false, |_| {}).unwrap_err();
    assert!(err.to_string().contains("manifest.json: config.split is None"), "{err}");
    // yi-mat does not need it.
    export_dataset(Format::YiMat, &dataset, &out, false, |_| {}).expect("yi-mat");
}

#[test]
fn a_folder_that_is_not_a_dataset_is_a_clear_error() {
    let dir = tempfile::tempdir().expect("temp dir");
    let not_a_dataset = dir.path().join("empty");
    std::fs::create_dir(&not_a_dataset).expect("mkdir");
    let out = dir.path().join("out");
    for format in Format::ALL {
        let err = export_dataset(format, &not_a_dataset, &out, false, |_| {}).unwrap_err();
        assert!(
            matches!(err, FormatError::Dataset(DatasetError::MissingManifest { .. })),
            "{err:?}"
        );
        assert!(err.to_string().contains("no manifest.json (not a dataset"), "{err}");
        assert!(!out.exists());
    }
}

#[test]
fn exports_are_deterministic_and_refuse_a_non_empty_folder() {
    let dir = tempfile::tempdir().expect("temp dir");
    let dataset = dir.path().join("data");
    write_dataset(&dataset, &hinges(&[4, 4]), "train");
    for format in Format::ALL {
        let (one, two) =
            (dir.path().join(format!("{format}-1")), dir.path().join(format!("{format}-2")));
        export_dataset(format, &dataset, &one, false, |_| {}).expect("first");
        export_dataset(format, &dataset, &two, false, |_| {}).expect("second");
        let first = files(&one);
        assert_eq!(first, files(&two), "{format}");
        // Without force a non-empty folder is refused and left as it was.
        let err = export_dataset(format, &dataset, &one, false, |_| {}).unwrap_err();
        assert!(matches!(err, FormatError::Output(OutputError::NotEmpty { .. })), "{err:?}");
        assert_eq!(files(&one), first);
        export_dataset(format, &dataset, &one, true, |_| {}).expect("forced");
        assert_eq!(files(&one), first);
    }
    // The dataset folder itself is never an output folder.
    let err = export_dataset(Format::YiMat, &dataset, &dataset, true, |_| {}).unwrap_err();
    assert!(matches!(err, FormatError::OutputHoldsDataset { .. }), "{err:?}");
    assert!(dataset.join("manifest.json").is_file());
}
