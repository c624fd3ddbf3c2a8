#!/usr/bin/python3
"""Regenerates the small real stereo scenes under tests/data/real/ from their full-size originals.

Every scene is the left view, the right view and the left view's ground-truth disparity (d = xLeft - xRight >= 0)
of a Middlebury stereo dataset. Each is cropped centrally to a multiple of its reduction factor and reduced in
factor x factor blocks. Colour: the box average of the 8-bit codes. Disparity: the median of the block's known
values, converted to pixels of the reduced image; unknown when fewer than half of the block is known. Written as
left.png, right.png (8-bit RGB) and disparity_left.png, a 16-bit grey PNG of disparity * 256 (0 = unknown), i.e.
s3d convert --depth-scale 0.00390625.

Where the originals are read from:
- aloe: Debian package opencv-doc, /usr/share/doc/opencv-doc/examples/data/aloe{L.jpg,R.jpg,GT.png}.
- motorcycle: Debian package python3-skimage, /usr/lib/python3/dist-packages/skimage/data/motorcycle_* (or the
  folder given with --skimage-data, e.g. an unpacked .deb).
- art, bowling1, flowerpots: the Middlebury archives, in a folder given with --middlebury DIR laid out as the
  stereo pages publish them: DIR/scenes2005/FullSize/Art/, DIR/scenes2006/HalfSize/Bowling1/ and
  DIR/scenes2006/HalfSize/Flowerpots/, each holding view1.png, view5.png and disp1.png.
Every original is checked against its SHA-256 below before use, so the output is reproducible.
Run: /usr/bin/python3 tests/data/real/make_real_scenes.py --middlebury DIR
(needs python3-numpy, python3-pil, opencv-doc, python3-skimage)
"""
import argparse
import hashlib
import os
import sys

import numpy as np
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
OPENCV_DATA = "/usr/share/doc/opencv-doc/examples/data"
SKIMAGE_DATA = "/usr/lib/python3/dist-packages/skimage/data"
DISPARITY_STEPS_PER_PX = 256

# Each scene: where its originals lie (a key of the source folders, a folder below it), the left view, right view
# and left disparity files, the disparity code per source pixel, the reduction factor, an explicit crop of the
# source (else central), and the SHA-256 of the three originals.
SCENES = {
    "aloe": dict(  # Middlebury 2006, full size; central 1280x1108 -> 320x277
        source=("opencv", ""), files=("aloeL.jpg", "aloeR.jpg", "aloeGT.png"), per_px=1.0, factor=4,
        crop=(slice(1, 1109), slice(1, 1281)),
        sha256=("cce5736808efe80d9f04b118dbb978c344d4345672b332718c3e039a3eeb8eee",
                "9b23100df31a846bc6e6a6545563b2b4120b948c9835c7d36cde00af77f4503e",
                "39ce4f3cb48d797d1091c5152f93361d8104298c337f8a1c134d87dda3442c04")),
    "art": dict(  # Middlebury 2005, full size 1390x1110 -> 231x185
        source=("middlebury", "scenes2005/FullSize/Art"), files=("view1.png", "view5.png", "disp1.png"),
        per_px=1.0, factor=6, crop=None,
        sha256=("4cb22b9db1ef50192fbea9944378f54a159a6fd051e7de2a03e9ca5eaece3172",
                "d8bd23c772dc9650f1bbc76af571b18433fe3e2f69d151ce21b8aa84561d526c",
                "4dfa1d682518486c9a3affe567951fc8ccd03c65825e79dfa8f91ecb9c5d2e48")),
    "bowling1": dict(  # Middlebury 2006, half size 626x555 (disparity code = 2 x pixels) -> 208x185
        source=("middlebury", "scenes2006/HalfSize/Bowling1"), files=("view1.png", "view5.png", "disp1.png"),
        per_px=2.0, factor=3, crop=None,
        sha256=("e2a8036e76bd1bcafd5468fa74c4cd40f478b0c965d47a121f6a214fa067479e",
                "a6582d35aac33cf2bdfaa089262c6fd9ec846ada081d83208992e45b35c2c4c1",
                "72cfa781a389abafe8c52f84d3465da1bbe53ab33d78a7a3a55b6a0d877430fa")),
    "flowerpots": dict(  # Middlebury 2006, half size 656x555 (disparity code = 2 x pixels) -> 218x185
        source=("middlebury", "scenes2006/HalfSize/Flowerpots"), files=("view1.png", "view5.png", "disp1.png"),
        per_px=2.0, factor=3, crop=None,
        sha256=("a73d4b17aeddc2f7b51dfc973ff73c7889e5a7d7a9bac123b148ef86bcd4acc5",
                "ab28c98ed8089952a10a042c0eee19e9c4667a1b78e89c3cb427b016cac60af7",
                "00cbe0d411ea4a093c676d98edff62b2dddaa1578ebe9b435329db692ee3d14b")),
    "motorcycle": dict(  # Middlebury 2014, quarter size 741x500 as scikit-image ships it -> 247x166
        source=("skimage", ""), files=("motorcycle_left.png", "motorcycle_right.png", "motorcycle_disp.npz"),
        per_px=1.0, factor=3, crop=None,
        sha256=("db18e9c4157617403c3537a6ba355dfeafe9a7eabb6b9b94cb33f6525dd49179",
                "5fc913ae870e42a4b662314bc904d1786bcad8e2f0b9b67dba5a229406357797",
                "2e49c8cebff3fa20359a0cc6880c82e1c03bbb106da81a177218281bc2f113d7")),
}


def blocks(array, factor):
    h, w = array.shape[0] // factor, array.shape[1] // factor
    array = array[: h * factor, : w * factor]
    return array.reshape(h, factor, w, factor, *array.shape[2:]).swapaxes(1, 2).reshape(h, w, factor * factor, *array.shape[2:])


def central_crop(shape, factor):
    h, w = shape[0] // factor * factor, shape[1] // factor * factor
    top, left = (shape[0] - h) // 2, (shape[1] - w) // 2
    return (slice(top, top + h), slice(left, left + w))


def reduce_color(path, crop, factor):
    image = np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)[crop]
    return np.clip(np.rint(blocks(image, factor).mean(axis=2)), 0, 255).astype(np.uint8)


def read_disparity(path, per_px):
    """The disparity in source pixels, NaN where unknown (0 in Middlebury PNGs, infinity in the 2014 maps)."""
    if path.endswith(".npz"):
        disparity = np.load(path)["arr_0"].astype(np.float64)
    else:
        disparity = np.asarray(Image.open(path), dtype=np.float64)
        disparity[disparity == 0] = np.nan
    disparity[~np.isfinite(disparity)] = np.nan
    return disparity / per_px


def reduce_disparity(disparity, crop, factor):
    cells = blocks(disparity[crop], factor)
    out = np.zeros(cells.shape[:2], dtype=np.uint16)
    for y in range(cells.shape[0]):
        for x in range(cells.shape[1]):
            values = cells[y, x][np.isfinite(cells[y, x])]
            if values.size * 2 >= factor * factor:
                out[y, x] = int(np.rint(np.median(values) / factor * DISPARITY_STEPS_PER_PX))
    return out


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def make_scene(name, spec, roots):
    root = roots[spec["source"][0]]
    if root is None:
        sys.exit(f"{name}: give the folder of the Middlebury archives with --middlebury DIR")
    paths = [os.path.join(root, spec["source"][1], f) for f in spec["files"]]
    for path in paths:
        if not os.path.isfile(path):
            sys.exit(f"{name}: missing original {path}")
    for path, digest in zip(paths, spec["sha256"]):
        if sha256(path) != digest:
            sys.exit(f"{name}: {path} is not the expected original (SHA-256 differs)")
    disparity = read_disparity(paths[2], spec["per_px"])
    crop = spec["crop"] or central_crop(disparity.shape, spec["factor"])
    folder = os.path.join(HERE, name)
    os.makedirs(folder, exist_ok=True)
    for path, out in zip(paths[:2], ("left.png", "right.png")):
        Image.fromarray(reduce_color(path, crop, spec["factor"])).save(os.path.join(folder, out), optimize=True)
    reduced = reduce_disparity(disparity, crop, spec["factor"])
    Image.fromarray(reduced).save(os.path.join(folder, "disparity_left.png"), optimize=True)
    known = reduced > 0
    print(f"{name}: {reduced.shape[1]}x{reduced.shape[0]}, disparity {reduced[known].min() / DISPARITY_STEPS_PER_PX:.2f}"
          f" .. {reduced.max() / DISPARITY_STEPS_PER_PX:.2f} px, unknown {100.0 * (1.0 - known.mean()):.1f} %")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--middlebury", help="folder holding scenes2005/ and scenes2006/ of the Middlebury archives")
    parser.add_argument("--skimage-data", default=SKIMAGE_DATA, help="scikit-image's data folder (motorcycle)")
    parser.add_argument("scenes", nargs="*", default=list(SCENES), help="scenes to make (default: all)")
    args = parser.parse_args()
    roots = {"opencv": OPENCV_DATA, "skimage": args.skimage_data, "middlebury": args.middlebury}
    for name in args.scenes:
        if name not in SCENES:
            sys.exit(f"unknown scene {name} (known: {', '.join(SCENES)})")
        make_scene(name, SCENES[name], roots)


if __name__ == "__main__":
    main()
