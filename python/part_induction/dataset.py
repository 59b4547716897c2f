"""Reading dataset folders: ``manifest.json`` and the ``/pair`` records of ``pairs.mcap``.

The format is docs/FORMAT.md ("Dataset format"). Pairs stream from one forward pass over
``pairs.mcap`` (a dataset never has to fit in memory), in file order, each decoded into a
:class:`Pair` of plain numpy arrays. Every array of a pair is its own writable copy.

Frames and units, as in the format: every cloud is normalised on its own,
``normalised = (object - centre) / scale`` (bounding box centred at the origin, diagonal 1);
P is the source, Q the target; motions, flow and correspondences map P's normalised frame to
Q's normalised frame.
"""

from __future__ import annotations

import hashlib
import io
import json
import os
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Dict, Iterator, List, NoReturn, Optional, Sequence, Tuple, Union

import cbor2
import numpy as np
from mcap.records import Channel, Message
from mcap.stream_reader import StreamReader

PAIRS_FILE = "pairs.mcap"
MANIFEST_FILE = "manifest.json"
DATASET_FORMAT = "part-induction-dataset"
DATASET_FORMAT_VERSION = 1
PAIR_TOPIC = "/pair"
PAIR_ENCODING = "cbor"
PAIR_SCHEMA = "part_induction.Pair"
PAIR_SCHEMA_VERSION = 2
"""Record layout written by the generator; readers accept 1 to this."""
OLDEST_PAIR_SCHEMA_VERSION = 1
KINDS = ("SF2F", "SF2P", "SP2P", "XF2F", "XF2P")
#: Kinds whose P and Q are two different objects of one category: no flow, no correspondences.
CROSS_INSTANCE_KINDS = ("XF2F", "XF2P")
IMAGE_KINDS = ("depth", "labels", "colour")

PathLike = Union[str, "os.PathLike[str]"]
# Scan images: PNG bytes, or decoded arrays when Pillow is there and asked for.
Image = Union[bytes, np.ndarray]


class DatasetError(Exception):
    """A dataset folder or its ``pairs.mcap`` breaks the format; the message names the file
    and, for a pair, the zero-based ``/pair`` message index and the field."""


@dataclass
class Motions:
    """The ground-truth motion of every part: part ``k`` maps a point ``x`` of P's normalised
    frame to ``scale * rotations[k] @ x + translations[k]`` in Q's normalised frame.

    Attributes
    ----------
    rotations : np.ndarray
        float32, shape [K, 3, 3]: rotation matrices.
    translations : np.ndarray
        float32, shape [K, 3]: translations, Q's normalised units.
    scale : float
        The scale shared by all parts (P's ``scale`` / Q's ``scale``).
    """

    rotations: np.ndarray
    translations: np.ndarray
    scale: float

    def __len__(self) -> int:
        return len(self.rotations)

    def apply(self, points: np.ndarray, parts: np.ndarray) -> np.ndarray:
        """Moves each point by its part's motion.

        Parameters
        ----------
        points : np.ndarray
            float, shape [N, 3], P's normalised frame.
        parts : np.ndarray
            integer, shape [N]: the part of each point, below K.

        Returns
        -------
        np.ndarray
            float32, shape [N, 3]: the moved points, Q's normalised frame.
        """
        r = self.rotations[parts]
        moved = self.scale * np.einsum("nij,nj->ni", r, points) + self.translations[parts]
        return moved.astype(np.float32)


@dataclass
class Joint:
    """The ground-truth joint that moves one part, seen in both clouds.

    Attributes
    ----------
    part : int
        The part it moves (>= 1).
    kind : str
        ``"revolute"`` or ``"prismatic"``.
    axis_p, pivot_p : np.ndarray
        float32, shape [3]: unit axis and a point on it, P's normalised frame.
    axis_q, pivot_q : np.ndarray
        float32, shape [3]: the same in Q's normalised frame.
    value_p, value_q : float
        Joint values in P's and Q's states: radians (revolute) or object units (prismatic).
    """

    part: int
    kind: str
    axis_p: np.ndarray
    pivot_p: np.ndarray
    axis_q: np.ndarray
    pivot_q: np.ndarray
    value_p: float
    value_q: float


@dataclass
class PairInput:
    """What a method may see of a pair: its id, kind and two clouds, no ground truth.

    Attributes
    ----------
    id : str
        The pair's id.
    kind : str
        ``"SF2F"``, ``"SF2P"`` or ``"SP2P"``.
    p : np.ndarray
        float32, shape [N_p, 3]: the source cloud, P's normalised frame.
    q : np.ndarray
        float32, shape [N_q, 3]: the target cloud, Q's normalised frame.
    """

    id: str
    kind: str
    p: np.ndarray
    q: np.ndarray


@dataclass
class Pair:
    """One pair with its ground truth, as the ``/pair`` record holds it.

    Attributes
    ----------
    id : str
        Unique pair id, e.g. ``sf2f-00012-3``.
    kind : str
        ``"SF2F"``, ``"SF2P"`` or ``"SP2P"``.
    p, q : np.ndarray
        float32, shapes [N_p, 3] and [N_q, 3]: source and target clouds, each in its own
        normalised frame.
    p_centre, q_centre : np.ndarray
        float32, shape [3]: each cloud's bounding-box centre, object frame.
    p_scale, q_scale : float
        Each cloud's bounding-box diagonal, object units (> 0).
    part_p, part_q : np.ndarray
        uint8, shapes [N_p] and [N_q]: part id of each point (part ``k`` of P is part ``k`` of
        Q; part 0 holds the root link).
    num_parts : int
        K, base included.
    scale : float
        The scale shared by all part motions.
    motions : Motions
        K part motions, P's normalised frame to Q's.
    flow : np.ndarray or None
        float32, shape [N_p, 3]: ``motions[part_p[i]](p_i) - p_i``, Q's normalised units;
        None for a cross-instance pair (``XF2F``, ``XF2P``: P and Q are two different objects
        of one category, and no flow is defined between two shapes).
    corr_mask : np.ndarray
        bool, shape [N_p]: whether each moved point of P is present in Q (all False for a
        cross-instance pair).
    corr_index : np.ndarray
        int32, shape [N_p]: index of the nearest point of Q of the same part to the moved
        point, -1 where ``corr_mask`` is False.
    joints : list of Joint
        One per joint that moves a part.
    provenance : dict
        ``category``, ``object_id``, ``articulation_p``, ``articulation_q``, ``seed``,
        ``generator_version``; ``seed_q`` for a cross-instance pair (Q's object is object
        ``object_id`` of the dataset's config under that seed); from schema version 2 also ``joints_p`` and ``joints_q``
        (every joint of the object by name -> its value in P's / Q's state, radians or
        object units) and ``pose_p`` and ``pose_q`` (``{"rotation": 9 floats row-major,
        "translation": 3 floats}``: the object's rest frame, the exported URDF's ``base``
        frame, into the posed object frame that the cloud's centre and scale normalise).
    scan_p, scan_q : dict or None
        The camera of a scanned side (``scan_p`` for SP2P, ``scan_q`` for SF2P and SP2P),
        else None: ``width``, ``height`` (int, pixels), ``intrinsics`` (float32 [4],
        ``fx, fy, cx, cy`` in pixels), ``rotation`` (float32 [3, 3]) and ``translation``
        (float32 [3]) of the camera-to-object transform (object frame, before
        normalisation), ``depth_scale`` (float, object units per depth-PNG unit) and the
        PNG paths ``depth``, ``labels``, ``colour`` relative to the dataset folder.
    images_p, images_q : dict or None
        Only when the dataset was read with ``images``: for a scanned side, ``depth``,
        ``labels`` and ``colour`` as PNG bytes, or as arrays (uint16 [H, W], uint8 [H, W],
        uint8 [H, W, 3]) when decoded with Pillow; None for a full side.
    """

    id: str
    kind: str
    p: np.ndarray
    q: np.ndarray
    p_centre: np.ndarray
    p_scale: float
    q_centre: np.ndarray
    q_scale: float
    part_p: np.ndarray
    part_q: np.ndarray
    num_parts: int
    scale: float
    motions: Motions
    flow: Optional[np.ndarray]
    corr_mask: np.ndarray
    corr_index: np.ndarray
    joints: List[Joint]
    provenance: Dict[str, Any]
    scan_p: Optional[Dict[str, Any]] = None
    scan_q: Optional[Dict[str, Any]] = None
    images_p: Optional[Dict[str, Image]] = None
    images_q: Optional[Dict[str, Image]] = None

    def input(self) -> PairInput:
        """The pair as a method sees it: id, kind, P and Q, no ground truth."""
        return PairInput(self.id, self.kind, self.p, self.q)


class _Folder:
    """What a pair dataset and a set dataset folder share: the manifest's checksums and the
    scans' images."""

    path: Path
    manifest: Dict[str, Any]

    def verify(self) -> None:
        """Checks every file's size and sha256 against the manifest.

        Raises
        ------
        DatasetError
            Naming the first file that differs or is missing.
        """
        for name, entry in self.manifest["files"].items():
            path = self.path / name
            try:
                size = path.stat().st_size
                digest = hashlib.sha256()
                with open(path, "rb") as f:
                    for block in iter(lambda: f.read(1 << 20), b""):
                        digest.update(block)
            except OSError as e:
                raise DatasetError(f"{path}: {e}") from e
            if size != entry["bytes"] or digest.hexdigest() != entry["sha256"].lower():
                raise DatasetError(
                    f"{path}: size or sha256 differs from the manifest "
                    "(the file changed after the manifest was written)"
                )

    def _read_images(
        self, scan: Optional[Dict[str, Any]], decode: Any
    ) -> Optional[Dict[str, Image]]:
        if scan is None:
            return None
        out: Dict[str, Image] = {}
        for kind in IMAGE_KINDS:
            relative = Path(scan[kind])
            if relative.is_absolute() or ".." in relative.parts:
                raise DatasetError(f"{self.path}: image path {scan[kind]!r} leaves the folder")
            path = self.path / relative
            try:
                out[kind] = decode(path.read_bytes())
            except OSError as e:
                raise DatasetError(f"{path}: {e}") from e
        return out


class Dataset(_Folder):
    """A dataset folder opened for reading; iterate it for its pairs, in file order.

    Attributes
    ----------
    path : Path
        The dataset folder.
    manifest : dict
        ``manifest.json`` as parsed JSON.
    content_hash : str
        The sha256 of ``pairs.mcap`` listed in the manifest (lowercase hex): the id a
        prediction file names its dataset by.
    """

    def __init__(self, path: PathLike, images: Union[bool, str] = False) -> None:
        self.path = Path(path)
        self.manifest = _read_manifest(self.path)
        self.content_hash: str = self.manifest["files"][PAIRS_FILE]["sha256"].lower()
        self._images = images

    def __len__(self) -> int:
        return int(self.manifest["counts"]["pairs"])

    def __iter__(self) -> Iterator[Pair]:
        return self.pairs(images=self._images)

    def __repr__(self) -> str:
        return f"Dataset({str(self.path)!r}, {len(self)} pairs)"

    def pairs(self, images: Union[bool, str] = False) -> Iterator[Pair]:
        """Streams the pairs in file order, one forward pass over ``pairs.mcap``.

        Parameters
        ----------
        images : bool or {"bytes", "arrays"}
            Also read each scanned side's PNGs into ``images_p`` / ``images_q``: ``"bytes"``
            gives the PNG bytes, ``"arrays"`` decodes them with Pillow (an ImportError
            without it), True decodes when Pillow is installed and gives bytes otherwise.

        Raises
        ------
        DatasetError
            On a wrong schema, a truncated or corrupt file, a pair that breaks the format
            (naming the file, the ``/pair`` message index and the field), or fewer pairs
            than the manifest announces.
        """
        decode = _image_decoder(images)
        path = self.path / PAIRS_FILE
        count = 0
        for index, record in iter_records(path):
            pair = decode_pair(record, f"{path}: {PAIR_TOPIC} message {index}")
            if decode is not None:
                pair.images_p = self._read_images(pair.scan_p, decode)
                pair.images_q = self._read_images(pair.scan_q, decode)
            count += 1
            yield pair
        if count != len(self):
            raise DatasetError(
                f"{path}: holds {count} pairs but the manifest announces {len(self)} "
                "(truncated?)"
            )

    def inputs(self) -> Iterator[PairInput]:
        """Streams what a method may see of each pair (no ground truth), in file order."""
        for pair in self.pairs():
            yield pair.input()

def open_dataset(path: PathLike, *, images: Union[bool, str] = False) -> Dataset:
    """Opens a dataset folder (``pairs.mcap``, ``manifest.json``, ...) for reading.

    Parameters
    ----------
    path : str or os.PathLike
        The dataset folder, e.g. ``datasets/sf2f``.
    images : bool or {"bytes", "arrays"}
        What iterating the dataset does with scan images; see :meth:`Dataset.pairs`.

    Raises
    ------
    DatasetError
        When the folder has no ``manifest.json`` (not a dataset, or its generation did not
        finish) or the manifest is of another format or version.
    """
    return Dataset(path, images=images)


def iter_records(path: PathLike) -> Iterator[Tuple[int, Dict[str, Any]]]:
    """Streams the raw ``/pair`` CBOR maps of a ``pairs.mcap`` file in file order, with their
    zero-based message index; checks the channel's schema and the chunks' CRCs.

    Raises
    ------
    DatasetError
        On a wrong schema, a truncated or corrupt file, or a message that is not CBOR.
    """
    for index, data in iter_messages(path):
        try:
            record = cbor2.loads(data)
        except Exception as e:  # cbor2 raises several types; all mean "not our record"
            raise DatasetError(f"{path}: {PAIR_TOPIC} message {index}: not valid CBOR: {e}") from e
        if not isinstance(record, dict):
            raise DatasetError(f"{path}: {PAIR_TOPIC} message {index}: not a CBOR map")
        yield index, record


def iter_messages(path: PathLike) -> Iterator[Tuple[int, bytes]]:
    """Streams the raw bytes of the ``/pair`` messages of a ``pairs.mcap`` file in file order,
    with their zero-based index (see :func:`iter_records`)."""
    return _iter_topic(path, PAIR_TOPIC, _check_channel)


def _iter_topic(
    path: PathLike, topic: str, check: Any
) -> Iterator[Tuple[int, bytes]]:
    """The raw messages of ``topic`` in file order; ``check(path, channel)`` vets its
    channel."""
    # A linear pass, not the seeking reader: it keeps file order, needs no summary section,
    # and on a truncated file fails after the last whole chunk, which names where it broke.
    channel: Optional[int] = None
    index = 0
    with open(path, "rb") as f:
        records = iter(StreamReader(f, validate_crcs=True).records)
        while True:
            try:
                record = next(records)
            except StopIteration:
                break
            except Exception as e:  # McapError, CRCValidationError, zstd errors: a broken file
                raise DatasetError(
                    f"{path}: not a readable MCAP file after {index} {topic} messages "
                    f"(truncated or corrupt?): {type(e).__name__} {e}".rstrip()
                ) from e
            if isinstance(record, Channel) and record.topic == topic:
                check(path, record)
                channel = record.id
            elif isinstance(record, Message) and record.channel_id == channel:
                yield index, record.data
                index += 1
    if channel is None:
        raise DatasetError(f"{path}: wrong schema: no {topic} channel")


def collate_numpy(pairs: Sequence[Pair]) -> Dict[str, Any]:
    """Batches pairs into arrays with a leading batch dimension B; clouds of unequal sizes
    are padded to the largest, with zeros (``corr_index``: -1) and a False valid mask.

    Parameters
    ----------
    pairs : sequence of Pair
        The batch.

    Returns
    -------
    dict
        ``id``, ``kind``: lists of str. ``p``, ``q``: float32 [B, N_p, 3], [B, N_q, 3];
        ``p_valid``, ``q_valid``: bool [B, N_p], [B, N_q], True on real points;
        ``part_p``, ``part_q``: int64 [B, N_p], [B, N_q]; ``flow``: float32 [B, N_p, 3], or
        None for a batch of cross-instance pairs (a batch mixing the two is refused);
        ``corr_mask``: bool [B, N_p]; ``corr_index``: int64 [B, N_p];
        ``p_centre``, ``q_centre``: float32 [B, 3]; ``p_scale``, ``q_scale``, ``scale``:
        float32 [B]; ``num_parts``: int64 [B]; ``rotations``: float32 [B, K, 3, 3] (identity
        past a pair's parts), ``translations``: float32 [B, K, 3], ``part_valid``: bool
        [B, K], with K the largest part count of the batch. Frames as in :class:`Pair`;
        joints, provenance and scans are not batched (read them from the pairs).
    """
    if len(pairs) == 0:
        raise ValueError("collate_numpy: empty batch")
    out: Dict[str, Any] = {
        "id": [x.id for x in pairs],
        "kind": [x.kind for x in pairs],
    }
    out["p"], out["p_valid"] = _pad([x.p for x in pairs], 0)
    out["q"], out["q_valid"] = _pad([x.q for x in pairs], 0)
    out["part_p"], _ = _pad([x.part_p.astype(np.int64) for x in pairs], 0)
    out["part_q"], _ = _pad([x.part_q.astype(np.int64) for x in pairs], 0)
    flows = [x.flow for x in pairs]
    if all(f is None for f in flows):
        out["flow"] = None
    elif any(f is None for f in flows):
        without = next(x.id for x in pairs if x.flow is None)
        raise ValueError(
            f"collate_numpy: pair {without!r} has no flow (cross-instance) but others do; "
            "batch cross-instance pairs on their own"
        )
    else:
        out["flow"], _ = _pad(flows, 0)
    out["corr_mask"], _ = _pad([x.corr_mask for x in pairs], False)
    out["corr_index"], _ = _pad([x.corr_index.astype(np.int64) for x in pairs], -1)
    out["p_centre"] = np.stack([x.p_centre for x in pairs]).astype(np.float32)
    out["q_centre"] = np.stack([x.q_centre for x in pairs]).astype(np.float32)
    out["p_scale"] = np.array([x.p_scale for x in pairs], np.float32)
    out["q_scale"] = np.array([x.q_scale for x in pairs], np.float32)
    out["scale"] = np.array([x.scale for x in pairs], np.float32)
    out["num_parts"] = np.array([x.num_parts for x in pairs], np.int64)
    k = max(x.num_parts for x in pairs)
    rotations = np.tile(np.eye(3, dtype=np.float32), (len(pairs), k, 1, 1))
    for b, x in enumerate(pairs):
        rotations[b, : x.num_parts] = x.motions.rotations
    out["rotations"] = rotations
    out["translations"], out["part_valid"] = _pad([x.motions.translations for x in pairs], 0)
    return out


def subsample_pair(pair: Pair, points: int, rng: np.random.Generator) -> Pair:
    """The pair with each cloud resampled to ``points`` points: a random subset, or (for a
    smaller cloud) every point plus random repeats, in random order.

    The ground truth of the kept points of P is kept; ``corr_index`` is remapped to the kept
    counterpart in Q, and is -1 (``corr_mask`` False) where that point was dropped. Scans,
    joints, motions and normalisations are unchanged (the clouds' frames do not move).

    Parameters
    ----------
    pair : Pair
        The pair to resample.
    points : int
        Points per cloud after resampling (> 0).
    rng : np.random.Generator
        Draws the subsets.
    """
    take_p = _draw(len(pair.p), points, rng)
    take_q = _draw(len(pair.q), points, rng)
    position = np.full(len(pair.q), -1, np.int32)
    # Reversed, so an index drawn twice maps to its first position.
    position[take_q[::-1]] = np.arange(len(take_q) - 1, -1, -1, dtype=np.int32)
    corr_index = pair.corr_index[take_p]
    corr_index = np.where(corr_index >= 0, position[np.maximum(corr_index, 0)], -1)
    corr_index = corr_index.astype(np.int32)
    return replace(
        pair,
        p=pair.p[take_p],
        q=pair.q[take_q],
        part_p=pair.part_p[take_p],
        part_q=pair.part_q[take_q],
        flow=None if pair.flow is None else pair.flow[take_p],
        corr_mask=corr_index >= 0,
        corr_index=corr_index,
    )


def _draw(n: int, points: int, rng: np.random.Generator) -> np.ndarray:
    if n >= points:
        return rng.permutation(n)[:points]
    return rng.permutation(np.concatenate([np.arange(n), rng.integers(0, n, points - n)]))


def _pad(arrays: List[np.ndarray], fill: Any) -> Tuple[np.ndarray, np.ndarray]:
    """Stacks arrays along a new first axis, padding their first axis to the longest with
    ``fill``; returns the stack and a bool [B, N] mask of the real entries."""
    n = max(len(a) for a in arrays)
    if all(len(a) == n for a in arrays):
        return np.stack(arrays), np.ones((len(arrays), n), bool)
    first = arrays[0]
    out = np.full((len(arrays), n) + first.shape[1:], fill, first.dtype)
    valid = np.zeros((len(arrays), n), bool)
    for b, a in enumerate(arrays):
        out[b, : len(a)] = a
        valid[b, : len(a)] = True
    return out, valid


def decode_pair(record: Dict[str, Any], where: str) -> Pair:
    """Decodes and checks one ``/pair`` CBOR map.

    Checks the schema version, the kind, every array's length against N_p, N_q and K, that
    no value is NaN or infinite, part ids below K, and that ``corr_index`` is -1 exactly
    where ``corr_mask`` is 0 and otherwise names a point of Q of the same part. (Unlike the
    Rust reader it does not re-check that rotations are rotations and that the flow equals
    the motions.)

    Parameters
    ----------
    record : dict
        The decoded CBOR map.
    where : str
        Names the record in errors, e.g. ``"datasets/sf2f/pairs.mcap: /pair message 3"``.

    Raises
    ------
    DatasetError
        Naming ``where``, the pair id and the field.
    """
    c = _Checker(where)
    version = c.get(record, "schema_version", int)
    if not OLDEST_PAIR_SCHEMA_VERSION <= version <= PAIR_SCHEMA_VERSION:
        c.fail(
            "schema_version",
            f"version {version} (this reader knows {OLDEST_PAIR_SCHEMA_VERSION} "
            f"to {PAIR_SCHEMA_VERSION})",
        )
    pair_id = c.get(record, "id", str)
    c.where = f"{where} (pair {pair_id!r})"
    kind = c.get(record, "kind", str)
    if kind not in KINDS:
        c.fail("kind", f"{kind!r} is not one of {', '.join(KINDS)}")
    p, p_centre, p_scale = c.cloud(record, "p")
    q, q_centre, q_scale = c.cloud(record, "q")
    n_p, n_q = len(p), len(q)
    k = c.get(record, "num_parts", int)
    if k < 1:
        c.fail("num_parts", f"{k} parts (must be at least 1)")
    part_p = c.array(record, "part_p", np.uint8, 1, n_p)
    part_q = c.array(record, "part_q", np.uint8, 1, n_q)
    for field, parts in (("part_p", part_p), ("part_q", part_q)):
        if parts.max() >= k:
            bad = np.flatnonzero(parts >= k)
            c.fail(field, f"entry {bad[0]} holds part {parts[bad[0]]}, but the pair has {k} parts")
    scale = c.number(record, "scale")
    motions = c.motions(record, k, scale)
    if kind in CROSS_INSTANCE_KINDS:
        if "flow" in record:
            c.fail("flow", f"present, but a {kind} pair has none (two different objects)")
        flow = None
    else:
        flow = c.array(record, "flow", np.float32, 3, n_p)
    mask = c.array(record, "corr_mask", np.uint8, 1, n_p)
    if mask.max() > 1:
        bad = np.flatnonzero(mask > 1)
        c.fail("corr_mask", f"entry {bad[0]} is {mask[bad[0]]} (must be 0 or 1)")
    corr_mask = mask.astype(bool)
    corr_index = c.array(record, "corr_index", np.int32, 1, n_p)
    c.correspondences(corr_mask, corr_index, part_p, part_q)
    joints = [c.joint(j, i) for i, j in enumerate(c.get(record, "joints", list))]
    provenance = c.get(record, "provenance", dict)
    scan_p = c.scan(record, "scan_p")
    scan_q = c.scan(record, "scan_q")
    return Pair(
        id=pair_id, kind=kind, p=p, q=q, p_centre=p_centre, p_scale=p_scale,
        q_centre=q_centre, q_scale=q_scale, part_p=part_p, part_q=part_q, num_parts=k,
        scale=scale, motions=motions, flow=flow, corr_mask=corr_mask, corr_index=corr_index,
        joints=joints, provenance=provenance, scan_p=scan_p, scan_q=scan_q,
    )


class _Checker:
    """Field readers that raise :class:`DatasetError` naming the record and the field."""

    def __init__(self, where: str) -> None:
        self.where = where

    def fail(self, field: str, reason: str) -> NoReturn:
        raise DatasetError(f"{self.where}: field `{field}`: {reason}")

    def get(self, record: Dict[str, Any], key: str, kind: Any, field: str = "") -> Any:
        field = field or key
        if key not in record:
            self.fail(field, "missing")
        value = record[key]
        # bool is an int in Python but never one in the format.
        if not isinstance(value, kind) or (kind is not bool and isinstance(value, bool)):
            expected = "number" if isinstance(kind, tuple) else kind.__name__
            self.fail(field, f"is {type(value).__name__}, expected {expected}")
        return value

    def number(self, record: Dict[str, Any], key: str, field: str = "") -> float:
        field = field or key
        value = self.get(record, key, (int, float), field)
        if not np.isfinite(value):
            self.fail(field, f"non-finite value {value}")
        return float(np.float32(value))

    def floats(self, record: Dict[str, Any], key: str, n: int, field: str = "") -> np.ndarray:
        field = field or key
        values = self.get(record, key, list, field)
        try:
            out = np.array(values, np.float32)
        except (TypeError, ValueError):
            out = None
        if out is None or out.shape != (n,):
            self.fail(field, f"expected {n} numbers, found {values!r}")
        if not np.isfinite(out).all():
            self.fail(field, "non-finite value")
        return out

    def array(
        self, record: Dict[str, Any], key: str, dtype: Any, width: int, n: Optional[int],
        field: str = "",
    ) -> np.ndarray:
        """A byte-string field as a native-endian copy of shape [n] or [n, width]."""
        field = field or key
        data = self.get(record, key, bytes, field)
        item = np.dtype(dtype).newbyteorder("<")
        size = item.itemsize * width
        if len(data) % size:
            self.fail(field, f"byte length {len(data)} is not a multiple of {size}")
        values = np.frombuffer(data, item).astype(np.dtype(dtype).newbyteorder("="))
        if width > 1:
            values = values.reshape(-1, width)
        if n is not None and len(values) != n:
            self.fail(field, f"has {len(values)} entries, expected {n}")
        if values.dtype.kind == "f" and not np.isfinite(values).all():
            bad = np.flatnonzero(~np.isfinite(values).reshape(len(values), -1).all(1))[0]
            self.fail(field, f"non-finite value at entry {bad}")
        return values

    def cloud(self, record: Dict[str, Any], key: str) -> Tuple[np.ndarray, np.ndarray, float]:
        cloud = self.get(record, key, dict)
        points = self.array(cloud, "points", np.float32, 3, None, f"{key}.points")
        if len(points) == 0:
            self.fail(f"{key}.points", "empty cloud")
        centre = self.floats(cloud, "centre", 3, f"{key}.centre")
        scale = self.number(cloud, "scale", f"{key}.scale")
        if scale <= 0:
            self.fail(f"{key}.scale", f"{scale} is not positive")
        return points, centre, scale

    def motions(self, record: Dict[str, Any], k: int, scale: float) -> Motions:
        motions = self.get(record, "motions", list)
        if len(motions) != k:
            self.fail("motions", f"has {len(motions)} entries, expected {k}")
        rotations = np.empty((k, 3, 3), np.float32)
        translations = np.empty((k, 3), np.float32)
        for i, m in enumerate(motions):
            if not isinstance(m, dict):
                self.fail(f"motions[{i}]", "not a map")
            rotations[i] = self.floats(m, "rotation", 9, f"motions[{i}].rotation").reshape(3, 3)
            translations[i] = self.floats(m, "translation", 3, f"motions[{i}].translation")
        return Motions(rotations, translations, scale)

    def correspondences(
        self, mask: np.ndarray, index: np.ndarray, part_p: np.ndarray, part_q: np.ndarray
    ) -> None:
        n_q = len(part_q)
        absent = ~mask & (index != -1)
        if absent.any():
            i = np.flatnonzero(absent)[0]
            self.fail("corr_index", f"entry {i} is {index[i]} where the mask is 0")
        outside = mask & ((index < 0) | (index >= n_q))
        if outside.any():
            i = np.flatnonzero(outside)[0]
            self.fail("corr_index", f"entry {i}: {index[i]} is not a point of Q ({n_q})")
        other = mask & (part_q[np.where(mask, index, 0)] != part_p)
        if other.any():
            i = np.flatnonzero(other)[0]
            self.fail("corr_index", f"entry {i}: Q point {index[i]} is of another part")

    def joint(self, joint: Any, i: int) -> Joint:
        f = f"joints[{i}]"
        if not isinstance(joint, dict):
            self.fail(f, "not a map")
        kind = self.get(joint, "kind", str, f"{f}.kind")
        if kind not in ("revolute", "prismatic"):
            self.fail(f"{f}.kind", f"{kind!r} is not revolute or prismatic")
        return Joint(
            part=self.get(joint, "part", int, f"{f}.part"),
            kind=kind,
            axis_p=self.floats(joint, "axis_p", 3, f"{f}.axis_p"),
            pivot_p=self.floats(joint, "pivot_p", 3, f"{f}.pivot_p"),
            axis_q=self.floats(joint, "axis_q", 3, f"{f}.axis_q"),
            pivot_q=self.floats(joint, "pivot_q", 3, f"{f}.pivot_q"),
            value_p=self.number(joint, "value_p", f"{f}.value_p"),
            value_q=self.number(joint, "value_q", f"{f}.value_q"),
        )

    def scan(self, record: Dict[str, Any], key: str) -> Optional[Dict[str, Any]]:
        scan = record.get(key)
        if scan is None:
            return None
        if not isinstance(scan, dict):
            self.fail(key, "not a map")
        out = dict(scan)
        out["width"] = self.get(scan, "width", int, f"{key}.width")
        out["height"] = self.get(scan, "height", int, f"{key}.height")
        out["intrinsics"] = self.floats(scan, "intrinsics", 4, f"{key}.intrinsics")
        out["rotation"] = self.floats(scan, "rotation", 9, f"{key}.rotation").reshape(3, 3)
        out["translation"] = self.floats(scan, "translation", 3, f"{key}.translation")
        out["depth_scale"] = self.number(scan, "depth_scale", f"{key}.depth_scale")
        for kind in IMAGE_KINDS:
            out[kind] = self.get(scan, kind, str, f"{key}.{kind}")
        return out


def _check_channel(path: PathLike, channel: Channel) -> None:
    schema = channel.metadata.get("schema")
    version = channel.metadata.get("schema_version")
    known = [str(v) for v in range(OLDEST_PAIR_SCHEMA_VERSION, PAIR_SCHEMA_VERSION + 1)]
    if (channel.message_encoding, schema) != (PAIR_ENCODING, PAIR_SCHEMA) or version not in known:
        raise DatasetError(
            f"{path}: wrong schema: {PAIR_TOPIC} has encoding {channel.message_encoding!r}, "
            f"schema {schema!r} version {version!r} (expected {PAIR_ENCODING!r}, "
            f"{PAIR_SCHEMA!r} version {OLDEST_PAIR_SCHEMA_VERSION} to {PAIR_SCHEMA_VERSION})"
        )


def _read_manifest(folder: Path, records: str = PAIRS_FILE) -> Dict[str, Any]:
    path = folder / MANIFEST_FILE
    if not path.is_file():
        raise DatasetError(
            f"{folder}: no {MANIFEST_FILE} (not a dataset, or its generation did not finish)"
        )
    try:
        manifest = json.loads(path.read_text("utf-8"))
    except (OSError, ValueError) as e:
        raise DatasetError(f"{path}: invalid manifest: {e}") from e
    fmt = (manifest.get("format"), manifest.get("format_version"))
    if fmt != (DATASET_FORMAT, DATASET_FORMAT_VERSION):
        raise DatasetError(
            f"{path}: invalid manifest: format {fmt[0]!r} version {fmt[1]!r} (this reader "
            f"knows {DATASET_FORMAT!r} version {DATASET_FORMAT_VERSION})"
        )
    files = manifest.get("files")
    if records == PAIRS_FILE and isinstance(files, dict) and "sets.mcap" in files:
        raise DatasetError(
            f"{folder} holds sets (sets.mcap), not pairs: open it with "
            "part_induction.open_set_dataset"
        )
    try:
        manifest["files"][records]["sha256"]
        int(manifest["counts"]["pairs"] if records == PAIRS_FILE else manifest["counts"].get("sets", 0))
    except (KeyError, TypeError, ValueError) as e:
        raise DatasetError(f"{path}: invalid manifest: lacks {e}") from e
    return manifest


def _image_decoder(images: Union[bool, str]) -> Any:
    """None (no images), or a function from PNG bytes to what ``images`` asks for."""
    if images is False:
        return None
    if images not in (True, "bytes", "arrays"):
        raise ValueError(f"images must be a bool, 'bytes' or 'arrays', not {images!r}")
    if images == "bytes":
        return lambda data: data
    try:
        from PIL import Image as PILImage
    except ImportError:
        if images == "arrays":
            raise
        return lambda data: data

    def decode(data: bytes) -> np.ndarray:
        with PILImage.open(io.BytesIO(data)) as image:
            array = np.asarray(image)
        # Pillow opens 16-bit grey PNGs as 32-bit "I" images on some versions.
        return array.astype(np.uint16) if array.dtype.kind == "i" else array

    return decode
