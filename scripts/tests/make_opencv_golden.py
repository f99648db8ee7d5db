#!/usr/bin/env python3
"""Writes tests/data/opencv/golden.txt: what OpenCV's cv2.cvtColor(COLOR_RGB2GRAY) and
cv2.resize(INTER_AREA) give for deterministic uint8 images, the values
tests/wrappers/test_opencv_image_ops.cpp checks src/rlrun/wrappers/opencv_image_ops.cpp against.

Needs OpenCV's Python module (Debian: apt install python3-opencv). Images come from a 64-bit
LCG both sides can compute: x <- x * 6364136223846793005 + 1442695040888963407 (mod 2^64), a
pixel is x >> 56. Each line: an operation, the sizes, the seed, then the output's bytes in hex.
  resize H W C h w seed HEX     cv2.resize(image (H, W, C), (w, h), INTER_AREA)
  gray H W seed HEX             cv2.cvtColor(image (H, W, 3), COLOR_RGB2GRAY)
"""
import os
import sys

import cv2
import numpy as np

MASK = (1 << 64) - 1


def image(shape, seed):
    x = seed
    values = []
    for _ in range(int(np.prod(shape))):
        x = (x * 6364136223846793005 + 1442695040888963407) & MASK
        values.append(x >> 56)
    return np.array(values, dtype=np.uint8).reshape(shape)


RESIZES = [
    # (H, W, C, h, w): CarRacing to the zoo's 64 and to 84, 2x2 blocks (vector path for 1/3/4
    # channels, scalar for 2), 3x3 and 2x3 blocks, Atari's 210x160 to 84, CartPole's 400x600
    # render to 84, odd sizes, a one-sided shrink, no change.
    (96, 96, 3, 64, 64), (96, 96, 3, 84, 84), (96, 96, 1, 64, 64), (96, 96, 1, 48, 48),
    (96, 96, 3, 48, 48), (96, 96, 4, 48, 48), (96, 96, 2, 48, 48), (90, 90, 1, 30, 30),
    (60, 90, 3, 30, 30), (210, 160, 1, 84, 84), (400, 600, 3, 84, 84), (400, 600, 1, 84, 84),
    (37, 23, 4, 11, 7), (50, 50, 2, 17, 33), (84, 84, 1, 84, 84), (20, 30, 3, 20, 15),
]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "..", "tests", "data", "opencv", "golden.txt")
    lines = [f"# cv2 {cv2.__version__}, numpy {np.__version__}: scripts/tests/make_opencv_golden.py"]
    for seed, (H, W, C, h, w) in enumerate(RESIZES, start=1):
        src = image((H, W, C), seed)
        dst = cv2.resize(src if C > 1 else src[:, :, 0], (w, h), interpolation=cv2.INTER_AREA)
        lines.append(f"resize {H} {W} {C} {h} {w} {seed} {dst.tobytes().hex()}")
    for seed, (H, W) in enumerate([(96, 96), (7, 5)], start=100):
        src = image((H, W, 3), seed)
        lines.append(f"gray {H} {W} {seed} {cv2.cvtColor(src, cv2.COLOR_RGB2GRAY).tobytes().hex()}")
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
