"""Makes the README's render pictures: one object per layout, its start and end state from
one view, read from the files `generator render` wrote in that layout.

    cargo build --release -p generator && python3 docs/images/render_pictures.py
"""

import pathlib
import subprocess
import tempfile

from PIL import Image

ROOT = pathlib.Path(__file__).resolve().parents[2]
GENERATOR = ROOT / "target" / "release" / "generator"


def render(layout, out):
    subprocess.run(
        [str(GENERATOR), "render", "--layout", layout, "-n", "6", "--views", "8",
         "--width", "400", "--height", "300", "--out", str(out)],
        check=True,
    )


def side_by_side(paths, target):
    images = [Image.open(p).convert("RGBA") for p in paths]
    w, h = images[0].size
    out = Image.new("RGBA", (w * len(images), h), (255, 255, 255, 255))
    for i, image in enumerate(images):
        out.alpha_composite(image, (i * w, 0))
    out.convert("RGB").save(target, optimize=True)
    print("wrote", target)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        render("paris", tmp / "paris")
        base = tmp / "paris" / "load" / "sapien" / "laptop" / "000000_laptop"
        side_by_side([base / s / "train" / "0002.png" for s in ("start", "end")],
                     ROOT / "docs" / "images" / "render_paris.png")
        render("dta", tmp / "dta")
        base = tmp / "dta" / "000001_cabinet" / "color_segmented"
        side_by_side([base / f"{t:05d}_0002.png" for t in (0, 1)],
                     ROOT / "docs" / "images" / "render_dta.png")
        render("artgs", tmp / "artgs")
        base = tmp / "artgs" / "data" / "part_induction" / "render" / "000005_desk_lamp"
        side_by_side([base / s / "train" / "rgba" / "0002.png" for s in ("start", "end")],
                     ROOT / "docs" / "images" / "render_artgs.png")


if __name__ == "__main__":
    main()
