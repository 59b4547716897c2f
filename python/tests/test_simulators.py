"""Objects exported by `generator export-objects`, checked by the simulators themselves:
MuJoCo loads `mobility.xml`, PyBullet and SAPIEN load `mobility.urdf`, usd-core reads
`mobility.usda` (with UsdPhysics' own parser). One object of every category, and for each:

- it loads without a warning;
- forward kinematics at several joint configurations agrees with the generator's
  (`generator/examples/kinematics_json.rs`) to 1e-5;
- at rest (each state of `states.json`) no two links that no joint connects are in contact;
- with a fixed base and gravity, one simulated second moves no joint outside its limits
  (beyond the simulator's constraint slack) and produces no NaN;
- joints driven by a position controller reach their targets;
- a small sphere dropped inside an opened container (cabinet and its drawer, microwave,
  oven, washing machine, refrigerator, dishwasher) comes to rest on a floor inside it,
  touching no wall, where the convex hull of the visual mesh (what a simulator makes of a
  mesh used as collision) leaves no room for it at all.

usd-core has no simulator: the USD file's joints are checked against the URDF's and its
forward kinematics is composed from the UsdPhysics joint frames. SAPIEN runs without a
rendering device here, so its loader's visual shapes are dropped before building.
"""

from __future__ import annotations

import contextlib
import json
import os
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional, Tuple

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco", reason="pip install mujoco (the `sim` extra)")
pybullet = pytest.importorskip("pybullet", reason="pip install pybullet (the `sim` extra)")
pxr = pytest.importorskip("pxr", reason="pip install usd-core (the `sim` extra)")
from pxr import Gf, Usd, UsdPhysics  # noqa: E402
from scipy.spatial import ConvexHull  # noqa: E402

GRAVITY = np.array([0.0, -9.81, 0.0])  # the object frame is Y-up
# Categories with something to put things in, and the links that must have room for the
# probe (the washing machine's body is solid in the generator: its drum is not hollow, so
# its detergent drawer holds the probe).
CONTAINERS = {
    "cabinet": ["link_0", "link_1"],  # the body and its drawer
    "microwave": ["link_0"],
    "oven": ["link_0"],
    "washing_machine": ["link_2"],
    "refrigerator": ["link_0"],
    "dishwasher": ["link_0"],
    "wardrobe": ["link_0"],
    "safe": ["link_0"],
    "toolbox": ["link_0"],
    "trash_can": ["link_0"],
    "mailbox": ["link_0"],
}
FK_TOLERANCE = 1e-5
PENETRATION = 1e-5  # deeper than this is a contact (touching faces meet at about 1e-8)


@contextlib.contextmanager
def captured_output() -> Iterator[List[str]]:
    """Everything written to file descriptors 1 and 2 inside the block (the simulators'
    C++ cores print their warnings there), as the only item of the yielded list."""
    sys.stdout.flush()
    sys.stderr.flush()
    out: List[str] = []
    with tempfile.TemporaryFile() as tmp:
        saved = [os.dup(1), os.dup(2)]
        os.dup2(tmp.fileno(), 1)
        os.dup2(tmp.fileno(), 2)
        try:
            yield out
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)
            tmp.seek(0)
            out.append(tmp.read().decode(errors="replace"))


def folders(exported: Path) -> List[Path]:
    return [exported / o["folder"] for o in json.loads((exported / "objects.json").read_text())]


def states(folder: Path) -> List[Dict[str, float]]:
    return json.loads((folder / "states.json").read_text())["states"]


def adjacent(obj: Dict[str, Any]) -> set:
    """Pairs of URDF links that a joint connects."""
    return {frozenset((j["parent"], j["child"])) for j in obj["joints"]}


def mimic_followers(obj: Dict[str, Any]) -> set:
    return {j["name"] for j in obj["joints"] if j["mimic"]}


def assert_pose(actual: np.ndarray, expected: Any, what: str) -> None:
    np.testing.assert_allclose(actual, np.asarray(expected), atol=FK_TOLERANCE, err_msg=what)


# ---------------------------------------------------------------------------------- MuJoCo


def mj_load(folder: Path) -> Tuple[Any, Any]:
    model = mujoco.MjModel.from_xml_path(str(folder / "mobility.xml"))
    return model, mujoco.MjData(model)


def mj_set(model: Any, data: Any, values: Dict[str, float]) -> None:
    for name, value in values.items():
        data.qpos[model.joint(name).qposadr[0]] = value
    data.qvel[:] = 0.0


def mj_link_transform(model: Any, data: Any, link: str) -> np.ndarray:
    t = np.eye(4)
    t[:3, :3] = data.body(link).xmat.reshape(3, 3)
    t[:3, 3] = data.body(link).xpos
    return t


def mj_contacts(model: Any, data: Any) -> List[Tuple[str, str, float]]:
    """Contacts deeper than PENETRATION, by body name."""
    out = []
    for c in data.contact[: data.ncon]:
        if c.dist < -PENETRATION:
            a = model.body(model.geom_bodyid[c.geom1]).name
            b = model.body(model.geom_bodyid[c.geom2]).name
            out.append((a, b, float(c.dist)))
    return out


@pytest.fixture(scope="module")
def mujoco_models(exported: Path) -> Dict[str, Tuple[Any, Any, str]]:
    """Each folder's MuJoCo model and data, and what loading printed."""
    loaded = {}
    for folder in folders(exported):
        with captured_output() as printed:
            model, data = mj_load(folder)
        loaded[folder.name] = (model, data, printed[0])
    return loaded


def test_mujoco_loads_every_category_without_warnings(
    exported: Path, mujoco_models: Dict[str, Tuple[Any, Any, str]],
    kinematics: List[Dict[str, Any]],
) -> None:
    assert len(mujoco_models) == len(kinematics) >= 39
    for obj in kinematics:
        model, data, printed = mujoco_models[obj["folder"]]
        assert printed.strip() == "", f"{obj['folder']}: {printed}"
        assert int(np.sum(data.warning.number)) == 0, obj["folder"]
        # Names, types, axes, limits: the generator's.
        for joint in obj["joints"]:
            mine = model.joint(joint["name"])
            kind = {"revolute": mujoco.mjtJoint.mjJNT_HINGE, "prismatic": mujoco.mjtJoint.mjJNT_SLIDE}
            assert mine.type[0] == kind[joint["type"]], joint["name"]
            np.testing.assert_allclose(mine.axis, joint["axis"], atol=1e-7)
            np.testing.assert_allclose(mine.range, [joint["lower"], joint["upper"]], atol=1e-6)
            assert model.body(mine.bodyid[0]).name == joint["child"]
        # Mimic joints are equality constraints: follower = offset + multiplier * leader.
        mimics = [j for j in obj["joints"] if j["mimic"]]
        assert model.neq == len(mimics)
        for k, joint in enumerate(mimics):
            assert model.joint(model.eq_obj1id[k]).name == joint["name"]
            assert model.joint(model.eq_obj2id[k]).name == joint["mimic"]["joint"]
            np.testing.assert_allclose(
                model.eq_data[k][:2], [joint["mimic"]["offset"], joint["mimic"]["multiplier"]],
                atol=1e-6,
            )
        # Masses from the geometry (meta.json), not a constant.
        meta = json.loads((exported / obj["folder"] / "meta.json").read_text())
        for link, physics in meta["link_physics"].items():
            assert model.body(link).mass[0] == pytest.approx(physics["mass"], rel=1e-6)


def test_mujoco_forward_kinematics_matches_the_generator(
    mujoco_models: Dict[str, Tuple[Any, Any, str]], kinematics: List[Dict[str, Any]]
) -> None:
    for obj in kinematics:
        model, data, _ = mujoco_models[obj["folder"]]
        for state in obj["states"]:
            mj_set(model, data, state["values"])
            mujoco.mj_kinematics(model, data)
            for link, expected in state["links"].items():
                assert_pose(
                    mj_link_transform(model, data, link), expected["transform"],
                    f"{obj['folder']} {link}",
                )


def test_mujoco_no_two_unjoined_links_touch_at_rest(
    exported: Path, mujoco_models: Dict[str, Tuple[Any, Any, str]],
    kinematics: List[Dict[str, Any]],
) -> None:
    for obj in kinematics:
        model, data, _ = mujoco_models[obj["folder"]]
        joined = adjacent(obj)
        for k, values in enumerate(states(exported / obj["folder"])):
            mj_set(model, data, values)
            mujoco.mj_forward(model, data)
            touching = [c for c in mj_contacts(model, data) if frozenset(c[:2]) not in joined]
            assert not touching, f"{obj['folder']} state {k}: {touching[:3]}"


def test_mujoco_gravity_keeps_joints_in_their_limits(
    exported: Path, mujoco_models: Dict[str, Tuple[Any, Any, str]],
    kinematics: List[Dict[str, Any]],
) -> None:
    for obj in kinematics:
        model, data, _ = mujoco_models[obj["folder"]]
        np.testing.assert_allclose(model.opt.gravity, GRAVITY)
        mujoco.mj_resetData(model, data)
        mj_set(model, data, states(exported / obj["folder"])[0])
        steps = int(round(1.0 / model.opt.timestep))
        mujoco.mj_step(model, data, nstep=steps)
        assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel)), obj["folder"]
        for joint in obj["joints"]:
            q = data.qpos[model.joint(joint["name"]).qposadr[0]]
            slack = 0.02 * (joint["upper"] - joint["lower"]) + 1e-4
            assert joint["lower"] - slack <= q <= joint["upper"] + slack, (
                f"{obj['folder']} {joint['name']}: {q} outside "
                f"[{joint['lower']}, {joint['upper']}] after 1 s"
            )


def with_position_actuators(folder: Path, joints: List[str], gains: List[float]) -> Any:
    """The object's MJCF with a position actuator on each of `joints` (critically damped,
    MuJoCo's `dampratio`) and gravity compensated on every body, implicit integration."""
    root = ET.parse(folder / "mobility.xml").getroot()
    compiler = root.find("compiler")
    assert compiler is not None
    compiler.set("meshdir", str(folder))
    option = root.find("option")
    assert option is not None
    option.set("integrator", "implicitfast")
    for body in root.iter("body"):
        body.set("gravcomp", "1")
    actuators = ET.SubElement(root, "actuator")
    for name, kp in zip(joints, gains):
        ET.SubElement(actuators, "position", {"joint": name, "kp": str(kp), "dampratio": "1"})
    return mujoco.MjModel.from_xml_string(ET.tostring(root, encoding="unicode"))


def test_mujoco_position_control_reaches_its_targets(
    exported: Path, mujoco_models: Dict[str, Tuple[Any, Any, str]],
    kinematics: List[Dict[str, Any]],
) -> None:
    """Position actuators on every joint but the mimic followers (their equality
    constraint drives them) take the object from its first state to its last in 2 s."""
    for obj in kinematics:
        plain, _, _ = mujoco_models[obj["folder"]]
        folder = exported / obj["folder"]
        drawn = states(folder)
        driven = [j["name"] for j in obj["joints"] if j["name"] not in mimic_followers(obj)]
        if not driven:
            continue
        # Stiffness from each joint's own inertia (a natural frequency of about 100 rad/s
        # at qpos0; coupled chains such as the desk lamp's need it that stiff to settle).
        gains = [1e4 * plain.dof_M0[plain.joint(n).dofadr[0]] for n in driven]
        model = with_position_actuators(folder, driven, gains)
        data = mujoco.MjData(model)
        mj_set(model, data, drawn[0])
        goal = np.array([drawn[-1][n] for n in driven])
        data.ctrl[:] = goal
        mujoco.mj_step(model, data, nstep=int(round(2.0 / model.opt.timestep)))
        reached = np.array([data.qpos[model.joint(n).qposadr[0]] for n in driven])
        for j in obj["joints"]:
            if j["name"] in driven:
                q, g = reached[driven.index(j["name"])], goal[driven.index(j["name"])]
                tolerance = 0.01 * (j["upper"] - j["lower"]) + 1e-4
                assert abs(q - g) <= tolerance, f"{obj['folder']} {j['name']}: {q} for {g}"


# -------------------------------------------------------------------- probe in a container


def open_values(obj: Dict[str, Any]) -> Dict[str, float]:
    """Every joint at its upper limit (doors open, drawers out); mimic followers follow."""
    values = {j["name"]: j["upper"] for j in obj["joints"]}
    for j in obj["joints"]:
        if j["mimic"]:
            m = j["mimic"]
            values[j["name"]] = m["offset"] + m["multiplier"] * values[m["joint"]]
    return values


def probe_xml(folder: Path, at: np.ndarray, radius: float, hull_of: Optional[str]) -> str:
    """The object's MJCF with a free sphere at `at`; with `hull_of`, that link collides
    through its visual mesh (MuJoCo takes the mesh's convex hull) instead of its hulls."""
    root = ET.parse(folder / "mobility.xml").getroot()
    compiler = root.find("compiler")
    assert compiler is not None
    compiler.set("meshdir", str(folder))
    world = root.find("worldbody")
    assert world is not None
    if hull_of is not None:
        body = next(b for b in world.iter("body") if b.get("name") == hull_of)
        visual = next(g for g in body.findall("geom") if g.get("class") == "visual")
        for g in [g for g in body.findall("geom") if g.get("class") == "collision"]:
            body.remove(g)
        body.append(ET.Element("geom", {"class": "collision", "mesh": visual.get("mesh", ""),
                                         "pos": visual.get("pos", "0 0 0")}))  # fmt: skip
    probe = ET.SubElement(world, "body", {"name": "probe", "pos": " ".join(map(str, at))})
    ET.SubElement(probe, "freejoint")
    # Rolling friction (condim 6): a ball that lands on an edge stops instead of rolling on
    # out of an open front.
    ET.SubElement(probe, "geom", {"name": "probe", "type": "sphere", "size": str(radius),
                                  "mass": "0.01", "condim": "6",
                                  "friction": "1 0.005 0.05"})  # fmt: skip
    return ET.tostring(root, encoding="unicode")


def link_hull(model: Any, data: Any, folder: Path, link: str) -> ConvexHull:
    """The convex hull of a link's posed visual mesh (its vertices are in the object's
    rest frame; the visual geom sits at minus the link frame's rest position)."""
    import trimesh

    mesh = trimesh.load(str(folder / f"textured_objs/{link}.obj"), force="mesh", process=False)
    # MuJoCo moves a mesh geom's frame to the mesh's centroid: read the file's position.
    root = ET.parse(folder / "mobility.xml").getroot()
    geom = next(g for g in root.iter("geom") if g.get("name") == f"{link}_visual")
    offset = np.eye(4)
    offset[:3, 3] = [float(x) for x in geom.get("pos", "0 0 0").split()]
    posed = trimesh.transform_points(mesh.vertices, mj_link_transform(model, data, link) @ offset)
    return ConvexHull(posed)


def hull_margin(hull: ConvexHull, point: np.ndarray) -> float:
    """How far inside the hull a point is (negative outside)."""
    return float(-np.max(hull.equations[:, :3] @ point + hull.equations[:, 3]))


def find_probe(
    folder: Path, obj: Dict[str, Any], link: str
) -> Optional[Tuple[np.ndarray, float, ConvexHull]]:
    """A sphere inside the opened link's visual hull (by its radius at least), just above
    the collision geometry below it, and clear of every other collision hull by half its
    radius: of a grid of candidates, the one farthest from the walls."""
    model, data = mj_load(folder)
    mj_set(model, data, open_values(obj))
    mujoco.mj_forward(model, data)
    hull = link_hull(model, data, folder, link)
    lo, hi = hull.points.min(axis=0), hull.points.max(axis=0)
    radius = 0.08 * float(np.min(hi - lo))
    grid = np.stack(np.meshgrid(*[np.linspace(a, b, 9)[1:-1] for a, b in zip(lo, hi)],
                                indexing="ij"), axis=-1).reshape(-1, 3)  # fmt: skip
    inside = [p for p in grid if hull_margin(hull, p) > 1.5 * radius]
    best: Optional[Tuple[float, np.ndarray]] = None
    sphere = mujoco.MjModel.from_xml_string(probe_xml(folder, np.zeros(3), radius, None))
    sdata = mujoco.MjData(sphere)
    mj_set(sphere, sdata, open_values(obj))
    mujoco.mj_kinematics(sphere, sdata)
    probe_geom = sphere.geom("probe").id
    probe_body = sphere.body("probe").id
    collision_group = np.array([0, 0, 0, 1, 0, 0], dtype=np.uint8)
    address = sphere.joint(sphere.body("probe").jntadr[0]).qposadr[0]
    down = GRAVITY / np.linalg.norm(GRAVITY)
    for p in inside:
        # Straight down onto the collision geometry below; set the sphere just above it.
        hit = np.array([-1], dtype=np.int32)
        drop = mujoco.mj_ray(sphere, sdata, p, down, collision_group, 1, probe_body, hit)
        if hit[0] < 0:
            continue
        rest = p + down * (drop - radius - 1e-3)
        if hull_margin(hull, rest) < radius:
            continue
        sdata.qpos[address:address + 3] = rest
        sdata.qpos[address + 3:address + 7] = [1, 0, 0, 0]
        mujoco.mj_kinematics(sphere, sdata)
        # A ray that starts inside a hull leaves through its far side: not a floor.
        if mujoco.mj_geomDistance(sphere, sdata, probe_geom, hit[0], 1.0, None) <= 0:
            continue
        walls = [g for g in range(sphere.ngeom)
                 if sphere.geom_contype[g] and g not in (probe_geom, hit[0])]  # fmt: skip
        clearance = min(mujoco.mj_geomDistance(sphere, sdata, probe_geom, g, 1.0, None)
                        for g in walls)  # fmt: skip
        if clearance > 0.5 * radius and (best is None or clearance > best[0]):
            best = (clearance, rest)
    return None if best is None else (best[1], radius, hull)


def drop_probe(folder: Path, obj: Dict[str, Any], at: np.ndarray, radius: float,
               hull_of: Optional[str]) -> Tuple[Any, Any, List[Any]]:  # fmt: skip
    """Drops the sphere for one second with every joint held open; returns the model, the
    data, and the sphere's contacts at the start."""
    model = mujoco.MjModel.from_xml_string(probe_xml(folder, at, radius, hull_of))
    data = mujoco.MjData(model)
    values = open_values(obj)
    mj_set(model, data, values)
    mujoco.mj_forward(model, data)
    probe = model.geom("probe").id
    first = [c for c in data.contact[: data.ncon] if probe in (c.geom1, c.geom2)]
    for _ in range(int(round(1.0 / model.opt.timestep))):
        mj_set_joints_only(model, data, values)
        mujoco.mj_step(model, data)
    return model, data, first


def mj_set_joints_only(model: Any, data: Any, values: Dict[str, float]) -> None:
    for name, value in values.items():
        joint = model.joint(name)
        data.qpos[joint.qposadr[0]] = value
        data.qvel[joint.dofadr[0]] = 0.0


def test_a_probe_rests_inside_every_opened_container(
    exported: Path, kinematics: List[Dict[str, Any]]
) -> None:
    checked = []
    for obj in kinematics:
        if obj["category"] not in CONTAINERS:
            continue
        folder = exported / obj["folder"]
        links = ["link_0"] + [j["child"] for j in obj["joints"]]
        for link in links:
            found = find_probe(folder, obj, link)
            if found is None:
                assert link not in CONTAINERS[obj["category"]], f"{obj['folder']} {link}: no room"
                continue
            at, radius, hull = found
            model, data, first = drop_probe(folder, obj, at, radius, None)
            probe = model.geom("probe").id
            centre = data.geom_xpos[probe]
            assert np.all(np.isfinite(centre)), obj["folder"]
            assert hull_margin(hull, centre) > 0.5 * radius, f"{obj['folder']} {link}: it left"
            assert np.linalg.norm(data.qvel[-6:-3]) < 0.05, f"{obj['folder']} {link}: not at rest"
            touching = [c for c in data.contact[: data.ncon] if probe in (c.geom1, c.geom2)]
            assert touching, f"{obj['folder']} {link}: the probe floats"
            for c in touching:
                normal = c.frame[:3]
                assert abs(normal[1]) > 0.95, (
                    f"{obj['folder']} {link}: the probe touches a wall (normal {normal})"
                )
            assert not first, f"{obj['folder']} {link}: the probe started in contact"
            # The visual mesh's hull as the link's collision: the probe starts inside it, and
            # does not come to rest where it was put.
            model, data, first = drop_probe(folder, obj, at, radius, link)
            centre = data.geom_xpos[model.geom("probe").id]
            assert first, f"{obj['folder']} {link}: the visual hull has room for the probe too"
            assert np.linalg.norm(centre - at) > radius, f"{obj['folder']} {link}: it stayed"
            checked.append((obj["category"], link))
    assert {c for c, _ in checked} == set(CONTAINERS)
