"""The reader against the Rust reader's view of the same files, and its refusals."""

from __future__ import annotations

import hashlib
import json
import shutil
import struct
from pathlib import Path
from typing import Any, Callable, Dict, Optional

import cbor2
import numpy as np
import pytest
from mcap.records import Channel, Message
from mcap.stream_reader import StreamReader
from mcap.writer import CompressionType, Writer

from part_induction import DatasetError, Pair, open_dataset
from part_induction.dataset import collate_numpy, subsample_pair


def assert_floats(rust: Any, python: np.ndarray, what: str) -> None:
    """Rust writes its f32 values exactly, so they must be equal after a cast to f32."""
    np.testing.assert_array_equal(np.asarray(rust, np.float32), python, err_msg=what)


def assert_same_pair(rust: Dict[str, Any], pair: Pair) -> None:
    what = rust["id"]
    assert pair.id == rust["id"]
    assert pair.kind == rust["kind"]
    for side in ("p", "q"):
        assert_floats(rust[side]["points"], getattr(pair, side), f"{what} {side}")
        assert_floats(rust[side]["centre"], getattr(pair, f"{side}_centre"), f"{what} centre")
        assert np.float32(rust[side]["scale"]) == getattr(pair, f"{side}_scale")
    assert pair.p.dtype == pair.q.dtype == np.float32 and pair.p.shape[1] == 3
    assert pair.num_parts == rust["num_parts"]
    for field in ("part_p", "part_q"):
        assert getattr(pair, field).dtype == np.uint8
        np.testing.assert_array_equal(getattr(pair, field), rust[field], err_msg=field)
    assert np.float32(rust["scale"]) == pair.scale == pair.motions.scale
    assert pair.motions.rotations.shape == (pair.num_parts, 3, 3)
    assert_floats(rust["rotations"], pair.motions.rotations, f"{what} rotations")
    assert_floats(rust["translations"], pair.motions.translations, f"{what} translations")
    if rust["flow"] is None:
        assert pair.flow is None, f"{what}: a flow where Rust reads none"
    else:
        assert_floats(rust["flow"], pair.flow, f"{what} flow")
    assert pair.corr_mask.dtype == bool and pair.corr_index.dtype == np.int32
    np.testing.assert_array_equal(pair.corr_mask, rust["corr_mask"])
    np.testing.assert_array_equal(pair.corr_index, rust["corr_index"])
    assert len(pair.joints) == len(rust["joints"])
    for joint, expected in zip(pair.joints, rust["joints"]):
        assert (joint.part, joint.kind) == (expected["part"], expected["kind"])
        for key in ("axis_p", "pivot_p", "axis_q", "pivot_q", "value_p", "value_q"):
            assert_floats(expected[key], getattr(joint, key), f"{what} joint {key}")
    assert pair.provenance == rust["provenance"]
    for side in ("scan_p", "scan_q"):
        scan, expected = getattr(pair, side), rust[side]
        assert (scan is None) == (expected is None), side
        if scan is None:
            continue
        for key in ("width", "height", "depth", "labels", "colour"):
            assert scan[key] == expected[key], key
        for key in ("intrinsics", "rotation", "translation", "depth_scale"):
            assert_floats(expected[key], scan[key], f"{what} {side}.{key}")


@pytest.mark.parametrize("name", ["sf2f_dir", "sp2p_dir", "xf2p_dir"])
def test_every_field_matches_the_rust_reader(
    name: str, request: pytest.FixtureRequest, rust_dump: Callable[[Path], Any]
) -> None:
    folder: Path = request.getfixturevalue(name)
    rust = rust_dump(folder)
    dataset = open_dataset(folder)
    pairs = list(dataset)
    assert len(pairs) == len(rust) == len(dataset) > 0
    for expected, pair in zip(rust, pairs):
        assert_same_pair(expected, pair)
    scanned = [p for p in pairs if p.scan_q is not None]
    assert len(scanned) == (0 if name == "sf2f_dir" else len(pairs))


def test_a_cross_instance_pair_has_no_flow_and_two_seeds(xf2p_dir: Path) -> None:
    pairs = list(open_dataset(xf2p_dir))
    assert pairs and all(p.kind == "XF2P" for p in pairs)
    for pair in pairs:
        assert pair.flow is None
        assert not pair.corr_mask.any() and (pair.corr_index == -1).all()
        assert pair.provenance["seed_q"] != pair.provenance["seed"]
    batch = collate_numpy(pairs[:3])
    assert batch["flow"] is None and batch["p"].shape == (3, 64, 3)
    small = subsample_pair(pairs[0], 32, np.random.default_rng(0))
    assert small.flow is None and len(small.p) == 32


def test_a_batch_mixing_cross_instance_and_single_object_pairs_is_refused(
    sf2f_dir: Path, xf2p_dir: Path
) -> None:
    mixed = [next(iter(open_dataset(sf2f_dir))), next(iter(open_dataset(xf2p_dir)))]
    with pytest.raises(ValueError, match="no flow"):
        collate_numpy(mixed)


def test_the_ground_truth_is_consistent(sp2p_dir: Path) -> None:
    for pair in open_dataset(sp2p_dir):
        moved = pair.motions.apply(pair.p, pair.part_p)
        assert np.abs(pair.p + pair.flow - moved).max() < 1e-4
        hit = pair.corr_mask
        assert (pair.part_q[pair.corr_index[hit]] == pair.part_p[hit]).all()
        assert pair.num_parts == len(pair.motions) == int(pair.part_p.max()) + 1


def test_manifest_hash_and_input(sf2f_dir: Path) -> None:
    dataset = open_dataset(sf2f_dir)
    digest = hashlib.sha256((sf2f_dir / "pairs.mcap").read_bytes()).hexdigest()
    assert dataset.content_hash == digest
    assert dataset.manifest["counts"]["pairs"] == len(dataset) == 15
    assert dataset.path == sf2f_dir
    dataset.verify()
    first = next(iter(dataset))
    seen = first.input()
    assert (seen.id, seen.kind) == (first.id, "SF2F")
    np.testing.assert_array_equal(seen.p, first.p)
    np.testing.assert_array_equal(seen.q, first.q)
    assert not hasattr(seen, "flow")
    assert [x.id for x in dataset.inputs()] == [x.id for x in dataset]


def test_arrays_are_writable_copies(sf2f_dir: Path) -> None:
    pair = next(iter(open_dataset(sf2f_dir)))
    for field in ("p", "q", "part_p", "flow", "corr_index"):
        assert getattr(pair, field).flags.writeable, field


def png_size(data: bytes) -> tuple:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def test_images_of_scanned_sides(sp2p_dir: Path) -> None:
    pair = next(iter(open_dataset(sp2p_dir, images="bytes")))
    for side in ("p", "q"):
        scan, images = getattr(pair, f"scan_{side}"), getattr(pair, f"images_{side}")
        assert set(images) == {"depth", "labels", "colour"}
        for kind, data in images.items():
            assert data == (sp2p_dir / scan[kind]).read_bytes()
            assert png_size(data) == (scan["width"], scan["height"])
    assert next(iter(open_dataset(sp2p_dir))).images_q is None


def test_images_as_arrays(sp2p_dir: Path) -> None:
    pytest.importorskip("PIL", reason="Pillow is not installed (pip install pillow)")
    pair = next(iter(open_dataset(sp2p_dir, images=True)))
    w, h = pair.scan_q["width"], pair.scan_q["height"]
    assert pair.images_q["depth"].shape == (h, w) and pair.images_q["depth"].dtype == np.uint16
    assert pair.images_q["labels"].shape == (h, w)
    assert pair.images_q["colour"].shape == (h, w, 3)
    # Labels are part id + 1 on the object, 0 on the background.
    assert pair.images_q["labels"].max() <= pair.num_parts


def copy_dataset(src: Path, dst: Path) -> Path:
    shutil.copytree(src, dst)
    return dst


def rewrite_pairs(
    folder: Path,
    edit: Optional[Callable[[int, Dict[str, Any]], Dict[str, Any]]] = None,
    metadata: Optional[Dict[str, str]] = None,
) -> None:
    """Rewrites a dataset's `/pair` messages (only those), editing records or metadata."""
    path = folder / "pairs.mcap"
    with open(path, "rb") as f:
        records = list(StreamReader(f).records)
    channel = next(r for r in records if isinstance(r, Channel) and r.topic == "/pair")
    messages = [r for r in records if isinstance(r, Message) and r.channel_id == channel.id]
    with open(path, "wb") as f:
        writer = Writer(f, compression=CompressionType.ZSTD)
        writer.start()
        meta = dict(channel.metadata, **(metadata or {}))
        cid = writer.register_channel("/pair", "cbor", 0, meta)
        for i, m in enumerate(messages):
            record = cbor2.loads(m.data)
            if edit is not None:
                record = edit(i, record)
            writer.add_message(cid, m.log_time, cbor2.dumps(record), m.publish_time)
        writer.finish()


def test_a_rewritten_file_still_reads(sf2f_dir: Path, tmp_path: Path) -> None:
    # Guards the refusal tests below: their edits, not the rewriting, make the errors.
    folder = copy_dataset(sf2f_dir, tmp_path / "d")
    rewrite_pairs(folder)
    assert len(list(open_dataset(folder))) == 15


def test_wrong_schema_version_is_refused(sf2f_dir: Path, tmp_path: Path) -> None:
    folder = copy_dataset(sf2f_dir, tmp_path / "d")
    rewrite_pairs(folder, metadata={"schema_version": "3"})
    with pytest.raises(DatasetError, match=r"pairs\.mcap: wrong schema: .*version '3'"):
        list(open_dataset(folder))


def test_wrong_record_version_is_refused(sf2f_dir: Path, tmp_path: Path) -> None:
    folder = copy_dataset(sf2f_dir, tmp_path / "d")
    rewrite_pairs(folder, lambda i, r: dict(r, schema_version=3) if i == 4 else r)
    with pytest.raises(DatasetError, match=r"/pair message 4: field `schema_version`"):
        list(open_dataset(folder))


def test_disagreeing_lengths_name_the_message_and_field(sf2f_dir: Path, tmp_path: Path) -> None:
    folder = copy_dataset(sf2f_dir, tmp_path / "d")
    rewrite_pairs(folder, lambda i, r: dict(r, flow=r["flow"][:-12]) if i == 3 else r)
    reader = iter(open_dataset(folder))
    for _ in range(3):
        next(reader)  # the pairs before the broken one still come
    with pytest.raises(DatasetError) as err:
        next(reader)
    message = str(err.value)
    assert "pairs.mcap: /pair message 3 (pair 'sf2f-" in message
    assert "field `flow`: has 95 entries, expected 96" in message


@pytest.mark.parametrize(
    "edit, field",
    [
        (lambda r: dict(r, part_q=r["part_q"][:-1]), "part_q"),
        (lambda r: dict(r, corr_index=r["corr_index"][:-2]), "corr_index"),
        (lambda r: dict(r, motions=r["motions"][:-1]), "motions"),
        (lambda r: dict(r, part_p=bytes([9]) + r["part_p"][1:]), "part_p"),
        (lambda r: dict(r, flow=struct.pack("<f", float("nan")) + r["flow"][4:]), "flow"),
        (lambda r: dict(r, p=dict(r["p"], points=r["p"]["points"][:-4])), "p.points"),
        (lambda r: {k: v for k, v in r.items() if k != "provenance"}, "provenance"),
        (lambda r: {k: v for k, v in r.items() if k != "flow"}, "flow"),
        (lambda r: dict(r, kind="XF2F"), "flow"),
    ],
)
def test_broken_fields_are_named(sf2f_dir: Path, tmp_path: Path, edit: Any, field: str) -> None:
    folder = copy_dataset(sf2f_dir, tmp_path / "d")
    rewrite_pairs(folder, lambda i, r: edit(r) if i == 0 else r)
    with pytest.raises(DatasetError, match=rf"/pair message 0 .*field `{field}`"):
        list(open_dataset(folder))


def test_a_truncated_file_is_refused(sf2f_dir: Path, tmp_path: Path) -> None:
    folder = copy_dataset(sf2f_dir, tmp_path / "d")
    path = folder / "pairs.mcap"
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    with pytest.raises(DatasetError, match=r"pairs\.mcap: not a readable MCAP file after"):
        list(open_dataset(folder))


def test_a_corrupt_chunk_is_refused(sf2f_dir: Path, tmp_path: Path) -> None:
    folder = copy_dataset(sf2f_dir, tmp_path / "d")
    path = folder / "pairs.mcap"
    data = bytearray(path.read_bytes())
    data[len(data) // 3 : len(data) // 3 + 8] = b"\x00" * 8
    path.write_bytes(bytes(data))
    with pytest.raises(DatasetError, match=r"pairs\.mcap: not a readable MCAP file after"):
        list(open_dataset(folder))


def test_fewer_pairs_than_the_manifest_is_refused(sf2f_dir: Path, tmp_path: Path) -> None:
    folder = copy_dataset(sf2f_dir, tmp_path / "d")
    manifest = json.loads((folder / "manifest.json").read_text())
    manifest["counts"]["pairs"] = 16
    (folder / "manifest.json").write_text(json.dumps(manifest))
    with pytest.raises(DatasetError, match="holds 15 pairs but the manifest announces 16"):
        list(open_dataset(folder))
    with pytest.raises(DatasetError, match="pairs.mcap: size or sha256 differs"):
        rewrite_pairs(folder)
        open_dataset(folder).verify()


def test_a_folder_without_manifest_is_not_a_dataset(tmp_path: Path) -> None:
    with pytest.raises(DatasetError, match="no manifest.json"):
        open_dataset(tmp_path)
    (tmp_path / "manifest.json").write_text(json.dumps({"format": "x", "format_version": 1}))
    with pytest.raises(DatasetError, match="invalid manifest: format 'x'"):
        open_dataset(tmp_path)
