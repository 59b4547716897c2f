"""Makes the README's collision picture: one exported cabinet, its door and drawer open, the
visual meshes (left) beside the convex collision hulls every format uses (right, one colour
per hull), posed by MuJoCo from `mobility.xml`.

    pip install mujoco trimesh matplotlib && python3 docs/images/collision_picture.py
"""

import pathlib
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import mujoco  # noqa: E402
import numpy as np  # noqa: E402
import trimesh  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1].parent
TARGET = ROOT / "docs" / "images" / "collision_hulls.png"


def export(out):
    subprocess.run(
        ["cargo", "run", "-q", "-p", "generator", "--", "export-objects",
         "--categories", "cabinet", "-n", "1", "--seed", "3", "--out", str(out)],
        cwd=ROOT, check=True,
    )  # fmt: skip
    return next(p for p in out.iterdir() if p.is_dir())


def posed(model, data, link, path):
    """A mesh file of `link` (object rest frame) in the world, as MuJoCo poses the link."""
    mesh = trimesh.load(str(path), force="mesh", process=False)
    frame = np.eye(4)
    frame[:3, :3] = data.body(link).xmat.reshape(3, 3)
    frame[:3, 3] = data.body(link).xpos
    # Rest-frame vertices into the link frame: minus the link frame's rest position.
    return trimesh.transform_points(mesh.vertices - rest_origins[link], frame), mesh.faces


def draw(ax, pieces, title):
    for (vertices, faces), colour in pieces:
        poly = Poly3DCollection(vertices[faces][:, :, [0, 2, 1]], facecolor=colour,
                                edgecolor=(0, 0, 0, 0.15), linewidths=0.2)  # fmt: skip
        ax.add_collection3d(poly)
    every = np.concatenate([v for (v, _), _ in pieces])[:, [0, 2, 1]]
    lo, hi = every.min(axis=0), every.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for axis, c in zip("xyz", centre):
        getattr(ax, f"set_{axis}lim")(c - half, c + half)
    ax.view_init(elev=22, azim=60)
    ax.set_axis_off()
    ax.set_title(title, fontsize=10)


with tempfile.TemporaryDirectory() as tmp:
    folder = export(pathlib.Path(tmp) / "objects")
    model = mujoco.MjModel.from_xml_path(str(folder / "mobility.xml"))
    data = mujoco.MjData(model)
    for j in range(model.njnt):
        data.qpos[model.jnt_qposadr[j]] = model.jnt_range[j][1]  # every joint open
    mujoco.mj_kinematics(model, data)
    links = [model.body(b).name for b in range(1, model.nbody)]
    # Each link frame's rest position: MuJoCo's body positions are relative to the parent.
    rest_origins = {}
    for b in range(1, model.nbody):
        parent = model.body_parentid[b]
        base = rest_origins.get(model.body(parent).name, np.zeros(3))
        rest_origins[model.body(b).name] = base + model.body_pos[b]
    visual = [(posed(model, data, l, folder / f"textured_objs/{l}.obj"), (0.75, 0.75, 0.78, 1.0))
              for l in links]  # fmt: skip
    colours = plt.get_cmap("tab20")
    hulls = []
    for l in links:
        for k, path in enumerate(sorted((folder / "collision").glob(f"{l}_hull_*.obj"))):
            hulls.append((posed(model, data, l, path), colours(len(hulls) % 20)))
    figure = plt.figure(figsize=(8, 4.2), dpi=110)
    draw(figure.add_subplot(1, 2, 1, projection="3d"), visual, "visual meshes")
    draw(figure.add_subplot(1, 2, 2, projection="3d"), hulls,
         f"{len(hulls)} convex collision hulls")  # fmt: skip
    figure.tight_layout()
    figure.savefig(TARGET)
    print(f"wrote {TARGET}")
