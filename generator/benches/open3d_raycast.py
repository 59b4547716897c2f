"""Rays per second: Open3D's RaycastingScene (Embree) against our renderer's ray caster,
side by side in one run, on the same meshes, cameras and image size (a DigitalTwinArt-layout
render: gt/<state>/<state>_rotate.ply, cam_K.txt, init_keyframes.yml).

    python3 -m pip install open3d-cpu numpy
    cargo build --release -p generator --example raycast_rate
    target/release/generator render --layout dta -n 8 --views 8 --out /tmp/rays
    python3 generator/benches/open3d_raycast.py /tmp/rays
"""

import pathlib
import subprocess
import sys
import time

import numpy as np
import open3d as o3d

ROOT = pathlib.Path(__file__).resolve().parents[2]


def read_ply(path):
    text = path.read_text()
    header, body = text.split("end_header\n", 1)
    counts = {l.split()[1]: int(l.split()[2]) for l in header.splitlines() if l.startswith("element")}
    rows = body.splitlines()
    nv, nf = counts["vertex"], counts["face"]
    vertices = np.array([[float(x) for x in r.split()] for r in rows[:nv]], dtype=np.float32)
    faces = np.array([[int(x) for x in r.split()[1:]] for r in rows[nv:nv + nf]], dtype=np.uint32)
    return vertices, faces


def frames(folder):
    lines = (folder / "init_keyframes.yml").read_text().splitlines()
    for i in range(0, len(lines), 3):
        stem = lines[i][len("frame_"):-1]
        m = np.array([float(x) for x in lines[i + 1].split("[")[1].rstrip("]").split(",")]).reshape(4, 4)
        yield stem, int(lines[i + 2].split(":")[1]), m


def main(root):
    root = pathlib.Path(root)
    rays_total, hits, seconds = 0, 0, 0.0
    for folder in sorted(p for p in root.iterdir() if (p / "cam_K.txt").exists()):
        k = np.loadtxt(folder / "cam_K.txt").reshape(3, 3)
        poses = list(frames(folder))
        w, h = int(round(2 * k[0, 2])), int(round(2 * k[1, 2]))
        u, v = np.meshgrid(np.arange(w), np.arange(h), indexing="xy")
        local = np.stack([(u - k[0, 2]) / k[0, 0], -(v - k[1, 2]) / k[1, 1], -np.ones_like(u, dtype=float)], -1).reshape(-1, 3)
        for state, name in enumerate(["start", "end"]):
            vertices, faces = read_ply(folder / "gt" / name / f"{name}_rotate.ply")
            scene = o3d.t.geometry.RaycastingScene()
            scene.add_triangles(o3d.core.Tensor(vertices), o3d.core.Tensor(faces))
            rays = []
            for _, t, m in poses:
                if t != state:
                    continue
                d = local @ m[:3, :3].T
                d /= np.linalg.norm(d, axis=1, keepdims=True)
                o = np.broadcast_to(m[:3, 3], d.shape)
                rays.append(np.concatenate([o, d], 1).astype(np.float32))
            rays = o3d.core.Tensor(np.concatenate(rays))
            scene.cast_rays(rays[:1])  # builds the BVH, as ours is built before timing
            started = time.perf_counter()
            result = scene.cast_rays(rays)
            seconds += time.perf_counter() - started
            hits += int(np.isfinite(result["t_hit"].numpy()).sum())
            rays_total += rays.shape[0]
    print(f"open3d  rays {rays_total} hits {hits} seconds {seconds:.3f} rays_per_second {rays_total / seconds:.0f}")
    ours = subprocess.run([str(ROOT / "target" / "release" / "examples" / "raycast_rate"), str(root)],
                          check=True, capture_output=True, text=True).stdout.strip()
    for line in ours.splitlines():
        print("ours   ", line)


if __name__ == "__main__":
    main(sys.argv[1])
