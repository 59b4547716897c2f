"""PyTorch access to a dataset: random-access ``torch.utils.data.Dataset``\ s of pairs
(:class:`PairDataset`) and of sets of K views (:class:`SetTorchDataset`) and collate
functions for ``DataLoader``. Importing this module imports torch; the rest of the
package never does.

The batching itself is :func:`part_induction.dataset.collate_numpy` (plain numpy); this module
only turns its arrays into tensors.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple

import cbor2
import numpy as np
import torch
from torch.utils.data import Dataset as _TorchDataset

from .dataset import (
    PAIR_TOPIC,
    PAIRS_FILE,
    Dataset,
    DatasetError,
    Pair,
    PathLike,
    _iter_topic,
    collate_numpy,
    decode_pair,
    iter_messages,
    subsample_pair,
)


def _record(
    raw: List[bytes], index: int, what: str, path: Any, topic: str
) -> Tuple[int, Any, str]:
    """Message ``index`` (negative from the end) of ``raw`` decoded from CBOR, with its
    index and the place errors name."""
    if index < 0:
        index += len(raw)
    if not 0 <= index < len(raw):
        raise IndexError(f"{what} {index} of a dataset of {len(raw)}")
    where = f"{path}: {topic} message {index}"
    try:
        return index, cbor2.loads(raw[index]), where
    except Exception as e:  # cbor2 raises several types; all mean "not our record"
        raise DatasetError(f"{where}: not valid CBOR: {e}") from e


def _all(messages: Any, path: Any, expected: int, what: str) -> List[bytes]:
    """Every message's bytes, checked against the number the manifest announces."""
    out = [data for _, data in messages]
    if len(out) != expected:
        raise DatasetError(
            f"{path}: holds {len(out)} {what} but the manifest announces {expected} (truncated?)"
        )
    return out


class PairDataset(_TorchDataset):
    """The pairs of a dataset folder, by index.

    On first access it reads the raw CBOR bytes of every ``/pair`` message into memory (one
    pass over ``pairs.mcap``; about 25 KB per pair of two 512-point clouds, images not
    included) and decodes one pair per ``__getitem__``. Each ``DataLoader`` worker that
    starts before the first access reads the file once for itself.

    Parameters
    ----------
    path : str or os.PathLike
        The dataset folder.
    points : int, optional
        When given, each cloud is resampled to exactly this many points (a random subset, or
        every point plus random repeats for a smaller cloud) so that batches stack; the
        ground truth is subset with it and ``corr_index`` then names the kept counterpart in
        Q, or -1 (``corr_mask`` False) where it was dropped. None keeps the clouds as they
        are (``collate_pairs`` pads unequal sizes).
    seed : int, optional
        Seeds the resampling of item ``i`` with ``(seed, i)``, so an item is the same every
        time; None draws a fresh subset on every access.

    Examples
    --------
    >>> from torch.utils.data import DataLoader
    >>> loader = DataLoader(PairDataset("datasets/sf2f"), batch_size=16, shuffle=True,
    ...                     collate_fn=collate_pairs)
    >>> batch = next(iter(loader))
    >>> batch["p"].shape
    torch.Size([16, 512, 3])
    """

    def __init__(self, path: PathLike, points: Optional[int] = None, seed: Optional[int] = 0):
        if points is not None and points < 1:
            raise ValueError(f"points must be positive, not {points}")
        self.dataset = Dataset(path)
        self.points = points
        self.seed = seed
        self._messages: Optional[List[bytes]] = None

    def __len__(self) -> int:
        return len(self.dataset)

    def __getitem__(self, index: int) -> Pair:
        path = self.dataset.path / PAIRS_FILE
        index, record, where = _record(self._raw(), index, "pair", path, PAIR_TOPIC)
        pair = decode_pair(record, where)
        if self.points is not None:
            rng = np.random.default_rng(None if self.seed is None else (self.seed, index))
            pair = subsample_pair(pair, self.points, rng)
        return pair

    def _raw(self) -> List[bytes]:
        if self._messages is None:
            path = self.dataset.path / PAIRS_FILE
            self._messages = _all(iter_messages(path), path, len(self.dataset), "pairs")
        return self._messages


def collate_pairs(batch: Sequence[Pair]) -> Dict[str, Any]:
    """``collate_fn`` for a ``DataLoader`` over :class:`PairDataset`: the arrays of
    :func:`part_induction.dataset.collate_numpy` as tensors (same keys, shapes and dtypes;
    ``id`` and ``kind`` stay lists of str)."""
    return {
        key: torch.from_numpy(value) if isinstance(value, np.ndarray) else value
        for key, value in collate_numpy(batch).items()
    }


class SetTorchDataset(_TorchDataset):
    """The sets of a set dataset folder (``generator --kind sets``), by index: the
    PyTorch counterpart of :class:`PairDataset` for K observations of one object.

    On first access it reads the raw CBOR bytes of every ``/set`` message into memory (one
    pass over ``sets.mcap``) and decodes one set per ``__getitem__``
    (:func:`part_induction.sets.decode_set`, with its checks).

    Examples
    --------
    >>> from torch.utils.data import DataLoader
    >>> loader = DataLoader(SetTorchDataset("datasets/sets-scan"), batch_size=8,
    ...                     collate_fn=collate_sets)
    >>> next(iter(loader))["points"].shape
    torch.Size([8, 4, 512, 3])
    """

    def __init__(self, path: PathLike):
        from .sets import SetDataset

        self.dataset = SetDataset(path)
        self._messages: Optional[List[bytes]] = None

    def __len__(self) -> int:
        return len(self.dataset)

    def __getitem__(self, index: int) -> Any:
        from .sets import SET_TOPIC, SETS_FILE, decode_set

        path = self.dataset.path / SETS_FILE
        _, record, where = _record(self._raw(), index, "set", path, SET_TOPIC)
        return decode_set(record, where)

    def _raw(self) -> List[bytes]:
        from .sets import SET_TOPIC, SETS_FILE, _check_set_channel

        if self._messages is None:
            path = self.dataset.path / SETS_FILE
            messages = _iter_topic(path, SET_TOPIC, _check_set_channel)
            self._messages = _all(messages, path, len(self.dataset), "sets")
        return self._messages


def collate_sets(batch: Sequence[Any]) -> Dict[str, Any]:
    """``collate_fn`` for a ``DataLoader`` over :class:`SetTorchDataset`: the arrays of
    :func:`part_induction.sets.collate_sets_numpy` as tensors (same keys, shapes and dtypes;
    ``id`` and ``kinds`` stay lists)."""
    from .sets import collate_sets_numpy

    return {
        key: torch.from_numpy(value) if isinstance(value, np.ndarray) else value
        for key, value in collate_sets_numpy(batch).items()
    }
