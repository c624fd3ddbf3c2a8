#!/usr/bin/python3
"""Regenerates the small real stereo scenes under tests/data/real/ from the Debian package opencv-doc.

Aloe (Middlebury 2006, full size 1282x1110, ground-truth disparity of the left view in pixels, 0 = unknown):
the central 1280x1108 is reduced 4x4 -> 320x277. Color: box average of the 8-bit codes. Disparity: the median
of the block's known values divided by 4, unknown when fewer than half of the block is known; written as a 16-bit
grey PNG of disparity * 256 (0 = unknown), i.e. s3d convert --depth-scale 0.00390625.
Run: /usr/bin/python3 tests/data/real/make_real_scenes.py  (needs python3-numpy, python3-pil, opencv-doc)
"""
import os

import numpy as np
from PIL import Image

SOURCE = "/usr/share/doc/opencv-doc/examples/data"
HERE = os.path.dirname(os.path.abspath(__file__))
FACTOR = 4
DISPARITY_STEPS_PER_PX = 256


def blocks(array, factor):
    h, w = array.shape[0] // factor, array.shape[1] // factor
    array = array[: h * factor, : w * factor]
    return array.reshape(h, factor, w, factor, *array.shape[2:]).swapaxes(1, 2).reshape(h, w, factor * factor, *array.shape[2:])


def reduce_color(path, crop):
    image = np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)[crop]
    return np.clip(np.rint(blocks(image, FACTOR).mean(axis=2)), 0, 255).astype(np.uint8)


def reduce_disparity(path, crop):
    disparity = np.asarray(Image.open(path), dtype=np.float64)[crop]
    cells = blocks(disparity, FACTOR)
    known = cells > 0
    out = np.zeros(cells.shape[:2], dtype=np.uint16)
    for y in range(cells.shape[0]):
        for x in range(cells.shape[1]):
            values = cells[y, x][known[y, x]]
            if values.size * 2 >= FACTOR * FACTOR:
                out[y, x] = int(np.rint(np.median(values) / FACTOR * DISPARITY_STEPS_PER_PX))
    return out


def make_aloe():
    folder = os.path.join(HERE, "aloe")
    os.makedirs(folder, exist_ok=True)
    crop = (slice(1, 1109), slice(1, 1281))  # 1282x1110 -> 1280x1108, a multiple of 4
    Image.fromarray(reduce_color(os.path.join(SOURCE, "aloeL.jpg"), crop)).save(os.path.join(folder, "left.png"), optimize=True)
    Image.fromarray(reduce_color(os.path.join(SOURCE, "aloeR.jpg"), crop)).save(os.path.join(folder, "right.png"), optimize=True)
    disparity = reduce_disparity(os.path.join(SOURCE, "aloeGT.png"), crop)
    Image.fromarray(disparity).save(os.path.join(folder, "disparity_left.png"), optimize=True)


if __name__ == "__main__":
    make_aloe()
