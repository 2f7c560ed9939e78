#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Independent check of the transforms.json camera reader (issue 19).

Parses the COLMAP statue model's cameras.bin / images.bin / points3D.bin with numpy alone,
converts each pose to a NeRF/instant-ngp transforms.json (camera-to-world, OpenGL axes) by the
textbook formulas (no project code), writes a small Gaussian PLY at the model's points, then
renders each camera with `vis4gs render` once from the COLMAP folder and once from the
transforms.json and asserts identical pixels.

Usage: TransformsFromColmap.py VIS4GS_EXE DATASET_DIR WORK_DIR
Exit 77 (skip) when DATASET_DIR is absent (and CI is not "true").
"""
import os
import struct
import subprocess
import sys
import zlib

import numpy as np

SKIP = 77


def read_cameras(path):
    nparams = {0: 3, 1: 4, 2: 4, 3: 5, 4: 8, 5: 8, 6: 12, 7: 5, 8: 4, 9: 5, 10: 12}
    cams = {}
    with open(path, "rb") as f:
        (n,) = struct.unpack("<Q", f.read(8))
        for _ in range(n):
            cid, model, w, h = struct.unpack("<iiQQ", f.read(24))
            p = struct.unpack("<%dd" % nparams[model], f.read(8 * nparams[model]))
            if model == 0:  # SIMPLE_PINHOLE f cx cy
                fx = fy = p[0]
                cx, cy = p[1], p[2]
            elif model in (1, 4, 5, 6):  # fx fy cx cy ...
                fx, fy, cx, cy = p[:4]
            else:  # SIMPLE_RADIAL, RADIAL, ...: f cx cy k...
                fx = fy = p[0]
                cx, cy = p[1], p[2]
            cams[cid] = dict(w=w, h=h, fx=fx, fy=fy, cx=cx, cy=cy)
    return cams


def read_images(path):
    images = []
    with open(path, "rb") as f:
        (n,) = struct.unpack("<Q", f.read(8))
        for _ in range(n):
            iid = struct.unpack("<i", f.read(4))[0]
            q = struct.unpack("<4d", f.read(32))
            t = struct.unpack("<3d", f.read(24))
            cid = struct.unpack("<i", f.read(4))[0]
            name = b""
            while True:
                c = f.read(1)
                if c == b"\0":
                    break
                name += c
            (npts,) = struct.unpack("<Q", f.read(8))
            f.read(24 * npts)
            images.append(dict(id=iid, q=q, t=t, cam=cid, name=name.decode()))
    return images


def read_points(path, limit):
    xyz, rgb = [], []
    with open(path, "rb") as f:
        (n,) = struct.unpack("<Q", f.read(8))
        for _ in range(n):
            _, x, y, z, r, g, b, _ = struct.unpack("<QdddBBBd", f.read(43))
            (tl,) = struct.unpack("<Q", f.read(8))
            f.read(8 * tl)
            if len(xyz) < limit:
                xyz.append((x, y, z))
                rgb.append((r, g, b))
    return np.array(xyz), np.array(rgb) / 255.0


def quat_to_rot(q):
    w, x, y, z = np.array(q) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def write_ply(path, xyz, rgb, scale):
    c0 = 0.28209479177387814
    n = len(xyz)
    props = ["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2", "opacity",
             "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"]
    data = np.zeros((n, len(props)), dtype="<f4")
    data[:, 0:3] = xyz
    data[:, 6:9] = (rgb - 0.5) / c0
    data[:, 9] = 2.0  # sigmoid ~ 0.88
    data[:, 10:13] = np.log(scale)
    data[:, 13] = 1.0
    head = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % n
    head += "".join("property float %s\n" % p for p in props) + "end_header\n"
    with open(path, "wb") as f:
        f.write(head.encode())
        f.write(data.tobytes())


def read_png(path):
    raw = open(path, "rb").read()
    assert raw[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, w = 8, b"", 0
    while pos < len(raw):
        (ln,) = struct.unpack(">I", raw[pos:pos + 4])
        kind, body = raw[pos + 4:pos + 8], raw[pos + 8:pos + 8 + ln]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, path
            ch = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + ln
    data = np.frombuffer(zlib.decompress(idat), dtype=np.uint8)
    stride = w * ch
    out = np.zeros((h, stride), dtype=np.int32)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(h):
        ft = data[y * (stride + 1)]
        line = data[y * (stride + 1) + 1:(y + 1) * (stride + 1)].astype(np.int32)
        cur = np.zeros(stride, dtype=np.int32)
        for i in range(stride):
            a = cur[i - ch] if i >= ch else 0
            b = prev[i]
            c = prev[i - ch] if i >= ch else 0
            if ft == 0:
                p = 0
            elif ft == 1:
                p = a
            elif ft == 2:
                p = b
            elif ft == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[i] = (line[i] + p) & 255
        out[y] = cur
        prev = cur
    return out.reshape(h, w, ch)


def main():
    exe, dataset, work = sys.argv[1:4]
    sparse = os.path.join(dataset, "sparse", "0")
    if not os.path.isfile(os.path.join(sparse, "images.bin")):
        print("SharedData folder %s is absent: test skipped" % dataset)
        return 1 if os.environ.get("CI") == "true" else SKIP
    os.makedirs(work, exist_ok=True)
    cams = read_cameras(os.path.join(sparse, "cameras.bin"))
    images = sorted(read_images(os.path.join(sparse, "images.bin")), key=lambda i: i["name"])
    frames = []
    for im in images:
        c = cams[im["cam"]]
        r = quat_to_rot(im["q"])  # world-to-camera, OpenCV axes
        t = np.array(im["t"])
        c2w = np.eye(4)
        c2w[:3, :3] = r.T
        c2w[:3, 3] = -r.T @ t
        c2w[:3, 1:3] *= -1  # OpenCV (y down, z forward) -> OpenGL (y up, z backward)
        frames.append({
            "file_path": os.path.join(os.path.abspath(dataset), "images", im["name"]),
            "fl_x": c["fx"], "fl_y": c["fy"], "cx": c["cx"], "cy": c["cy"],
            "w": c["w"], "h": c["h"],
            "transform_matrix": c2w.tolist(),
        })
    tj = os.path.join(work, "transforms.json")
    import json
    with open(tj, "w") as f:
        json.dump({"frames": frames}, f, indent=1)

    xyz, rgb = read_points(os.path.join(sparse, "points3D.bin"), 4000)
    extent = np.linalg.norm(xyz.max(0) - xyz.min(0))
    ply = os.path.join(work, "statue-points.ply")
    write_ply(ply, xyz, rgb, 0.005 * extent)

    checked = 0
    for im in images[:: max(1, len(images) // 4)]:
        name = os.path.splitext(im["name"])[0]
        outs = []
        for cams_arg, tag in ((dataset, "colmap"), (tj, "transforms")):
            out = os.path.join(work, "%s-%s.png" % (name, tag))
            cmd = [exe, "render", ply, "--cameras=" + cams_arg, "--camera=" + name,
                   "--resolution=160,120", "--threads=1", "--output=" + out]
            subprocess.run(cmd, check=True)
            outs.append(read_png(out).astype(np.float64) / 255.0)
        a, b = outs
        covered = np.mean(a[..., :3].sum(-1) > 0)
        diff = np.abs(a - b).max()
        print("%s: %.1f%% of pixels covered, max |colmap - transforms| = %g" %
              (name, 100 * covered, diff))
        if covered < 0.01:
            print("FAILED: camera %s sees almost nothing of the scene" % name)
            return 1
        if diff > 1e-5:
            print("FAILED: camera %s renders differently from transforms.json" % name)
            return 1
        checked += 1
    print("transforms.json cameras render like the COLMAP cameras (%d views)" % checked)
    return 0


if __name__ == "__main__":
    sys.exit(main())
