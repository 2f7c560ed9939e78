"""Writes a small INRIA PLY (SH degree 0) of extreme Gaussians for the selection self-test, and
a cameras.json beside it with one camera whose near plane (view z = 0.2) cuts through some of
them: needles, disks, huge and tiny scales, opacity 0 and 1 (logits -inf, +inf, +-30), means
at, just before and just behind the near plane, among ordinary Gaussians. Deterministic.

Usage: MakeExtremeScene.py OUTPUT_DIR  (writes OUTPUT_DIR/extreme.ply, OUTPUT_DIR/cameras.json)
"""

import json
import math
import os
import random
import struct
import sys

PROPERTIES = ["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2", "opacity",
              "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"]


def gaussians():
    rng = random.Random(7)
    out = []
    for i in range(3000):
        pos = [rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)]
        scales = [rng.uniform(-4.5, -3.0) for _ in range(3)]
        logit = rng.uniform(-2, 4)
        kind = i % 10
        if kind == 0:  # needle
            scales = [0.0, -10.0, -10.0]
        elif kind == 1:  # disk
            scales = [-1.0, -1.0, -13.0]
        elif kind == 2:  # huge
            scales = [1.5, 1.5, 1.5]
            logit = rng.uniform(-6, -3)
        elif kind == 3:  # tiny
            scales = [-15.0, -15.0, -15.0]
        elif kind == 4:  # at the near plane of the camera (centre (0, 0, -3), looking +z)
            pos[2] = -3.0 + 0.2 + rng.choice([-1e-3, 0.0, 1e-6, 1e-3, 0.05])
            pos[0] *= 0.1
            pos[1] *= 0.1
        elif kind == 5:
            logit = rng.choice([math.inf, 30.0])
        elif kind == 6:
            logit = rng.choice([-math.inf, -30.0])
        rot = [rng.uniform(-1, 1) for _ in range(4)]
        colour = [rng.uniform(-1.5, 1.5) for _ in range(3)]
        out.append(pos + [0.0, 0.0, 0.0] + colour + [logit] + scales + rot)
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: MakeExtremeScene.py OUTPUT_DIR")
    directory = sys.argv[1]
    os.makedirs(directory, exist_ok=True)
    rows = gaussians()
    header = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(rows)
    header += "".join("property float %s\n" % p for p in PROPERTIES) + "end_header\n"
    path = os.path.join(directory, "extreme.ply")
    with open(path + ".tmp", "wb") as f:
        f.write(header.encode("ascii"))
        for r in rows:
            f.write(struct.pack("<%df" % len(PROPERTIES), *r))
    os.replace(path + ".tmp", path)
    camera = {"id": 0, "img_name": "near", "width": 640, "height": 480,
              "position": [0.0, 0.0, -3.0],
              "rotation": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
              "fx": 500.0, "fy": 500.0}
    side = dict(camera, id=1, img_name="side", position=[3.0, 0.0, 0.0],
                rotation=[[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])
    cameras = os.path.join(directory, "cameras.json")
    with open(cameras + ".tmp", "w") as f:
        json.dump([camera, side], f)
    os.replace(cameras + ".tmp", cameras)
    print("wrote %d Gaussians to %s and 2 cameras to %s" % (len(rows), path, cameras))


if __name__ == "__main__":
    main()
