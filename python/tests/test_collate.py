"""Batching: collate_numpy (no torch needed), subsample_pair, and the optional torch wrapper."""

from __future__ import annotations

import subprocess
import sys
from dataclasses import replace
from pathlib import Path
from typing import List

import numpy as np
import pytest

from part_induction import Pair, collate_numpy, open_dataset
from part_induction.dataset import subsample_pair


def first_pairs(folder: Path, n: int) -> List[Pair]:
    pairs = []
    for pair in open_dataset(folder):
        pairs.append(pair)
        if len(pairs) == n:
            return pairs
    raise AssertionError(f"{folder} has fewer than {n} pairs")


def test_equal_sizes_stack(sf2f_dir: Path) -> None:
    pairs = first_pairs(sf2f_dir, 4)
    batch = collate_numpy(pairs)
    assert batch["id"] == [p.id for p in pairs]
    assert batch["kind"] == ["SF2F"] * 4
    assert batch["p"].shape == (4, 96, 3) and batch["p"].dtype == np.float32
    assert batch["p_valid"].all() and batch["q_valid"].all()
    assert batch["part_p"].dtype == np.int64 and batch["corr_index"].dtype == np.int64
    for b, pair in enumerate(pairs):
        np.testing.assert_array_equal(batch["p"][b], pair.p)
        np.testing.assert_array_equal(batch["flow"][b], pair.flow)
        np.testing.assert_array_equal(batch["corr_index"][b], pair.corr_index)
        k = pair.num_parts
        np.testing.assert_array_equal(batch["rotations"][b, :k], pair.motions.rotations)
        np.testing.assert_array_equal(batch["rotations"][b, k:], np.eye(3)[None].repeat(
            batch["rotations"].shape[1] - k, 0))
        assert batch["part_valid"][b].sum() == k == batch["num_parts"][b]
        assert batch["scale"][b] == np.float32(pair.scale)
        np.testing.assert_array_equal(batch["q_centre"][b], pair.q_centre)


def test_unequal_sizes_pad_with_a_mask(sf2f_dir: Path) -> None:
    a, b = first_pairs(sf2f_dir, 2)
    short = replace(
        b, p=b.p[:50], part_p=b.part_p[:50], flow=b.flow[:50], corr_mask=b.corr_mask[:50],
        corr_index=b.corr_index[:50], q=b.q[:70], part_q=b.part_q[:70],
    )
    batch = collate_numpy([a, short])
    assert batch["p"].shape == (2, 96, 3) and batch["q"].shape == (2, 96, 3)
    np.testing.assert_array_equal(batch["p_valid"].sum(1), [96, 50])
    np.testing.assert_array_equal(batch["q_valid"].sum(1), [96, 70])
    np.testing.assert_array_equal(batch["p"][1, :50], short.p)
    assert (batch["p"][1, 50:] == 0).all() and (batch["flow"][1, 50:] == 0).all()
    assert (batch["corr_index"][1, 50:] == -1).all() and not batch["corr_mask"][1, 50:].any()
    np.testing.assert_array_equal(batch["p"][0], a.p)


def test_subsample_keeps_the_ground_truth(sp2p_dir: Path) -> None:
    rng = np.random.default_rng(3)
    for pair in first_pairs(sp2p_dir, 3):
        for points in (40, 64, 100):
            small = subsample_pair(pair, points, rng)
            assert small.p.shape == small.q.shape == (points, 3)
            assert len(small.part_p) == len(small.flow) == len(small.corr_index) == points
            moved = small.motions.apply(small.p, small.part_p)
            assert np.abs(small.p + small.flow - moved).max() < 1e-4
            hit = small.corr_index >= 0
            np.testing.assert_array_equal(hit, small.corr_mask)
            # A kept counterpart is the same point of Q as before.
            for i in np.flatnonzero(hit)[:10]:
                j = int(np.flatnonzero((pair.p == small.p[i]).all(1))[0])
                np.testing.assert_array_equal(small.q[small.corr_index[i]],
                                              pair.q[pair.corr_index[j]])
            if points >= 64:
                assert set(map(tuple, small.p)) == set(map(tuple, pair.p))


def test_importing_the_package_does_not_import_torch() -> None:
    code = "import sys, part_induction; assert 'torch' not in sys.modules, 'torch imported'"
    python_dir = Path(__file__).resolve().parents[1]
    subprocess.run([sys.executable, "-c", code], check=True, cwd=python_dir)


def test_torch_dataset_and_collate(sf2f_dir: Path) -> None:
    torch = pytest.importorskip("torch", reason="torch is not installed (pip install torch)")
    from torch.utils.data import DataLoader

    from part_induction.torch import PairDataset, collate_pairs

    dataset = PairDataset(sf2f_dir)
    assert len(dataset) == 15
    pairs = list(open_dataset(sf2f_dir))
    assert dataset[-1].id == pairs[-1].id
    with pytest.raises(IndexError):
        dataset[15]
    loader = DataLoader(dataset, batch_size=4, shuffle=False, collate_fn=collate_pairs)
    batches = list(loader)
    assert [len(b["id"]) for b in batches] == [4, 4, 4, 3]
    first = batches[0]
    assert first["id"] == [p.id for p in pairs[:4]]
    assert first["p"].shape == (4, 96, 3) and first["p"].dtype == torch.float32
    assert first["part_p"].dtype == torch.int64 and first["p_valid"].dtype == torch.bool
    np.testing.assert_array_equal(first["flow"].numpy(), np.stack([p.flow for p in pairs[:4]]))

    resampled = PairDataset(sf2f_dir, points=32, seed=5)
    a, b = resampled[2], resampled[2]
    assert a.p.shape == (32, 3)
    np.testing.assert_array_equal(a.p, b.p)  # the same subset every time with a seed
    batch = collate_pairs([resampled[i] for i in range(3)])
    assert batch["p"].shape == (3, 32, 3) and bool(batch["p_valid"].all())
