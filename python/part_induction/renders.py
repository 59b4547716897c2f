"""Renders for image-based methods (``generator render``; docs/FORMAT.md, "Renders"):
the ground truth every layout writes (``ground_truth.json``) and joints-only prediction
files (``joints.json``) that ``evaluator score --dataset <render folder>`` scores in every
family's convention (ours, PARIS, DigitalTwinArt, ArtGS; docs/METRICS.md).

Joints are given in the layout's world frame and units (the frame the method saw): a
unit-free ``axis`` direction, a ``pivot`` point on the axis, and the ``state`` change from
the start state to the end state, radians (revolute, right-handed about ``axis``) or world
units along ``axis`` (prismatic).
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from pathlib import Path
from typing import Any, Dict, Iterable, List, Mapping, Sequence, Union

JOINTS_FORMAT = "part-induction-joints"
JOINTS_VERSION = 1
MAX_JOINTS = 8

PathLike = Union[str, "os.PathLike[str]"]


class RenderError(ValueError):
    """A render folder, ground truth or joints file that cannot be used (names what and where)."""


def read_ground_truth(render: PathLike) -> Dict[str, Any]:
    """The render's ``ground_truth.json``: ``layout``, ``seed`` and ``objects`` (each with
    ``folder``, ``world``, ``diagonal`` and its moving ``joints``)."""
    path = Path(render) / "ground_truth.json"
    try:
        return json.loads(path.read_text())
    except OSError as e:
        raise RenderError(f"{path}: {e.strerror or e}") from e
    except json.JSONDecodeError as e:
        raise RenderError(f"{path}: not JSON: {e}") from e


def joint(kind: str, axis: Sequence[float], pivot: Sequence[float], state: float) -> Dict[str, Any]:
    """One predicted joint, checked: ``kind`` revolute or prismatic, a finite non-zero
    ``axis``, a finite ``pivot`` and ``state``."""
    if kind not in ("revolute", "prismatic"):
        raise RenderError(f"joint type {kind!r} is not 'revolute' or 'prismatic'")
    axis = [float(x) for x in axis]
    pivot = [float(x) for x in pivot]
    if len(axis) != 3 or len(pivot) != 3:
        raise RenderError(f"axis and pivot need 3 numbers, got {len(axis)} and {len(pivot)}")
    values = axis + pivot + [float(state)]
    if not all(math.isfinite(v) for v in values):
        raise RenderError(f"a joint number is not finite: axis {axis}, pivot {pivot}, state {state}")
    if all(v == 0.0 for v in axis):
        raise RenderError("the joint axis is zero")
    return {"type": kind, "axis": axis, "pivot": pivot, "state": float(state)}


def joint_from_trans(entry: Mapping[str, Any]) -> Dict[str, Any]:
    """A joint from a ``trans_info`` entry as PARIS, DigitalTwinArt and ArtGS write their
    ground truth and motion files (``type`` rotate/translate, ``axis.o``, ``axis.d``, and
    ``l``/``r`` in degrees or world units)."""
    kind = {"rotate": "revolute", "translate": "prismatic"}.get(entry.get("type"))
    if kind is None:
        raise RenderError(f"trans_info type {entry.get('type')!r} is not 'rotate' or 'translate'")
    block = entry[entry["type"]]
    change = float(block["r"]) - float(block["l"])
    state = math.radians(change) if kind == "revolute" else change
    return joint(kind, entry["axis"]["d"], entry["axis"]["o"], state)


def write_joint_predictions(
    path: PathLike,
    method: str,
    objects: Mapping[str, Iterable[Mapping[str, Any]]],
    render: PathLike | None = None,
) -> Path:
    """Writes a joints-only prediction file: ``objects`` maps an object folder (the
    ``folder`` of ``ground_truth.json``) to its predicted joints (:func:`joint`). With
    ``render``, every folder is checked against that render's ground truth first. The file
    is written to a temporary beside ``path`` and renamed into place."""
    if not method or "," in method:
        raise RenderError(f"method name {method!r} must be non-empty and hold no comma")
    known = None
    if render is not None:
        known = {o["folder"] for o in read_ground_truth(render)["objects"]}
    out: Dict[str, List[Dict[str, Any]]] = {}
    for folder, joints in objects.items():
        if known is not None and folder not in known:
            raise RenderError(f"object {folder!r} is not in the render {render}")
        checked = [joint(j["type"], j["axis"], j["pivot"], j["state"]) for j in joints]
        if len(checked) > MAX_JOINTS:
            raise RenderError(f"object {folder!r}: more than {MAX_JOINTS} joints")
        out[folder] = checked
    record = {"format": JOINTS_FORMAT, "version": JOINTS_VERSION, "method": method, "objects": out}
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent or ".", prefix=f".{path.name}.")
    try:
        with os.fdopen(fd, "w") as f:
            json.dump(record, f, indent=1)
            f.write("\n")
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path
