"""Objects exported by `generator export-objects`, checked by the simulators themselves:
MuJoCo loads `mobility.xml`, PyBullet and SAPIEN load `mobility.urdf`, usd-core reads
`mobility.usda` (with UsdPhysics' own parser). One object of every category, and for each:

- it loads without a warning;
- forward kinematics at several joint configurations agrees with the generator's
  (`generator/examples/kinematics_json.rs`) to 1e-5 (plus a relative 1e-6 for the 46 m
  windmill: the generator's kinematics is single precision);
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
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional, Tuple

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco", reason="pip install mujoco (the `sim` extra)")
pybullet = pytest.importorskip("pybullet", reason="pip install pybullet (the `sim` extra)")
pxr = pytest.importorskip("pxr", reason="pip install usd-core (the `sim` extra)")
from pxr import Gf, Usd, UsdGeom, UsdPhysics  # noqa: E402
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
PYBULLET_MARGIN = 1e-3  # the collision margin PyBullet gives each convex mesh shape


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
    """To FK_TOLERANCE, plus a relative 1e-6: the generator's kinematics and SAPIEN's poses
    are single precision, and the windmill's hub is 46 m up (1e-5 off there)."""
    np.testing.assert_allclose(
        actual, np.asarray(expected), atol=FK_TOLERANCE, rtol=1e-6, err_msg=what
    )


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
            body = model.body(link).id
            colliding = [g for g in range(model.ngeom)
                         if model.geom_bodyid[g] == body and model.geom_contype[g]]  # fmt: skip
            assert len(colliding) == physics["hulls"], f"{obj['folder']} {link}"


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


# -------------------------------------------------------------------------------- PyBullet


@pytest.fixture(scope="module")
def bullet() -> Iterator[Any]:
    """A headless PyBullet client."""
    client = pybullet.connect(pybullet.DIRECT)
    yield client
    pybullet.disconnect(client)


def pb_load(client: int, folder: Path) -> Tuple[int, Dict[str, int], str]:
    """The object (fixed base), its joints' indices by name (the index of a joint is that
    of its child link), and what loading printed."""
    pybullet.resetSimulation(physicsClientId=client)
    with captured_output() as printed:
        body = pybullet.loadURDF(
            str(folder / "mobility.urdf"), useFixedBase=True,
            flags=pybullet.URDF_USE_INERTIA_FROM_FILE, physicsClientId=client,
        )
    joints = {}
    for i in range(pybullet.getNumJoints(body, physicsClientId=client)):
        info = pybullet.getJointInfo(body, i, physicsClientId=client)
        joints[info[1].decode()] = i
    return body, joints, printed[0]


def pb_link_index(client: int, body: int, link: str) -> int:
    if link == "base":
        return -1
    for i in range(pybullet.getNumJoints(body, physicsClientId=client)):
        if pybullet.getJointInfo(body, i, physicsClientId=client)[12].decode() == link:
            return i
    raise KeyError(link)


def pb_set(client: int, body: int, joints: Dict[str, int], values: Dict[str, float]) -> None:
    for name, value in values.items():
        pybullet.resetJointState(body, joints[name], value, 0.0, physicsClientId=client)


def pb_link_transform(client: int, body: int, index: int) -> np.ndarray:
    state = pybullet.getLinkState(body, index, computeForwardKinematics=True,
                                  physicsClientId=client)  # fmt: skip
    t = np.eye(4)
    t[:3, :3] = np.asarray(pybullet.getMatrixFromQuaternion(state[5])).reshape(3, 3)
    t[:3, 3] = state[4]
    return t


def test_pybullet_loads_every_category_with_matching_kinematics(
    bullet: int, exported: Path, kinematics: List[Dict[str, Any]]
) -> None:
    for obj in kinematics:
        folder = exported / obj["folder"]
        body, joints, printed = pb_load(bullet, folder)
        assert printed.strip() == "", f"{obj['folder']}: {printed}"
        meta = json.loads((folder / "meta.json").read_text())
        for link, physics in meta["link_physics"].items():
            index = pb_link_index(bullet, body, link)
            mass = pybullet.getDynamicsInfo(body, index, physicsClientId=bullet)[0]
            assert mass == pytest.approx(physics["mass"], rel=1e-6), f"{obj['folder']} {link}"
            shapes = pybullet.getCollisionShapeData(body, index, physicsClientId=bullet)
            assert len(shapes) == physics["hulls"], f"{obj['folder']} {link}: collision shapes"
        for joint in obj["joints"]:
            info = pybullet.getJointInfo(body, joints[joint["name"]], physicsClientId=bullet)
            kind = {"revolute": pybullet.JOINT_REVOLUTE, "prismatic": pybullet.JOINT_PRISMATIC}
            assert info[2] == kind[joint["type"]]
            np.testing.assert_allclose(info[8:10], [joint["lower"], joint["upper"]], atol=1e-6)
            # PyBullet gives the axis in the child's inertial frame (principal axes, as Bullet
            # diagonalises the inertia): into the link frame.
            inertial = pybullet.getDynamicsInfo(body, joints[joint["name"]], physicsClientId=bullet)
            rotation = np.asarray(pybullet.getMatrixFromQuaternion(inertial[4])).reshape(3, 3)
            np.testing.assert_allclose(rotation @ info[13], joint["axis"], atol=1e-5)
        for state in obj["states"]:
            pb_set(bullet, body, joints, state["values"])
            for link, expected in state["links"].items():
                index = pb_link_index(bullet, body, link)
                assert_pose(pb_link_transform(bullet, body, index), expected["transform"],
                            f"{obj['folder']} {link}")  # fmt: skip


def test_pybullet_contacts_gravity_and_position_control(
    bullet: int, exported: Path, kinematics: List[Dict[str, Any]]
) -> None:
    """At rest no unjoined links touch; one second under gravity keeps every joint in its
    limits; position motors take the object from its first state to its last."""
    for obj in kinematics:
        folder = exported / obj["folder"]
        body, joints, _ = pb_load(bullet, folder)
        links = {pb_link_index(bullet, body, f"link_{i}"): f"link_{i}"
                 for i in range(len(obj["joints"]) + 1)}  # fmt: skip
        joined = adjacent(obj)
        drawn = states(folder)
        for k, values in enumerate(drawn):
            pb_set(bullet, body, joints, values)
            for a in links:
                for b in links:
                    if a >= b or frozenset((links[a], links[b])) in joined:
                        continue
                    close = pybullet.getClosestPoints(
                        body, body, 0.0, linkIndexA=a, linkIndexB=b, physicsClientId=bullet
                    )
                    # PyBullet's distances include each convex shape's 1 mm collision margin.
                    deepest = min((c[8] for c in close), default=0.0)
                    assert deepest > -PENETRATION - 2 * PYBULLET_MARGIN, (
                        f"{obj['folder']} state {k}: {links[a]} and {links[b]} overlap by {-deepest}"
                    )
        # Gravity, every joint free (PyBullet holds joints with velocity motors by default).
        # PyBullet caps the force of a joint limit (100 N s per step by default), too little
        # for the excavator's 6 t boom: raised, as docs/SIMULATORS.md tells users to.
        pybullet.setGravity(*GRAVITY, physicsClientId=bullet)
        pb_set(bullet, body, joints, drawn[0])
        for i in joints.values():
            pybullet.setJointMotorControl2(body, i, pybullet.VELOCITY_CONTROL, force=0.0,
                                           physicsClientId=bullet)  # fmt: skip
            pybullet.changeDynamics(body, i, jointLimitForce=1e8, physicsClientId=bullet)
        for _ in range(240):
            pybullet.stepSimulation(physicsClientId=bullet)
        for joint in obj["joints"]:
            q = pybullet.getJointState(body, joints[joint["name"]], physicsClientId=bullet)[0]
            slack = 0.02 * (joint["upper"] - joint["lower"]) + 1e-4
            assert np.isfinite(q), f"{obj['folder']} {joint['name']}"
            assert joint["lower"] - slack <= q <= joint["upper"] + slack, (
                f"{obj['folder']} {joint['name']}: {q} after 1 s"
            )
        # Position control to the last state (PyBullet ignores URDF mimic tags: every joint
        # gets its own motor, the followers' targets satisfying their coupling).
        pb_set(bullet, body, joints, drawn[0])
        for name, i in joints.items():
            if name in drawn[-1]:
                pybullet.setJointMotorControl2(
                    body, i, pybullet.POSITION_CONTROL, targetPosition=drawn[-1][name],
                    force=1e12, positionGain=0.5, velocityGain=1.0, physicsClientId=bullet,
                )
        for _ in range(480):
            pybullet.stepSimulation(physicsClientId=bullet)
        for joint in obj["joints"]:
            q = pybullet.getJointState(body, joints[joint["name"]], physicsClientId=bullet)[0]
            tolerance = 0.01 * (joint["upper"] - joint["lower"]) + 1e-4
            assert abs(q - drawn[-1][joint["name"]]) <= tolerance, (
                f"{obj['folder']} {joint['name']}: {q} for {drawn[-1][joint['name']]}"
            )
        pybullet.setGravity(0, 0, 0, physicsClientId=bullet)


# ------------------------------------------------------------------------------------- USD


def gf_matrix(position: Any, orientation: Any) -> np.ndarray:
    """A pose from a Gf position and quaternion (column-vector convention)."""
    t = np.eye(4)
    t[:3, :3] = np.asarray(Gf.Matrix3d(Gf.Rotation(Gf.Quatd(orientation)))).T
    t[:3, 3] = [float(x) for x in position]
    return t


def joint_motion(kind: str, value: float) -> np.ndarray:
    """Motion about or along the joint frame's X axis."""
    t = np.eye(4)
    if kind == "revolute":
        c, s = np.cos(value), np.sin(value)
        t[1:3, 1:3] = [[c, -s], [s, c]]
    else:
        t[0, 3] = value
    return t


def test_usd_parses_with_usdphysics_and_agrees_with_the_generator(
    exported: Path, kinematics: List[Dict[str, Any]]
) -> None:
    """UsdPhysics' own parser (the one Isaac's PhysX plug-in builds on) reads every object:
    one articulation, a rigid body per link with its mass, its hulls as convex colliders,
    the joints with the generator's names, types, axes and limits; forward kinematics
    composed from the parsed joint frames is the generator's."""
    for obj in kinematics:
        folder = exported / obj["folder"]
        with captured_output() as printed:
            stage = Usd.Stage.Open(str(folder / "mobility.usda"))
            parsed = UsdPhysics.UsdPhysicsLoadStageFromPrimRange(stage, ["/"])
        assert printed[0].strip() == "", f"{obj['folder']}: {printed[0]}"
        assert str(UsdGeom.GetStageUpAxis(stage)) == "Y"
        found = {str(k).split(".")[-1]: v for k, v in parsed.items()}
        assert len(found["Articulation"][0]) == 1 and len(found["Scene"][0]) == 1
        meta = json.loads((folder / "meta.json").read_text())
        root = stage.GetDefaultPrim().GetPath()
        bodies = {str(p).split("/")[-1] for p in found["RigidBody"][0]}
        assert bodies == set(meta["link_physics"]), obj["folder"]
        for link, physics in meta["link_physics"].items():
            prim = stage.GetPrimAtPath(root.AppendChild(link))
            mass = UsdPhysics.MassAPI(prim).GetMassAttr().Get()
            assert mass == pytest.approx(physics["mass"], rel=1e-6), f"{obj['folder']} {link}"
        hulls = [p for p in found["MeshShape"][0]]
        assert len(hulls) == sum(p["hulls"] for p in meta["link_physics"].values())
        for desc in found["MeshShape"][1]:
            assert desc.approximation == UsdPhysics.Tokens.convexHull
        descs: Dict[str, Tuple[str, Any]] = {}
        for kind in ["RevoluteJoint", "PrismaticJoint"]:
            for path, desc in zip(*found.get(kind, ([], []))):
                name = stage.GetPrimAtPath(path).GetAttribute("part_induction:name").Get()
                descs[name] = ("revolute" if kind == "RevoluteJoint" else "prismatic", desc)
        assert set(descs) == {j["name"] for j in obj["joints"]}, obj["folder"]
        for joint in obj["joints"]:
            kind, desc = descs[joint["name"]]
            assert kind == joint["type"]
            assert str(desc.body0).split("/")[-1] == joint["parent"]
            assert str(desc.body1).split("/")[-1] == joint["child"]
            assert desc.axis == UsdPhysics.Axis.X
            frame = gf_matrix(desc.localPose0Position, desc.localPose0Orientation)
            np.testing.assert_allclose(frame[:3, 0], joint["axis"], atol=1e-6)
            scale = np.pi / 180 if kind == "revolute" else 1.0
            np.testing.assert_allclose(
                [desc.limit.lower * scale, desc.limit.upper * scale],
                [joint["lower"], joint["upper"]], atol=1e-6,
            )
        by_child = {d[1].body1: d for d in descs.values()}
        for state in obj["states"]:
            world: Dict[str, np.ndarray] = {"link_0": np.eye(4)}

            def pose(link: str) -> np.ndarray:
                if link not in world:
                    kind, desc = by_child[root.AppendChild(link)]
                    name = next(n for n, d in descs.items() if d[1] is desc)
                    world[link] = (
                        pose(str(desc.body0).split("/")[-1])
                        @ gf_matrix(desc.localPose0Position, desc.localPose0Orientation)
                        @ joint_motion(kind, state["values"][name])
                        @ np.linalg.inv(gf_matrix(desc.localPose1Position, desc.localPose1Orientation))
                    )
                return world[link]

            for link, expected in state["links"].items():
                assert_pose(pose(link), expected["transform"], f"{obj['folder']} {link}")


# ----------------------------------------------------------------------------------- SAPIEN


def test_sapien_loads_every_category_simulates_and_drives_it(
    exported: Path, kinematics: List[Dict[str, Any]]
) -> None:
    """SAPIEN 3 (PhysX) loads every URDF as an articulation with the generator's joints,
    masses and forward kinematics; a second under gravity keeps every joint in its limits;
    joint drives take the object from its first state to its last. There is no rendering
    device here: the loader's visual shapes are dropped before building (the collision
    shapes, masses and joints are what is checked)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # "Failed to find system libvulkan" on import
        sapien = pytest.importorskip("sapien", reason="pip install sapien (the `sim` extra)")
    config = sapien.physx.PhysxSceneConfig()
    config.gravity = GRAVITY.tolist()
    sapien.physx.set_scene_config(config)
    for obj in kinematics:
        folder = exported / obj["folder"]
        scene = sapien.Scene([sapien.physx.PhysxCpuSystem()])
        scene.set_timestep(1 / 240)
        loader = scene.create_urdf_loader()
        loader.fix_root_link = True
        with captured_output() as printed:
            builders, _, _ = loader.parse(str(folder / "mobility.urdf"))
            assert len(builders) == 1, obj["folder"]
            for link in builders[0].link_builders:
                link.visual_records = []
            robot = builders[0].build()
        assert printed[0].strip() == "", f"{obj['folder']}: {printed[0]}"
        names = [j.name for j in robot.active_joints]
        assert set(names) == {j["name"] for j in obj["joints"]}, obj["folder"]
        limits = dict(zip(names, robot.qlimits.tolist()))
        for joint in obj["joints"]:
            np.testing.assert_allclose(limits[joint["name"]], [joint["lower"], joint["upper"]],
                                       atol=1e-6)  # fmt: skip
        meta = json.loads((folder / "meta.json").read_text())
        links = {link.name: link for link in robot.links}
        for link, physics in meta["link_physics"].items():
            assert links[link].mass == pytest.approx(physics["mass"], rel=1e-5)
            assert len(links[link].collision_shapes) == physics["hulls"], obj["folder"]
        for state in obj["states"]:
            robot.set_qpos(np.array([state["values"][n] for n in names]))
            for link, expected in state["links"].items():
                assert_pose(links[link].entity_pose.to_transformation_matrix(),
                            expected["transform"], f"{obj['folder']} {link}")  # fmt: skip
        drawn = states(folder)
        robot.set_qpos(np.array([drawn[0][n] for n in names]))
        robot.set_qvel(np.zeros(len(names)))
        for _ in range(240):
            scene.step()
        for name, q in zip(names, robot.qpos):
            lo, hi = limits[name]
            slack = 0.02 * (hi - lo) + 1e-4
            assert np.isfinite(q) and lo - slack <= q <= hi + slack, f"{obj['folder']} {name}: {q}"
        robot.set_qpos(np.array([drawn[0][n] for n in names]))
        robot.set_qvel(np.zeros(len(names)))
        for joint, name in zip(robot.active_joints, names):
            inertia = max(links[joint.child_link.name].mass, 1e-6)
            joint.set_drive_property(stiffness=1e5 * inertia, damping=1e3 * inertia)
            joint.set_drive_target(drawn[-1][name])
        for _ in range(480):
            robot.set_qf(robot.compute_passive_force(gravity=True))
            scene.step()
        for name, q in zip(names, robot.qpos):
            lo, hi = limits[name]
            assert abs(q - drawn[-1][name]) <= 0.01 * (hi - lo) + 1e-4, (
                f"{obj['folder']} {name}: {q} for {drawn[-1][name]}"
            )


def test_pybullet_a_probe_rests_inside_every_opened_container(
    bullet: int, exported: Path, kinematics: List[Dict[str, Any]]
) -> None:
    """The same spots as MuJoCo's probe test, in PyBullet: the sphere settles on the floor
    it was set on, inside the container, touching no wall."""
    checked = 0
    for obj in kinematics:
        if obj["category"] not in CONTAINERS:
            continue
        folder = exported / obj["folder"]
        for link in CONTAINERS[obj["category"]]:
            found = find_probe(folder, obj, link)
            assert found is not None, f"{obj['folder']} {link}: no room"
            at, radius, hull = found
            body, joints, _ = pb_load(bullet, folder)
            values = open_values(obj)
            pb_set(bullet, body, joints, values)
            for name, i in joints.items():
                if name in values:  # held open
                    pybullet.setJointMotorControl2(
                        body, i, pybullet.POSITION_CONTROL, targetPosition=values[name],
                        force=1e12, physicsClientId=bullet,
                    )
            shape = pybullet.createCollisionShape(pybullet.GEOM_SPHERE, radius=radius,
                                                  physicsClientId=bullet)  # fmt: skip
            probe = pybullet.createMultiBody(0.01, shape, basePosition=at.tolist(),
                                             physicsClientId=bullet)  # fmt: skip
            pybullet.changeDynamics(probe, -1, rollingFriction=0.005, spinningFriction=0.005,
                                    physicsClientId=bullet)  # fmt: skip
            pybullet.setGravity(*GRAVITY, physicsClientId=bullet)
            for _ in range(240):
                pybullet.stepSimulation(physicsClientId=bullet)
            centre = np.asarray(pybullet.getBasePositionAndOrientation(probe, bullet)[0])
            assert hull_margin(hull, centre) > 0.5 * radius, f"{obj['folder']} {link}: it left"
            speed = np.linalg.norm(pybullet.getBaseVelocity(probe, bullet)[0])
            assert speed < 0.05, f"{obj['folder']} {link}: not at rest ({speed} m/s)"
            contacts = pybullet.getContactPoints(bodyA=probe, physicsClientId=bullet)
            assert contacts, f"{obj['folder']} {link}: the probe floats"
            for c in contacts:
                assert abs(c[7][1]) > 0.95, f"{obj['folder']} {link}: a wall ({c[7]})"
            pybullet.setGravity(0, 0, 0, physicsClientId=bullet)
            checked += 1
    assert checked == sum(len(links) for links in CONTAINERS.values())
