"""Helpers of the splat-transform reference checks: an independent numpy PLY reader and writer,
a generated scene, and running PlayCanvas's converter (installed by
install-splat-transform.sh into <build>/reference-tools, skipped with code 77 when absent)."""
import os
import subprocess
import sys

import numpy as np

TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
         "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
         "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


def read_ply(path):
    """Returns {element name: numpy structured array} of a binary PLY (scalar properties)."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    elements, order = {}, ">" if b"binary_big_endian" in data[:end] else "<"
    for line in data[:end].decode("ascii").splitlines():
        tok = line.split()
        if tok and tok[0] == "element":
            elements[tok[1]] = (int(tok[2]), [])
        elif tok and tok[0] == "property":
            assert tok[1] != "list", f"{path}: list property"
            list(elements.values())[-1][1].append((tok[2], order + TYPES[tok[1]]))
    out, offset = {}, end
    for name, (count, props) in elements.items():
        dtype = np.dtype(props)
        out[name] = np.frombuffer(data, dtype=dtype, count=count, offset=offset)
        offset += count * dtype.itemsize
    assert offset == len(data), f"{path}: {len(data) - offset} bytes after the elements"
    return out


def write_ply(path, columns):
    """Writes a little-endian float32 vertex PLY from {name: array} (insertion order)."""
    n = len(next(iter(columns.values())))
    header = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % n
    header += "".join("property float %s\n" % c for c in columns) + "end_header\n"
    rows = np.empty(n, dtype=[(c, "<f4") for c in columns])
    for c, v in columns.items():
        rows[c] = v
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(rows.tobytes())


def generated_scene(n=3000, seed=19):
    """A scene of SH degree 3 in the trainer's layout, with values the formats clamp included."""
    rng = np.random.default_rng(seed)
    cols = {}
    centers = rng.uniform(-20, 20, (8, 3))
    pos = centers[rng.integers(0, 8, n)] + rng.normal(0, 1.5, (n, 3))
    for i, c in enumerate("xyz"):
        cols[c] = pos[:, i]
    for i in range(3):
        cols["f_dc_%d" % i] = rng.normal(0, 1.2, n)
    for i in range(45):
        cols["f_rest_%d" % i] = rng.normal(0, 0.4, n)
    cols["f_rest_7"][:10] = 5.0  # outside the 8-bit range [-4, 4]
    cols["opacity"] = rng.normal(0, 3, n)
    for i in range(3):
        cols["scale_%d" % i] = rng.normal(-4, 1, n)
    q = rng.normal(0, 1, (n, 4))
    for i in range(4):
        cols["rot_%d" % i] = q[:, i]
    return cols


def splat_transform(build):
    """Path of splat-transform's CLI, installing it when needed; exits 77 (skip) when it cannot."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "install-splat-transform.sh")
    r = subprocess.run(["bash", script, build], capture_output=True, text=True)
    if r.returncode != 0:
        sys.stdout.write(r.stderr)
        sys.exit(r.returncode)
    return r.stdout.strip().splitlines()[-1]


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        print("FAILED: %s exited %d\n%s%s" % (" ".join(cmd), r.returncode, r.stdout, r.stderr))
        sys.exit(1)
    return r.stdout


def convert(cli, src, dst, *extra):
    """splat-transform src -> dst (overwriting)."""
    return run(["node", cli, "-q", "-w", *extra, src, dst])


GAUSSIAN_COLUMNS = (["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity"] +
                    ["scale_%d" % i for i in range(3)] + ["rot_%d" % i for i in range(4)])


def compare_exact(what, ours, ref, columns, ulps=0):
    """Counts values of @columns that differ by more than @ulps float32 ulps (inf == inf)."""
    bad, worst = 0, (0, None)
    for c in columns:
        a, b = ours[c].astype(np.float32), ref[c].astype(np.float32)
        same = (a == b) | (np.isnan(a) & np.isnan(b))
        ia, ib = a.view(np.int32).astype(np.int64), b.view(np.int32).astype(np.int64)
        dist = np.where(same, 0, np.abs(ia - ib))
        dist[(np.sign(a) != np.sign(b)) & ~same] = 1 << 40
        bad += int(np.count_nonzero(dist > ulps))
        if dist.max(initial=0) > worst[0]:
            worst = (int(dist.max()), c)
    print("%s: %d columns x %d Gaussians, %d values differ by more than %d ulp (largest: %s ulp in %s)"
          % (what, len(columns), len(ours), bad, ulps, worst[0], worst[1]))
    return bad


def check_commands(vis4gs, scene, decoded_ply, work, label):
    """`vis4gs render` of @scene (a compressed PLY, a .sog, a SOG folder) must give the same PNG
    bytes as the render of @decoded_ply (our reader's float32 PLY of it), and `vis4gs analyze`
    must run on it. Returns the number of failures."""
    if not vis4gs:
        return 0
    import re
    pngs = []
    for i, path in enumerate((scene, decoded_ply)):
        png = os.path.join(work, "render-%s-%d.png" % (label, i))
        run([vis4gs, "render", path, "--resolution=160,120", "--output=" + png])
        pngs.append(open(png, "rb").read())
    failures = 0
    if pngs[0] != pngs[1]:
        print("FAILED: vis4gs render of %s differs from the render of its decoded PLY" % scene)
        failures += 1
    else:
        print("vis4gs render %s: same PNG as its decoded PLY (%d bytes)" % (label, len(pngs[0])))
    out = run([vis4gs, "analyze", scene, "--scores=shape", "--top=2",
               "--output=" + os.path.join(work, "analyze-%s" % label)])
    if not re.search(r"top 2 by NeedleShape.*wrote .*report.html", out, re.S):
        print("FAILED: vis4gs analyze %s printed:\n%s" % (scene, out))
        failures += 1
    else:
        print("vis4gs analyze %s: report written" % label)
    return failures
