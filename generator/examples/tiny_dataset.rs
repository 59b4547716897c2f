//! Writes a tiny SF2F dataset (2 objects, 10 pairs, 128 points) to a temporary folder and
//! reads it back. This should print "read back 10 pairs" and the first pair's summary.

use generator::config::GeneratorConfig;
use generator::generate::generate_dataset;
use pairs::dataset::Dataset;

fn main() -> anyhow::Result<()> {
    let dir = tempfile::tempdir()?;
    let config = GeneratorConfig { objects: 2, points: 128, ..Default::default() };
    let manifest = generate_dataset(&config, dir.path(), false, None, |_| {})?;
    println!("wrote {} pairs to {}", manifest.counts.pairs, dir.path().display());
    let dataset = Dataset::open(dir.path())?;
    dataset.verify()?;
    let pairs: Vec<_> = dataset.pairs()?.collect::<Result<_, _>>()?;
    println!("read back {} pairs", pairs.len());
    let first = &pairs[0];
    println!(
        "{}: {} with {} parts, joints {:?}",
        first.id(),
        first.provenance().category,
        first.truth().num_parts(),
        first.truth().joints.iter().map(|j| j.kind.as_str()).collect::<Vec<_>>()
    );
    Ok(())
}
