//! The Python snippet of docs/FORMAT.md reads our files: runs it when Python with `mcap`,
//! `cbor2` and `numpy` is available, and says so when it skips.

use std::process::Command;

use pairs::dataset::{DatasetOrigin, DatasetWriter, PAIRS_FILE};
use pairs::synthetic;

/// The snippet between the `python-reader` markers of docs/FORMAT.md.
fn snippet() -> String {
    let doc = include_str!("../../docs/FORMAT.md");
    let start = doc.find("<!-- python-reader: begin -->").expect("begin marker");
    let end = doc.find("<!-- python-reader: end -->").expect("end marker");
    let block = &doc[start..end];
    let code_start = block.find("```python\n").expect("python block") + "```python\n".len();
    let code_end = block[code_start..].find("```").expect("block end") + code_start;
    block[code_start..code_end].to_string()
}

fn python_has_packages() -> bool {
    Command::new("python3")
        .args(["-c", "import mcap, cbor2, numpy"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false)
}

#[test]
fn the_documented_python_snippet_reads_a_pair() {
    if !python_has_packages() {
        eprintln!("SKIPPED: python3 with mcap, cbor2 and numpy is not available (pip install mcap cbor2 numpy)");
        return;
    }
    let dir = tempfile::tempdir().expect("tempdir");
    let pair = synthetic::hinge_pair("py-0", 5, 0.8);
    let mut writer = DatasetWriter::create(dir.path(), false).expect("create");
    writer.write(&pair).expect("write");
    writer
        .finish(DatasetOrigin {
            generator_version: "test".into(),
            seed: 0,
            config: serde_json::json!({}),
            splits: Default::default(),
            shard: None,
            assets: Vec::new(),
            left_out: Default::default(),
        })
        .expect("finish");

    let path = dir.path().join(PAIRS_FILE);
    let code = snippet().replace("datasets/sf2f/pairs.mcap", path.to_str().expect("utf-8 path"));
    // After the snippet: check what it decoded against the ground truth it carries.
    let checks = "
mask = part_p == 1
assert np.abs(p[mask] + flow[mask] - moved[mask]).max() < 1e-5
assert (corr_index == np.arange(len(p))).all()
print('first', *p[0], *q[-1])
";
    let out = Command::new("python3")
        .args(["-c", &format!("{code}{checks}")])
        .output()
        .expect("python runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "python failed: {}\n{stdout}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.starts_with("py-0 (50, 3) (50, 3) 2 hinge"), "{stdout}");
    let first: Vec<f32> = stdout
        .lines()
        .find_map(|l| l.strip_prefix("first "))
        .expect("values line")
        .split_whitespace()
        .map(|v| v.parse().expect("a float"))
        .collect();
    let (p0, q_last) = (pair.input().p.points[0], pair.input().q.points[49]);
    let expected = [p0.x, p0.y, p0.z, q_last.x, q_last.y, q_last.z];
    for (a, b) in first.iter().zip(expected) {
        assert!((a - b).abs() < 1e-6, "{first:?} vs {expected:?}");
    }
}
