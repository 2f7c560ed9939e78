#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""`vis4gs train` on a tiny NeRF-synthetic folder (issue 19).

Writes RGBA PNGs of a grey disk on a transparent background (numpy + zlib), the Blender
transforms_train.json / transforms_test.json (camera_angle_x, file_path without extension,
OpenGL camera-to-world poses looking at the origin), trains a few iterations with
--white-background and without, and checks the log: the camera names (the test r_0 renamed),
and that the stored training images were composited on white / black.

Usage: TrainNerfSynthetic.py VIS4GS_EXE WORK_DIR
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import zlib

import h5py
import numpy as np

W, H = 32, 24


def write_png(path, rgba):
    h, w, _ = rgba.shape
    raw = b"".join(b"\0" + rgba[y].astype(np.uint8).tobytes() for y in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(
            ">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def look_at_origin(angle):
    # OpenGL camera-to-world: camera at radius 4 on the xz circle, z axis pointing away.
    c = np.array([4 * math.sin(angle), 0.0, 4 * math.cos(angle)])
    z = c / np.linalg.norm(c)
    x = np.cross([0.0, 1.0, 0.0], z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = x, y, z, c
    return m.tolist()


def main():
    exe, work = sys.argv[1:3]
    shutil.rmtree(work, ignore_errors=True)
    for split in ("train", "test"):
        os.makedirs(os.path.join(work, split))
    yy, xx = np.mgrid[0:H, 0:W]
    disk = ((xx - W / 2 + 0.5) ** 2 + (yy - H / 2 + 0.5) ** 2) < (H / 3) ** 2
    rgba = np.zeros((H, W, 4))
    rgba[disk] = (60, 120, 200, 255)
    for split, angles in (("train", (0, 0.5, 1.0, 1.5)), ("test", (0.25,))):
        frames = []
        for i, a in enumerate(angles):
            write_png(os.path.join(work, split, "r_%d.png" % i), rgba)
            frames.append({"file_path": "./%s/r_%d" % (split, i), "rotation": 0.0,
                           "transform_matrix": look_at_origin(a)})
        with open(os.path.join(work, "transforms_%s.json" % split), "w") as f:
            json.dump({"camera_angle_x": 0.69, "frames": frames}, f)
    for white in (True, False):
        log = os.path.join(work, "log-%s.h5" % ("white" if white else "black"))
        flag = "--white-background" if white else "--no-white-background"
        subprocess.run([exe, "train", work, "--iterations=20", flag, "--threads=1",
                        "--snapshot-interval=10", "--metrics-interval=10", "--embed-images",
                        "--output=" + log], check=True)
        with h5py.File(log, "r") as f:
            keys = sorted(f["images"].keys())
            print("images:", keys)
            if keys != ["r_0", "r_1", "r_2", "r_3", "test_r_0"]:
                print("FAILED: expected the 4 training and 1 test images in the log")
                return 1
            img = np.asarray(f["images"][keys[0]]).astype(np.float64)
            if img.max() > 1.5:
                img = img / 255.0
            corner, centre = img[0, 0], img[H // 2, W // 2]
            print("background", "white" if white else "black", "corner", corner, "centre", centre)
            if not np.allclose(corner[:3], 1.0 if white else 0.0, atol=1e-6):
                print("FAILED: transparent pixels are not composited on the background")
                return 1
            if not np.allclose(centre[:3], np.array([60, 120, 200]) / 255.0, atol=1e-6):
                print("FAILED: opaque pixels changed")
                return 1
    print("trained on the NeRF-synthetic folder on white and on black")
    return 0


if __name__ == "__main__":
    sys.exit(main())
