"""Reading set datasets: K observations of one object in K articulation states (the
MultiBodySync setting), the ``/set`` records of ``sets.mcap`` (docs/FORMAT.md, "Set
datasets").

A :class:`Set` holds K :class:`SetView` s with part ids consistent across all K (set part
``s`` in one view is set part ``s`` in every view), each part's motion from view 0, the
flows from view 0, and the joints in every view. :meth:`Set.pair` gives the pair of any two
views as the :class:`~part_induction.Pair` a pair dataset holds, so a pair method runs on a
set's pairs unchanged.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional, Sequence, Union

import cbor2
import numpy as np

from .dataset import (
    DatasetError,
    Image,
    Joint,
    Motions,
    Pair,
    PathLike,
    _Checker,
    _Folder,
    _image_decoder,
    _iter_topic,
    _read_manifest,
)

SETS_FILE = "sets.mcap"
SET_TOPIC = "/set"
SET_ENCODING = "cbor"
SET_SCHEMA = "part_induction.Set"
SET_SCHEMA_VERSION = 1
VIEW_KINDS = ("full", "scan")
MODES = ("full", "scan", "mixed")


@dataclass
class SetView:
    """One observation of a set.

    Attributes
    ----------
    kind : str
        ``"full"`` (surface samples) or ``"scan"`` (a virtual scan).
    points : np.ndarray
        float32, shape [N_k, 3]: the cloud, in its own normalised frame.
    centre : np.ndarray
        float32, shape [3]: the cloud's bounding-box centre, object frame.
    scale : float
        The cloud's bounding-box diagonal, object units.
    parts : np.ndarray
        uint8, shape [N_k]: the set part of each point.
    motions : Motions
        Each set part's motion from view 0's normalised frame to this view's (the identity
        for view 0); ``motions.scale`` is view 0's diagonal over this view's.
    flow : np.ndarray
        float32, shape [N_0, 3]: view 0's points moved into this view's state, minus view
        0's points (zeros for view 0).
    presence : np.ndarray
        bool, shape [K, N_k]: row j, whether each point moved into view j's state is present
        in view j (row k, its own, is all True).
    pair_parts : np.ndarray
        uint8, shape [K, P]: row j, the part of the pair (this view, view j) each set part
        belongs to (set parts that did not move apart between the two states are one part).
    scan : dict or None
        A scanned view's camera (the keys of ``Pair.scan_q``); None for a full view.
    images : dict or None
        Only when read with ``images``: a scanned view's ``depth``, ``labels`` and ``colour``.
    """

    kind: str
    points: np.ndarray
    centre: np.ndarray
    scale: float
    parts: np.ndarray
    motions: Motions
    flow: np.ndarray
    presence: np.ndarray
    pair_parts: np.ndarray
    scan: Optional[Dict[str, Any]] = None
    images: Optional[Dict[str, Image]] = None


@dataclass
class SetJoint:
    """A joint between two set parts, in every view.

    Attributes
    ----------
    name : str
        The joint's name (the exported URDF's).
    part, parent : int
        The set part it moves, and the set part it moves it against.
    kind : str
        ``"revolute"`` or ``"prismatic"``.
    axis, pivot : np.ndarray
        float32, shape [K, 3]: unit axis and a point on it, each view's normalised frame.
    value : np.ndarray
        float32, shape [K]: the joint's value in each view's state (radians or object units).
    """

    name: str
    part: int
    parent: int
    kind: str
    axis: np.ndarray
    pivot: np.ndarray
    value: np.ndarray


@dataclass
class Set:
    """K views of one object with their ground truth, as the ``/set`` record holds it.

    Attributes
    ----------
    id : str
        Unique set id, e.g. ``full-k4-00012-0``.
    num_parts : int
        P, the number of set parts (base included).
    views : list of SetView
        The K views, view 0 first.
    joints : list of SetJoint
        The joints between set parts.
    provenance : dict
        ``category``, ``object_id``, ``set_index``, ``seed``, ``generator_version`` and
        ``views``: per view ``articulation`` (its state's index), ``joints`` (every joint
        by name -> value) and ``pose`` (the object's rest frame into the view's object
        frame).
    """

    id: str
    num_parts: int
    views: List[SetView]
    joints: List[SetJoint]
    provenance: Dict[str, Any]

    def __len__(self) -> int:
        return len(self.views)

    @property
    def mode(self) -> str:
        """``"full"``, ``"scan"`` or ``"mixed"`` (view 0 full, the others scans)."""
        kinds = {v.kind for v in self.views[1:]}
        if self.views[0].kind == "scan":
            return "scan"
        return "mixed" if kinds == {"scan"} else "full"

    def points(self) -> List[np.ndarray]:
        """Each view's cloud (what a set method may see)."""
        return [v.points for v in self.views]

    def pair(self, i: int, j: int) -> Pair:
        """The pair of views ``i`` (as P) and ``j`` (as Q), with the ground truth a pair
        dataset holds for the same two observations: set parts merged where they did not
        move apart, motions composed from the views' own, flow, the correspondences of the
        points present in view j, and the joints that move a part of the pair. The same
        computation as the Rust ``Set::pair``.

        Raises
        ------
        ValueError
            For a view index out of range, ``i == j``, or a scan as P with a full shape as Q
            (no pair kind).
        """
        k = len(self.views)
        if not (0 <= i < k and 0 <= j < k) or i == j:
            raise ValueError(f"set {self.id}: views {i} and {j} make no pair of {k} views")
        vi, vj = self.views[i], self.views[j]
        kinds = {("full", "full"): "SF2F", ("full", "scan"): "SF2P", ("scan", "scan"): "SP2P"}
        kind = kinds.get((vi.kind, vj.kind))
        if kind is None:
            raise ValueError(f"set {self.id}: no pair kind has a scan as P and a full Q")
        groups = vi.pair_parts[j].astype(np.int64)
        part_p = groups[vi.parts].astype(np.uint8)
        part_q = groups[vj.parts].astype(np.uint8)
        count = int(groups.max()) + 1
        first = np.array([int(np.flatnonzero(groups == g)[0]) for g in range(count)])
        # motion_j ∘ motion_i⁻¹ per pair part, from its first set part (as Rust composes).
        si, sj = vi.motions.scale, vj.motions.scale
        rotations = np.empty((count, 3, 3), np.float32)
        translations = np.empty((count, 3), np.float32)
        for g, s in enumerate(first):
            ri, ti = vi.motions.rotations[s], vi.motions.translations[s]
            rj, tj = vj.motions.rotations[s], vj.motions.translations[s]
            inv_r = ri.T
            inv_t = -(inv_r @ ti) / np.float32(si)
            rotations[g] = rj @ inv_r
            translations[g] = rj @ inv_t * np.float32(sj) + tj
        scale = float(np.float32(sj) * np.float32(1.0 / np.float32(si)))
        motions = Motions(rotations, translations, scale)
        moved = motions.apply(vi.points, part_p)
        flow = (moved - vi.points).astype(np.float32)
        d = ((moved[:, None, :] - vj.points[None, :, :]) ** 2).sum(-1)
        d[part_p[:, None] != part_q[None, :]] = np.inf
        nearest = d.argmin(1)
        present = vi.presence[j] & np.isfinite(d[np.arange(len(d)), nearest])
        corr_index = np.where(present, nearest, -1).astype(np.int32)
        joints = [
            Joint(
                part=int(groups[joint.part]), kind=joint.kind,
                axis_p=joint.axis[i], pivot_p=joint.pivot[i],
                axis_q=joint.axis[j], pivot_q=joint.pivot[j],
                value_p=float(joint.value[i]), value_q=float(joint.value[j]),
            )
            for joint in self.joints
            if groups[joint.part] != groups[joint.parent]
        ]
        prov = self.provenance
        pi, pj = prov["views"][i], prov["views"][j]
        provenance = {
            "category": prov["category"], "object_id": prov["object_id"],
            "articulation_p": pi["articulation"], "articulation_q": pj["articulation"],
            "seed": prov["seed"], "generator_version": prov["generator_version"],
            "joints_p": pi["joints"], "joints_q": pj["joints"],
            "pose_p": pi.get("pose"), "pose_q": pj.get("pose"),
        }
        return Pair(
            id=f"{self.id}-{i}-{j}", kind=kind, p=vi.points, q=vj.points,
            p_centre=vi.centre, p_scale=vi.scale, q_centre=vj.centre, q_scale=vj.scale,
            part_p=part_p, part_q=part_q, num_parts=count, scale=scale, motions=motions,
            flow=flow, corr_mask=corr_index >= 0, corr_index=corr_index, joints=joints,
            provenance=provenance, scan_p=vi.scan, scan_q=vj.scan,
        )


class SetDataset(_Folder):
    """A set dataset folder opened for reading; iterate it for its sets, in file order.

    Attributes
    ----------
    path : Path
        The dataset folder.
    manifest : dict
        ``manifest.json`` as parsed JSON.
    content_hash : str
        The sha256 of ``sets.mcap`` listed in the manifest (lowercase hex).
    """

    def __init__(self, path: PathLike, images: Union[bool, str] = False) -> None:
        self.path = Path(path)
        self.manifest = _read_manifest(self.path, SETS_FILE)
        self.content_hash: str = self.manifest["files"][SETS_FILE]["sha256"].lower()
        self._images = images

    def __len__(self) -> int:
        # A set dataset with no set (every object left out) writes no `sets` count.
        return int(self.manifest["counts"].get("sets", 0))

    def __iter__(self) -> Iterator[Set]:
        return self.sets(images=self._images)

    def __repr__(self) -> str:
        return f"SetDataset({str(self.path)!r}, {len(self)} sets)"

    def sets(self, images: Union[bool, str] = False) -> Iterator[Set]:
        """Streams the sets in file order, one forward pass over ``sets.mcap``.

        Parameters
        ----------
        images : bool or {"bytes", "arrays"}
            Also read each scanned view's PNGs into ``SetView.images`` (as
            :meth:`part_induction.Dataset.pairs` does for pairs).

        Raises
        ------
        DatasetError
            On a wrong schema, a truncated or corrupt file, a set that breaks the format
            (naming the file, the ``/set`` message index and the field), or fewer sets than
            the manifest announces.
        """
        decode = _image_decoder(images)
        path = self.path / SETS_FILE
        count = 0
        for index, data in _iter_topic(path, SET_TOPIC, _check_set_channel):
            where = f"{path}: {SET_TOPIC} message {index}"
            try:
                record = cbor2.loads(data)
            except Exception as e:  # cbor2 raises several types; all mean "not our record"
                raise DatasetError(f"{where}: not valid CBOR: {e}") from e
            item = decode_set(record, where)
            if decode is not None:
                for view in item.views:
                    view.images = self._read_images(view.scan, decode)
            count += 1
            yield item
        if count != len(self):
            raise DatasetError(
                f"{path}: holds {count} sets but the manifest announces {len(self)} (truncated?)"
            )


def collate_sets_numpy(batch: Sequence[Set]) -> Dict[str, Any]:
    """Stacks sets of the same number of views K and points N per view: ``points`` float32
    [B, K, N, 3], ``parts`` int64 [B, K, N] (set parts, one id per part in every view),
    ``flow`` float32 [B, K, N, 3] (view 0's points moved into each view's state, minus view
    0's points; zeros for view 0), ``num_parts`` int64 [B]; ``id`` a list of str and
    ``kinds`` each set's view kinds. :func:`part_induction.torch.collate_sets` makes tensors
    of them.

    Raises
    ------
    ValueError
        On an empty batch, or sets that differ in K or in N.
    """
    if not batch:
        raise ValueError("collate_sets_numpy needs at least one set")
    shapes = sorted({(len(s.views), *sorted({len(v.points) for v in s.views})) for s in batch})
    if len(shapes) != 1 or len(shapes[0]) != 2:
        raise ValueError(
            f"sets of one K and one N per view stack; these have (K, N...) {shapes}"
        )

    def stack(get: Any, dtype: Any) -> np.ndarray:
        return np.stack([np.stack([get(v) for v in s.views]) for s in batch]).astype(dtype)

    return {
        "id": [s.id for s in batch],
        "kinds": [[v.kind for v in s.views] for s in batch],
        "points": stack(lambda v: v.points, np.float32),
        "parts": stack(lambda v: v.parts, np.int64),
        "flow": stack(lambda v: v.flow, np.float32),
        "num_parts": np.array([s.num_parts for s in batch], dtype=np.int64),
    }


def open_set_dataset(path: PathLike, *, images: Union[bool, str] = False) -> SetDataset:
    """Opens a set dataset folder (``sets.mcap``, ``manifest.json``, ...) for reading, as
    written by ``generator --kind sets``.

    Raises
    ------
    DatasetError
        When the folder has no ``manifest.json``, its manifest is of another format or
        version, or it holds pairs rather than sets.
    """
    return SetDataset(path, images=images)


def decode_set(record: Any, where: str) -> Set:
    """Decodes and checks one ``/set`` CBOR map: the schema version, every array's length
    against K, N_k and P, finite values, part ids below P, presence flags 0 or 1, and each
    ``pair_parts`` row numbered by first appearance. (Unlike the Rust reader it does not
    re-check that the flows equal the motions.)

    Raises
    ------
    DatasetError
        Naming ``where``, the set id and the field.
    """
    c = _Checker(where)
    if not isinstance(record, dict):
        c.fail("record", "not a CBOR map")
    version = c.get(record, "schema_version", int)
    if version != SET_SCHEMA_VERSION:
        c.fail("schema_version", f"version {version} (this reader knows {SET_SCHEMA_VERSION})")
    set_id = c.get(record, "id", str)
    c.where = f"{where} (set {set_id!r})"
    parts = c.get(record, "num_parts", int)
    if not 1 <= parts <= 256:
        c.fail("num_parts", f"{parts} parts (must be 1 to 256)")
    raw_views = c.get(record, "views", list)
    k = len(raw_views)
    if k < 2:
        c.fail("views", f"{k} views (a set has at least 2)")
    views = []
    for v, raw in enumerate(raw_views):
        f = f"views[{v}]"
        if not isinstance(raw, dict):
            c.fail(f, "not a map")
        kind = c.get(raw, "kind", str, f"{f}.kind")
        if kind not in VIEW_KINDS:
            c.fail(f"{f}.kind", f"{kind!r} is not full or scan")
        points, centre, scale = c.cloud(raw, "cloud")
        n = len(points)
        ids = c.array(raw, "parts", np.uint8, 1, n, f"{f}.parts")
        if ids.max() >= parts:
            c.fail(f"{f}.parts", f"holds part {ids.max()}, but the set has {parts} parts")
        scale_k = c.number(raw, "scale", f"{f}.scale")
        if scale_k <= 0:
            c.fail(f"{f}.scale", f"{scale_k} is not positive")
        motions = c.motions(raw, parts, scale_k)
        if v == 0:
            off = (np.abs(motions.rotations - np.eye(3)).max() + np.abs(motions.translations).max()
                   + abs(scale_k - 1.0))
            if off > 1e-5:
                c.fail(f"{f}.motions", "view 0's motions must be the identity")
            if "flow" in raw:
                c.fail(f"{f}.flow", "present on view 0")
            flow = None
        else:
            flow = c.array(raw, "flow", np.float32, 3, None, f"{f}.flow")
        presence = c.array(raw, "presence", np.uint8, 1, k * n, f"{f}.presence")
        if presence.max() > 1:
            c.fail(f"{f}.presence", "holds a value other than 0 or 1")
        if not presence.reshape(k, n)[v].all():
            c.fail(f"{f}.presence", f"row {v}, the view's own, must be all 1")
        groups = c.array(raw, "pair_parts", np.uint8, 1, k * parts, f"{f}.pair_parts")
        groups = groups.reshape(k, parts)
        if (groups[v] != np.arange(parts)).any():
            c.fail(f"{f}.pair_parts", f"row {v}, the view's own, must be 0 .. {parts - 1}")
        for j, row in enumerate(groups):
            seen = np.maximum.accumulate(np.concatenate([[-1], row[:-1].astype(np.int64)]))
            if (row.astype(np.int64) > seen + 1).any():
                c.fail(f"{f}.pair_parts", f"row {j} is not numbered by first appearance")
        scan = c.scan(raw, "scan")
        if (kind == "scan") != (scan is not None):
            c.fail(f"{f}.scan", "a scanned view has a camera, a full view none")
        views.append(SetView(
            kind=kind, points=points, centre=centre, scale=scale, parts=ids, motions=motions,
            flow=flow, presence=presence.reshape(k, n).astype(bool), pair_parts=groups,
            scan=scan,
        ))
    n0 = len(views[0].points)
    views[0].flow = np.zeros((n0, 3), np.float32)
    for v, view in enumerate(views[1:], 1):
        if len(view.flow) != n0:
            c.fail(f"views[{v}].flow", f"has {len(view.flow)} entries, expected {n0}")
    joints = []
    for i, raw in enumerate(c.get(record, "joints", list)):
        f = f"joints[{i}]"
        if not isinstance(raw, dict):
            c.fail(f, "not a map")
        kind = c.get(raw, "kind", str, f"{f}.kind")
        if kind not in ("revolute", "prismatic"):
            c.fail(f"{f}.kind", f"{kind!r} is not revolute or prismatic")
        arrays = {}
        for key, width in (("axis", 3), ("pivot", 3), ("value", 1)):
            values = c.get(raw, key, list, f"{f}.{key}")
            try:
                array = np.array(values, np.float32).reshape(k, width)
            except (TypeError, ValueError, OverflowError):
                c.fail(f"{f}.{key}", f"expected {k} entries of {width}")
            if not np.isfinite(array).all():
                c.fail(f"{f}.{key}", "non-finite value")
            arrays[key] = array
        if (np.abs(np.linalg.norm(arrays["axis"], axis=1) - 1.0) > 1e-3).any():
            c.fail(f"{f}.axis", "an axis is not unit length")
        part = c.get(raw, "part", int, f"{f}.part")
        parent = c.get(raw, "parent", int, f"{f}.parent")
        if not (0 <= part < parts and 0 <= parent < parts) or part == parent:
            c.fail(f, f"joins parts {part} and {parent} of {parts}")
        joints.append(SetJoint(
            name=c.get(raw, "name", str, f"{f}.name"), part=part, parent=parent, kind=kind,
            axis=arrays["axis"], pivot=arrays["pivot"], value=arrays["value"][:, 0],
        ))
    kinds = [view.kind for view in views]
    if kinds[0] == "scan" and "full" in kinds or "full" in kinds[1:] and "scan" in kinds[1:]:
        c.fail("views", "must be all full, all scanned, or view 0 full and the others scanned")
    provenance = c.get(record, "provenance", dict)
    for key, kind in (("category", str), ("object_id", int), ("seed", int),
                      ("generator_version", str)):
        c.get(provenance, key, kind, f"provenance.{key}")
    prov_views = c.get(provenance, "views", list, "provenance.views")
    if len(prov_views) != k:
        c.fail("provenance.views", f"expected {k} entries")
    for v, entry in enumerate(prov_views):
        f = f"provenance.views[{v}]"
        if not isinstance(entry, dict):
            c.fail(f, "not a map")
        c.get(entry, "articulation", int, f"{f}.articulation")
        c.get(entry, "joints", dict, f"{f}.joints")
    return Set(id=set_id, num_parts=parts, views=views, joints=joints, provenance=provenance)


def _check_set_channel(path: PathLike, channel: Any) -> None:
    schema = channel.metadata.get("schema")
    version = channel.metadata.get("schema_version")
    if (channel.message_encoding, schema, version) != (
        SET_ENCODING, SET_SCHEMA, str(SET_SCHEMA_VERSION)
    ):
        raise DatasetError(
            f"{path}: wrong schema: {SET_TOPIC} has encoding {channel.message_encoding!r}, "
            f"schema {schema!r} version {version!r} (expected {SET_ENCODING!r}, "
            f"{SET_SCHEMA!r} version {SET_SCHEMA_VERSION})"
        )
