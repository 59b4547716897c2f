"""The set reader against the Rust reader: every array of every set, and every pair of two
views that `Set::pair` gives, computed here by `Set.pair`."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest

from part_induction import DatasetError, open_dataset, open_set_dataset

from test_dataset import assert_floats


def test_sets_read_as_the_rust_reader_reads_them(
    sets_dir: Path, rust_dump: Callable[[Path], Any]
) -> None:
    rust = rust_dump(sets_dir)
    dataset = open_set_dataset(sets_dir, images="bytes")
    sets = list(dataset)
    assert len(sets) == len(rust) == len(dataset) == 3
    for expected, item in zip(rust, sets):
        what = expected["id"]
        assert item.id == what and item.num_parts == expected["num_parts"]
        assert len(item) == 4 and item.mode == "mixed"
        for k, (view, want) in enumerate(zip(item.views, expected["views"])):
            assert view.kind == want["kind"] == ("full" if k == 0 else "scan")
            assert_floats(want["cloud"]["points"], view.points, f"{what} view {k} points")
            assert_floats(want["cloud"]["centre"], view.centre, f"{what} view {k} centre")
            assert np.float32(want["cloud"]["scale"]) == view.scale
            np.testing.assert_array_equal(view.parts, want["parts"])
            assert np.float32(want["scale"]) == view.motions.scale
            assert_floats(want["rotations"], view.motions.rotations, f"{what} rotations")
            assert_floats(want["translations"], view.motions.translations, f"{what} t")
            assert_floats(want["flow"], view.flow, f"{what} view {k} flow")
            np.testing.assert_array_equal(view.presence, want["presence"])
            np.testing.assert_array_equal(view.pair_parts, want["pair_parts"])
            assert (view.scan is None) == (want["scan"] is None)
            if view.scan is not None:
                assert view.scan["depth"] == want["scan"]["depth"]
                assert view.images is not None and view.images["depth"][:4] == b"\x89PNG"
        assert len(item.joints) == len(expected["joints"])
        for joint, want in zip(item.joints, expected["joints"]):
            assert (joint.name, joint.part, joint.parent, joint.kind) == (
                want["name"], want["part"], want["parent"], want["kind"])
            assert_floats(want["axis"], joint.axis, f"{what} joint axis")
            assert_floats(want["value"], joint.value, f"{what} joint value")
        assert item.provenance == expected["provenance"]


def test_a_sets_pairs_are_the_rust_pairs(
    sets_dir: Path, rust_dump: Callable[[Path], Any]
) -> None:
    rust = rust_dump(sets_dir)
    checked = 0
    for expected, item in zip(rust, open_set_dataset(sets_dir)):
        assert len(expected["pairs"]) == 9  # 0 -> 1..3 and the 6 scan-to-scan pairs
        for want in expected["pairs"]:
            i, j = (int(x) for x in want["id"].rsplit("-", 2)[1:])
            pair = item.pair(i, j)
            what = want["id"]
            assert (pair.id, pair.kind, pair.num_parts) == (what, want["kind"], want["num_parts"])
            assert_floats(want["p"]["points"], pair.p, what)
            np.testing.assert_array_equal(pair.part_p, want["part_p"])
            np.testing.assert_array_equal(pair.part_q, want["part_q"])
            np.testing.assert_allclose(pair.motions.rotations, want["rotations"], atol=1e-5)
            np.testing.assert_allclose(pair.motions.translations, want["translations"], atol=1e-5)
            np.testing.assert_allclose(pair.flow, want["flow"], atol=1e-5)
            np.testing.assert_array_equal(pair.corr_mask, want["corr_mask"])
            np.testing.assert_array_equal(pair.corr_index, want["corr_index"])
            assert [(jt.part, jt.kind) for jt in pair.joints] == [
                (jt["part"], jt["kind"]) for jt in want["joints"]]
            assert pair.provenance == want["provenance"]
            checked += 1
        with pytest.raises(ValueError, match="no pair kind"):
            item.pair(1, 0)
    assert checked == 27


def test_the_pair_reader_points_to_the_set_reader(sets_dir: Path, sf2f_dir: Path) -> None:
    with pytest.raises(DatasetError, match="open_set_dataset"):
        open_dataset(sets_dir)
    with pytest.raises(DatasetError, match="sets"):
        open_set_dataset(sf2f_dir)


def test_a_truncated_set_file_is_an_error(sets_dir: Path, tmp_path: Path) -> None:
    import shutil

    broken = tmp_path / "broken"
    shutil.copytree(sets_dir, broken)
    data = (broken / "sets.mcap").read_bytes()
    (broken / "sets.mcap").write_bytes(data[: len(data) // 2])
    with pytest.raises(DatasetError, match="sets.mcap"):
        list(open_set_dataset(broken))


def test_sets_stack_into_batches(sets_dir: Path) -> None:
    from part_induction import collate_sets_numpy, open_set_dataset

    sets = list(open_set_dataset(sets_dir))
    batch = collate_sets_numpy(sets)
    k, n = len(sets[0].views), len(sets[0].views[0].points)
    assert batch["points"].shape == (len(sets), k, n, 3) and batch["points"].dtype == np.float32
    assert batch["parts"].shape == (len(sets), k, n) and batch["parts"].dtype == np.int64
    assert batch["flow"].shape == (len(sets), k, n, 3)
    for b, s in enumerate(sets):
        assert batch["id"][b] == s.id and batch["kinds"][b] == [v.kind for v in s.views]
        for view, v in enumerate(s.views):
            np.testing.assert_array_equal(batch["points"][b, view], v.points)
            np.testing.assert_array_equal(batch["parts"][b, view], v.parts)
        # View 0's flow is zero; the others move view 0's points.
        assert not batch["flow"][b, 0].any()
    assert list(batch["num_parts"]) == [s.num_parts for s in sets]
    cut = sets[0]
    cut.views[1].points = cut.views[1].points[:-1]
    with pytest.raises(ValueError, match="one K and one N"):
        collate_sets_numpy([cut])


def test_the_torch_set_dataset_reads_and_batches_sets(sets_dir: Path) -> None:
    sets = list(open_set_dataset(sets_dir))
    k, n = len(sets[0].views), len(sets[0].views[0].points)
    torch = pytest.importorskip("torch", reason="torch is not installed (pip install torch)")
    from torch.utils.data import DataLoader

    from part_induction.torch import SetTorchDataset, collate_sets

    data = SetTorchDataset(sets_dir)
    assert len(data) == len(sets) and data[-1].id == sets[-1].id
    loader = DataLoader(data, batch_size=len(sets), collate_fn=collate_sets)
    first = next(iter(loader))
    assert first["points"].shape == (len(sets), k, n, 3) and first["points"].dtype == torch.float32
    assert first["parts"].dtype == torch.int64
