"""Writing and reading prediction files (docs/FORMAT.md, "Prediction files").

A method written in any language goes on the leaderboards by writing one prediction file for
a dataset and handing it to ``evaluator score``. :class:`PredictionWriter` writes one and
refuses, at the call that passes it, any array of the wrong dtype, shape or with a NaN;
:func:`read_predictions` reads one back.

Frames and units: ``flow`` and ``motions`` map P's normalised frame to Q's normalised frame
(Q's normalised units), as the dataset's ground truth does; joints are in P's normalised
frame.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Type, Union

import cbor2
import numpy as np
from mcap.records import Channel, Message
from mcap.stream_reader import StreamReader
from mcap.writer import CompressionType, Writer

from .dataset import Dataset, PathLike
from .sets import SetDataset

FORMAT = "part-induction-predictions"
FORMAT_VERSION = 1
HEADER_TOPIC = "/header"
PREDICTION_TOPIC = "/prediction"
HEADER_SCHEMA = "part_induction.PredictionHeader"
PREDICTION_SCHEMA = "part_induction.Prediction"
SCHEMA_VERSION = 1
ENCODING = "cbor"
JOINT_KINDS = ("revolute", "prismatic")
# How far R^T R may stray from the identity (the Rust reader's tolerance).
ROTATION_TOLERANCE = 1e-3


class PredictionError(ValueError):
    """A prediction that breaks the format (at write time), or a prediction file that cannot
    be read; the message names the pair or the file."""


@dataclass
class PredictedJoint:
    """The joint a method predicts for one segment.

    Attributes
    ----------
    kind : str
        ``"revolute"`` or ``"prismatic"``.
    axis : array-like
        float, shape [3]: the axis direction, P's normalised frame (any non-zero length;
        the writer stores it normalised).
    pivot : array-like
        float, shape [3]: a point on the axis, P's normalised frame (any point for a
        prismatic joint).
    value : float
        The state change from P to Q: radians, or P's normalised units.
    """

    kind: str
    axis: Any
    pivot: Any
    value: float


# What `motions=` takes: (rotations [S,3,3], translations [S,3]) with an optional scales
# [S] (or one shared scale), or any object with `rotations`, `translations` and `scale`
# attributes, such as a pair's ground-truth `Motions`.
MotionsLike = Any
JointLike = Union[PredictedJoint, Mapping[str, Any], None]


class PredictionWriter:
    """Writes a prediction file for one dataset; use it as a context manager.

    The file is written under ``path + ".partial"`` and renamed to ``path`` by :meth:`close`
    (the end of the ``with`` block), so ``path`` never holds half a file; when the block
    ends with an exception, the partial file is removed instead.

    Parameters
    ----------
    path : str or os.PathLike
        The prediction file to write, e.g. ``predictions.mcap``.
    method : str
        The method's name (the default row name in ``evaluator score``).
    dataset : Dataset, SetDataset or str
        The dataset the predictions are for, or its content hash (the sha256 of its
        ``pairs.mcap``, or of a set dataset's ``sets.mcap``, as listed in its manifest).
        With a :class:`Dataset` or :class:`SetDataset`, each ``write`` also checks that the
        pair is one of the dataset's and that its arrays have the pair's numbers of points
        (from ``index.csv``). A set dataset's pairs are the pairs (view 0, view k) of every
        set, ids ``<set>-0-<k>``; :meth:`write_set` writes a set's labels as those records.
    method_version : str
        Free text (a git hash, ``1.2.0``); may be empty.

    Examples
    --------
    >>> with PredictionWriter("predictions.mcap", "my-method", dataset) as writer:
    ...     for pair in dataset:
    ...         writer.write(pair.id, segments_p, flow=flow)
    """

    def __init__(
        self,
        path: PathLike,
        method: str,
        dataset: Union[Dataset, str],
        method_version: str = "",
    ) -> None:
        self._views: Optional[Dict[str, List[int]]] = None
        if isinstance(dataset, Dataset):
            content_hash = dataset.content_hash
            self._sizes: Optional[Dict[str, Tuple[int, int]]] = _index_sizes(dataset)
        elif isinstance(dataset, SetDataset):
            content_hash = dataset.content_hash
            self._views = _set_sizes(dataset)
            self._sizes = {
                f"{set_id}-0-{k}": (points[0], points[k])
                for set_id, points in self._views.items()
                for k in range(1, len(points))
            }
        elif isinstance(dataset, str):
            content_hash = dataset.lower()
            self._sizes = None
        else:
            raise TypeError(f"dataset must be a Dataset or a content hash, not {dataset!r}")
        if len(content_hash) != 64 or any(c not in "0123456789abcdef" for c in content_hash):
            raise PredictionError(f"dataset hash {content_hash!r} is not a sha256 in hex")
        for name, value in (("method", method), ("method_version", method_version)):
            if not isinstance(value, str):
                raise TypeError(f"{name} must be a str, not {type(value).__name__}")
        if not method:
            raise PredictionError("method must not be empty")
        self.path = Path(path)
        self.partial = Path(f"{self.path}.partial")
        self._ids: set = set()
        self._count = 0
        self._file = open(self.partial, "wb")
        try:
            self._writer = Writer(self._file, compression=CompressionType.ZSTD)
            self._writer.start(profile="", library="part_induction (Python)")
            meta = {"schema_version": str(SCHEMA_VERSION)}
            header = self._writer.register_channel(
                HEADER_TOPIC, ENCODING, 0, {"schema": HEADER_SCHEMA, **meta}
            )
            self._channel = self._writer.register_channel(
                PREDICTION_TOPIC, ENCODING, 0, {"schema": PREDICTION_SCHEMA, **meta}
            )
            record = {
                "format": FORMAT,
                "format_version": FORMAT_VERSION,
                "method": method,
                "method_version": method_version,
                "dataset": content_hash,
            }
            self._writer.add_message(header, 0, cbor2.dumps(record), 0)
        except BaseException:
            self.abort()
            raise

    def __enter__(self) -> "PredictionWriter":
        return self

    def __exit__(
        self,
        kind: Optional[Type[BaseException]],
        value: Optional[BaseException],
        traceback: Optional[TracebackType],
    ) -> None:
        if kind is None:
            self.close()
        else:
            self.abort()

    def __len__(self) -> int:
        """Number of predictions written so far (errors included)."""
        return self._count

    def write(
        self,
        pair_id: str,
        segments_p: Any,
        *,
        segments_q: Any = None,
        flow: Any = None,
        motions: MotionsLike = None,
        corr_mask: Any = None,
        segment_probs: Any = None,
        joints: Optional[Sequence[JointLike]] = None,
    ) -> None:
        """Writes the prediction for one pair; None means the method does not estimate it.

        Parameters
        ----------
        pair_id : str
            The pair's id in the dataset.
        segments_p : array-like
            integer, shape [N_p], values in [0, 2^32): segment id of each point of P.
        segments_q : array-like, optional
            integer, shape [N_q]: segment id of each point of Q, the same ids as P's.
        flow : array-like, optional
            float, shape [N_p, 3]: the flow on P, Q's normalised units (``p + flow`` is P
            moved into Q's normalised frame). Stored as float32.
        motions : tuple or Motions, optional
            ``(rotations, translations)`` or ``(rotations, translations, scales)``:
            rotations float [S, 3, 3] (rotation matrices), translations float [S, 3] (Q's
            normalised units), scales float [S] or one float (> 0; 1 when omitted); segment
            ``s`` maps ``x -> scale_s * R_s x + t_s`` from P's normalised frame to Q's. S is
            one more than the largest segment id; an empty tuple of arrays is allowed.
            An object with ``rotations``, ``translations`` and ``scale`` (a pair's
            ground-truth ``Motions``) is taken too.
        corr_mask : array-like, optional
            float or bool, shape [N_p], in [0, 1]: belief that each point of P has a
            counterpart in Q.
        segment_probs : array-like, optional
            float, shape [N_p, C], in [0, 1]: soft segment probabilities of each point of P.
        joints : sequence, optional
            Length S: ``joints[s]`` is a :class:`PredictedJoint` (or a mapping with ``kind``,
            ``axis``, ``pivot``, ``value``) for the joint that moves segment ``s``, or None.

        Raises
        ------
        PredictionError
            Naming the pair and the field, on a wrong dtype or shape, a NaN or infinity, a
            value out of range, a repeated pair id, or (with a Dataset) an id or size that
            is not the dataset's.
        """
        where = self._start(pair_id)
        n_q: Optional[int] = None
        if self._sizes is not None:
            n_p, n_q = self._sizes[pair_id]
        else:
            n_p = None
        seg_p = _segments(where, "segments_p", segments_p, n_p)
        n_p = len(seg_p)
        record: Dict[str, Any] = {"id": pair_id, "segments_p": seg_p.tobytes()}
        num_segments = int(seg_p.max()) + 1 if n_p else 0
        if segments_q is not None:
            seg_q = _segments(where, "segments_q", segments_q, n_q)
            record["segments_q"] = seg_q.tobytes()
            if len(seg_q):
                num_segments = max(num_segments, int(seg_q.max()) + 1)
        if flow is not None:
            record["flow"] = _floats(where, "flow", flow, (n_p, 3)).tobytes()
        if motions is not None:
            record["motions"] = _motions(where, motions, num_segments)
        if corr_mask is not None:
            mask = _floats(where, "corr_mask", corr_mask, (n_p,), allow_bool=True)
            _in_unit_interval(where, "corr_mask", mask)
            record["corr_mask"] = mask.tobytes()
        if segment_probs is not None:
            probs = _floats(where, "segment_probs", segment_probs, (n_p, None))
            if probs.shape[1] == 0:
                raise PredictionError(f"{where}: `segment_probs` has no columns")
            _in_unit_interval(where, "segment_probs", probs)
            record["segment_probs"] = {"columns": probs.shape[1], "values": probs.tobytes()}
        if joints is not None:
            record["joints"] = _joints(where, joints, num_segments)
        self._add(record)

    def write_set(self, set_id: str, segments: Sequence[Any]) -> None:
        """Writes a set method's labels for one set of K views: ``segments[k]`` (integer,
        shape [N_k]) labels the points of view k, one id naming the same part in every view.
        They are written as the records of the pairs (view 0, view k), k = 1 .. K-1, each
        with view 0's labels as ``segments_p`` and view k's as ``segments_q``; the evaluator
        lifts such records to the set unchanged (docs/METRICS.md, "Sets").

        Raises
        ------
        PredictionError
            When the writer was not opened on a :class:`SetDataset`, the set is not one of
            it, or ``segments`` does not hold one label per point of each view.
        """
        if self._views is None:
            raise PredictionError(
                f"set {set_id!r}: write_set needs a writer opened on a SetDataset"
            )
        where = f"set {set_id!r}"
        points = self._views.get(set_id)
        if points is None:
            raise PredictionError(f"{where}: not a set of the dataset")
        if len(segments) != len(points):
            raise PredictionError(f"{where}: {len(segments)} label arrays for {len(points)} views")
        for k in range(1, len(points)):
            self.write(f"{set_id}-0-{k}", segments[0], segments_q=segments[k])

    def write_error(self, pair_id: str, reason: str) -> None:
        """Records that the method failed on a pair; the pair counts as failed with
        ``reason``.

        Raises
        ------
        PredictionError
            On an empty reason, a repeated pair id, or (with a Dataset) an unknown id.
        """
        where = self._start(pair_id)
        if not isinstance(reason, str) or not reason:
            raise PredictionError(f"{where}: the error reason must be a non-empty str")
        self._add({"id": pair_id, "error": reason})

    def close(self) -> None:
        """Finishes the file and renames it from ``path + ".partial"`` to ``path``."""
        if self._file.closed:
            return
        try:
            self._writer.finish()
            self._file.close()
            os.replace(self.partial, self.path)
        except BaseException:
            self.abort()
            raise

    def abort(self) -> None:
        """Closes and removes the partial file, leaving ``path`` untouched."""
        if not self._file.closed:
            self._file.close()
        try:
            os.remove(self.partial)
        except FileNotFoundError:
            pass

    def _start(self, pair_id: str) -> str:
        if self._file.closed:
            raise PredictionError(f"{self.path}: the writer is closed")
        if not isinstance(pair_id, str) or not pair_id:
            raise PredictionError(f"pair id must be a non-empty str, not {pair_id!r}")
        where = f"pair {pair_id!r}"
        if pair_id in self._ids:
            raise PredictionError(f"{where}: already written (one prediction per pair)")
        if self._sizes is not None and pair_id not in self._sizes:
            raise PredictionError(f"{where}: not a pair of the dataset")
        return where

    def _add(self, record: Dict[str, Any]) -> None:
        self._count += 1
        self._writer.add_message(self._channel, self._count, cbor2.dumps(record), self._count)
        self._ids.add(record["id"])


def read_predictions(path: PathLike) -> Tuple[Dict[str, Any], Iterator[Dict[str, Any]]]:
    """Reads a prediction file: its header now, its predictions as a stream in file order.

    Parameters
    ----------
    path : str or os.PathLike
        A prediction file.

    Returns
    -------
    header : dict
        ``format``, ``format_version``, ``method``, ``method_version``, ``dataset``.
    predictions : iterator of dict
        One per ``/prediction`` message, with the keys present in the file (null values
        dropped): ``id`` (str); ``segments_p``, ``segments_q`` (uint32 [N_p], [N_q]);
        ``flow`` (float32 [N_p, 3]); ``motions`` (dict of ``rotations`` float32 [S, 3, 3],
        ``translations`` float32 [S, 3], ``scales`` float32 [S]); ``corr_mask`` (float32
        [N_p]); ``segment_probs`` (float32 [N_p, C]); ``joints`` (list of None or dict with
        ``kind``, ``axis`` and ``pivot`` float32 [3], ``value`` float); ``error`` (str).

    Raises
    ------
    PredictionError
        When the header is missing, not first, or of another format or version; a channel's
        schema is not the documented one; the file is truncated or corrupt; or a message is
        not a CBOR map with an ``id``; or a byte string is not a whole number of its values.
        This reader is for inspecting files: it stops at the first such record, where
        ``evaluator score`` fails only that pair (docs/FORMAT.md), and it does not check for
        repeated ids, array lengths against the dataset, or rotations; the scorer does.
    """
    messages = _read_messages(Path(path))
    header = next(messages)
    return header, messages


def _read_messages(path: Path) -> Iterator[Dict[str, Any]]:
    """Yields the header, then every prediction decoded."""
    topics: Dict[int, str] = {}
    seen_header = False
    index = 0
    with open(path, "rb") as f:
        records = iter(StreamReader(f, validate_crcs=True).records)
        while True:
            try:
                record = next(records)
            except StopIteration:
                break
            except Exception as e:  # McapError, CRCValidationError, zstd errors: a broken file
                raise PredictionError(
                    f"{path}: not a readable MCAP file after {index} predictions "
                    f"(truncated or corrupt?): {type(e).__name__} {e}".rstrip()
                ) from e
            ours = (HEADER_TOPIC, PREDICTION_TOPIC)
            if isinstance(record, Channel) and record.topic in ours:
                _check_channel(path, record)
                topics[record.id] = record.topic
            elif isinstance(record, Message) and record.channel_id in topics:
                topic = topics[record.channel_id]
                where = f"{path}: {topic} message {index if seen_header else 0}"
                message = _cbor_map(where, record.data)
                if topic == HEADER_TOPIC:
                    if seen_header:
                        raise PredictionError(f"{path}: more than one {HEADER_TOPIC} message")
                    _check_header(path, message)
                    seen_header = True
                    yield message
                elif not seen_header:
                    raise PredictionError(f"{path}: a prediction comes before the header")
                else:
                    yield _decode_prediction(where, message)
                    index += 1
    if not seen_header:
        raise PredictionError(f"{path}: no {HEADER_TOPIC} message")


def _decode_prediction(where: str, message: Dict[str, Any]) -> Dict[str, Any]:
    pair_id = message.get("id")
    if not isinstance(pair_id, str):
        raise PredictionError(f"{where}: no text `id`")
    out: Dict[str, Any] = {"id": pair_id}
    where = f"{where} (pair {pair_id!r})"
    for key, dtype, width in (
        ("segments_p", np.uint32, 1),
        ("segments_q", np.uint32, 1),
        ("flow", np.float32, 3),
        ("corr_mask", np.float32, 1),
    ):
        if message.get(key) is not None:
            out[key] = _from_bytes(where, key, message[key], dtype, width)
    probs = message.get("segment_probs")
    if probs is not None:
        columns = probs.get("columns") if isinstance(probs, dict) else None
        if not isinstance(columns, int) or columns < 0:
            raise PredictionError(f"{where}: `segment_probs.columns` is not a uint")
        values = probs.get("values")
        if columns == 0:
            if values != b"":
                raise PredictionError(f"{where}: `segment_probs` has values but 0 columns")
            out["segment_probs"] = np.zeros((0, 0), np.float32)
        else:
            out["segment_probs"] = _from_bytes(where, "segment_probs", values, np.float32, columns)
    motions = message.get("motions")
    if motions is not None:
        try:
            rotations = np.array([m["rotation"] for m in motions], np.float32)
            translations = np.array([m["translation"] for m in motions], np.float32)
            out["motions"] = {
                "rotations": rotations.reshape(-1, 3, 3),
                "translations": translations.reshape(-1, 3),
                "scales": np.array([m.get("scale", 1.0) for m in motions], np.float32),
            }
        except (TypeError, KeyError, ValueError) as e:
            raise PredictionError(f"{where}: `motions` is malformed: {e}") from e
    joints = message.get("joints")
    if joints is not None:
        try:
            out["joints"] = [
                None
                if j is None
                else {
                    "kind": j["kind"],
                    "axis": np.array(j["axis"], np.float32),
                    "pivot": np.array(j["pivot"], np.float32),
                    "value": float(j["value"]),
                }
                for j in joints
            ]
        except (TypeError, KeyError, ValueError) as e:
            raise PredictionError(f"{where}: `joints` is malformed: {e}") from e
    if message.get("error") is not None:
        out["error"] = message["error"]
    return out


def _from_bytes(where: str, key: str, data: Any, dtype: Any, width: int) -> np.ndarray:
    if not isinstance(data, bytes):
        raise PredictionError(f"{where}: `{key}` is not a byte string")
    size = np.dtype(dtype).itemsize * width
    if len(data) % size:
        raise PredictionError(
            f"{where}: `{key}` byte length {len(data)} is not a multiple of {size}"
        )
    values = np.frombuffer(data, np.dtype(dtype).newbyteorder("<")).astype(dtype)
    return values.reshape(-1, width) if width > 1 else values


def _cbor_map(where: str, data: bytes) -> Dict[str, Any]:
    try:
        message = cbor2.loads(data)
    except Exception as e:  # cbor2 raises several types; all mean "not valid CBOR"
        raise PredictionError(f"{where}: not valid CBOR: {e}") from e
    if not isinstance(message, dict):
        raise PredictionError(f"{where}: not a CBOR map")
    return message


def _check_channel(path: Path, channel: Channel) -> None:
    schema = HEADER_SCHEMA if channel.topic == HEADER_TOPIC else PREDICTION_SCHEMA
    found = (
        channel.message_encoding,
        channel.metadata.get("schema"),
        channel.metadata.get("schema_version"),
    )
    if found != (ENCODING, schema, str(SCHEMA_VERSION)):
        raise PredictionError(
            f"{path}: wrong schema: {channel.topic} has encoding {found[0]!r}, schema "
            f"{found[1]!r} version {found[2]!r} (expected {ENCODING!r}, {schema!r} version "
            f"{SCHEMA_VERSION})"
        )


def _check_header(path: Path, header: Dict[str, Any]) -> None:
    found = (header.get("format"), header.get("format_version"))
    if found != (FORMAT, FORMAT_VERSION):
        raise PredictionError(
            f"{path}: header names format {found[0]!r} version {found[1]!r} (expected "
            f"{FORMAT!r} version {FORMAT_VERSION})"
        )


def _set_sizes(dataset: SetDataset) -> Dict[str, List[int]]:
    """Set id -> points of each view, from the set dataset's ``index.csv``."""
    import csv

    path = dataset.path / "index.csv"
    try:
        with open(path, newline="", encoding="utf-8") as f:
            return {
                row["id"]: [int(n) for n in row["points"].split(";")] for row in csv.DictReader(f)
            }
    except (OSError, KeyError, ValueError) as e:
        raise PredictionError(f"{path}: cannot read the sets' sizes: {e}") from e


def _index_sizes(dataset: Dataset) -> Dict[str, Tuple[int, int]]:
    """Pair id -> (N_p, N_q), from the dataset's ``index.csv``."""
    import csv

    path = dataset.path / "index.csv"
    try:
        with open(path, newline="", encoding="utf-8") as f:
            return {row["id"]: (int(row["n_p"]), int(row["n_q"])) for row in csv.DictReader(f)}
    except (OSError, KeyError, ValueError) as e:
        raise PredictionError(f"{path}: cannot read the pairs' sizes: {e}") from e


def _array(where: str, field: str, value: Any) -> np.ndarray:
    try:
        return np.asarray(value)
    except Exception as e:  # anything numpy cannot take is the caller's field error
        raise PredictionError(f"{where}: `{field}` is not an array: {e}") from e


def _shape_error(where: str, field: str, shape: Tuple[int, ...], expected: Sequence[Any]) -> str:
    dims = ", ".join("C" if d is None else str(d) for d in expected)
    return f"{where}: `{field}` has shape {shape}, expected [{dims}]"


def _check_shape(
    where: str, field: str, a: np.ndarray, expected: Sequence[Optional[int]]
) -> None:
    wrong = any(e is not None and s != e for s, e in zip(a.shape, expected))
    if a.ndim != len(expected) or wrong:
        raise PredictionError(_shape_error(where, field, a.shape, expected))


def _segments(where: str, field: str, value: Any, n: Optional[int]) -> np.ndarray:
    a = _array(where, field, value)
    if a.dtype.kind not in "iu":
        raise PredictionError(f"{where}: `{field}` must hold integers, not {a.dtype}")
    _check_shape(where, field, a, (n,))
    if len(a) and (a.min() < 0 or a.max() > 0xFFFFFFFF):
        raise PredictionError(f"{where}: `{field}` has ids outside [0, 2^32)")
    return a.astype("<u4")


def _floats(
    where: str, field: str, value: Any, shape: Sequence[Optional[int]], allow_bool: bool = False
) -> np.ndarray:
    a = _array(where, field, value)
    if a.dtype.kind not in "fiu" + ("b" if allow_bool else ""):
        raise PredictionError(f"{where}: `{field}` must hold floats, not {a.dtype}")
    _check_shape(where, field, a, shape)
    with np.errstate(over="ignore", invalid="ignore"):  # overflow is refused just below
        a = a.astype("<f4")
    bad = ~np.isfinite(a)
    if bad.any():
        entry = int(np.flatnonzero(bad.reshape(len(a), -1).any(1))[0]) if a.ndim else 0
        raise PredictionError(f"{where}: `{field}` has a NaN or infinite value at entry {entry}")
    return a


def _in_unit_interval(where: str, field: str, a: np.ndarray) -> None:
    if a.size and (a.min() < 0 or a.max() > 1):
        raise PredictionError(f"{where}: `{field}` has values outside [0, 1]")


def _motions(where: str, motions: MotionsLike, num_segments: int) -> List[Dict[str, Any]]:
    if hasattr(motions, "rotations") and hasattr(motions, "translations"):
        parts = (motions.rotations, motions.translations, getattr(motions, "scale", 1.0))
    elif isinstance(motions, (tuple, list)) and len(motions) in (2, 3):
        parts = tuple(motions) + ((1.0,) if len(motions) == 2 else ())
    else:
        raise PredictionError(
            f"{where}: `motions` must be (rotations, translations[, scales]) or a Motions"
        )
    rotations = _floats(where, "motions.rotations", parts[0], (None, 3, 3))
    s = len(rotations)
    translations = _floats(where, "motions.translations", parts[1], (s, 3))
    scales = _array(where, "motions.scales", parts[2])
    scales = np.full(s, scales, np.float32) if scales.ndim == 0 else scales
    scales = _floats(where, "motions.scales", scales, (s,))
    if s not in (0, num_segments):
        raise PredictionError(
            f"{where}: `motions` has {s} entries, expected {num_segments} (one per segment) or 0"
        )
    if (scales <= 0).any():
        raise PredictionError(f"{where}: `motions` scales must be positive")
    rt_r = np.einsum("sji,sjk->sik", rotations.astype(np.float64), rotations)
    defect = np.abs(rt_r - np.eye(3)).max(axis=(1, 2)) if s else np.zeros(0)
    bad = np.flatnonzero((defect > ROTATION_TOLERANCE) | (np.linalg.det(rotations) <= 0))
    if len(bad):
        raise PredictionError(f"{where}: `motions` rotation {bad[0]} is not a rotation matrix")
    return [
        {
            "rotation": [float(x) for x in r.reshape(9)],
            "translation": [float(x) for x in t],
            "scale": float(c),
        }
        for r, t, c in zip(rotations, translations, scales)
    ]


def _joints(where: str, joints: Sequence[JointLike], num_segments: int) -> List[Any]:
    if isinstance(joints, (str, bytes)) or not isinstance(joints, Sequence):
        raise PredictionError(f"{where}: `joints` must be a sequence (one entry per segment)")
    if len(joints) != num_segments:
        raise PredictionError(
            f"{where}: `joints` has {len(joints)} entries, expected {num_segments} (one per "
            "segment, None where no joint moves it)"
        )
    out: List[Any] = []
    for s, joint in enumerate(joints):
        field = f"joints[{s}]"
        if joint is None:
            out.append(None)
            continue
        if isinstance(joint, Mapping):
            try:
                joint = PredictedJoint(
                    joint["kind"], joint["axis"], joint["pivot"], joint["value"]
                )
            except KeyError as e:
                raise PredictionError(f"{where}: `{field}` lacks {e}") from e
        if not isinstance(joint, PredictedJoint):
            raise PredictionError(
                f"{where}: `{field}` must be a PredictedJoint, a mapping or None"
            )
        if joint.kind not in JOINT_KINDS:
            raise PredictionError(
                f"{where}: `{field}.kind` {joint.kind!r} is not one of {JOINT_KINDS}"
            )
        axis = _floats(where, f"{field}.axis", joint.axis, (3,))
        pivot = _floats(where, f"{field}.pivot", joint.pivot, (3,))
        value = _floats(where, f"{field}.value", joint.value, ())
        length = float(np.linalg.norm(axis.astype(np.float64)))
        if length < 1e-6:
            raise PredictionError(f"{where}: `{field}.axis` is zero")
        out.append(
            {
                "kind": joint.kind,
                # Stored as a unit vector, as the format says; the scorer normalises too.
                "axis": [float(x) for x in (axis / length).astype(np.float32)],
                "pivot": [float(x) for x in pivot],
                "value": float(value),
            }
        )
    return out

