#!/usr/bin/env bash
# Builds the libFuzzer targets of the scene parsers (Testing/Fuzz) with clang + AddressSanitizer
# in build-fuzz and runs each for a bounded time. Exits non-zero when a fuzzer finds a crash
# (the reproducer is left in build-fuzz/artifacts/; turn it into a regression test in
# Core/Scene/Testing before fixing the bug).
#
# Usage: Scripts/run-fuzzers.sh [seconds-per-target, default 20] [build dir, default build-fuzz]
# VIS4GS_FUZZ_SKIP_BUILD=1 runs already built targets (in <build dir>/fuzz).
set -euo pipefail

seconds="${1:-20}"
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${2:-$root/build-fuzz}"
data="${VIS4GS_SHARED_DATA_DIR:-$root/../shared/data}"
targets=(FuzzGaussianPly FuzzSplat FuzzCamerasJson FuzzTransformsJson FuzzColmap FuzzSpz FuzzCompressedPly
  FuzzSog FuzzKsplat FuzzGltf)

if [ "${VIS4GS_FUZZ_SKIP_BUILD:-0}" != 1 ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja \
    -DVIS4GS_CORE_ONLY=ON -DVIS4GS_ENABLE_FUZZING=ON -DBUILD_TESTING=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS="-fsanitize=address,fuzzer-no-link" \
    -DCMAKE_CXX_FLAGS="-fsanitize=address,fuzzer-no-link" >/dev/null
  cmake --build "$build" -j2 --target "${targets[@]}"
fi

# Seed corpora: small real inputs (headers plus a few rows of the real files) and hand-made ones.
seeds="$build/seeds"
rm -rf "$seeds"
mkdir -p "$seeds"/{FuzzGaussianPly,FuzzSplat,FuzzCamerasJson,FuzzTransformsJson,FuzzColmap,FuzzSpz,FuzzKsplat}
mkdir -p "$seeds/FuzzCompressedPly" "$seeds/FuzzSog" "$seeds/FuzzGltf"
ply="$data/inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply"
donut="$data/gs_ply_sh0_variant_donut_v3dg/fused.ply"
if [ -f "$ply" ]; then
  header=$(grep -a -b -m1 -o 'end_header' "$ply" | cut -d: -f1)
  head -c $((header + 11 + 3 * 248)) "$ply" >"$seeds/FuzzGaussianPly/inria3.ply"
  header=$(grep -a -b -m1 -o 'end_header' "$donut" | cut -d: -f1)
  head -c $((header + 11 + 4 * 56)) "$donut" >"$seeds/FuzzGaussianPly/donut4.ply"
  head -c $((32 * 4)) "$data/inria_ply_tiny_kacytran/model_1.splat" >"$seeds/FuzzSplat/four.splat"
fi
cat >"$seeds/FuzzGaussianPly/ascii.ply" <<'PLY'
ply
format ascii 1.0
comment seed
element vertex 2
property float x
property float y
property float z
property uchar score
property float f_dc_0
property float f_dc_1
property float f_dc_2
property double opacity
property float scale_0
property float scale_1
property float scale_2
property float rot_0
property float rot_1
property float rot_2
property float rot_3
property int id
end_header
1 2 3 7 0.1 0.2 0.3 -2.19 -4 -4 -4 1 0 0 0 10
nan -inf 1e-50 255 0 0 0 9 1 2 3 0 0 0 0 11
PLY
cat >"$seeds/FuzzCamerasJson/cameras.json" <<'JSON'
[{"id": 0, "img_name": "DSC0001", "width": 800, "height": 600, "position": [1.0, 2.0, 3.0],
  "rotation": [[0, -1, 0], [1, 0, 0], [0, 0, 1]], "fy": 700.5, "fx": 710.25},
 {"id": 1, "img_name": "b", "width": 8, "height": 6, "position": [0, 0, 0],
  "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fy": 7, "fx": 7, "cx": 4, "cy": 3}]
JSON
cat >"$seeds/FuzzTransformsJson/transforms.json" <<'JSON'
{"camera_angle_x": 0.69, "w": 8, "h": 6, "k1": 0.1,
 "frames": [{"file_path": "./train/r_0", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,4],[0,0,0,1]]},
  {"file_path": "b.png", "fl_x": 20, "fl_y": 21, "cx": 4, "cy": 3, "camera_angle_y": 0.5,
   "transform_matrix": [[0,0,1,4],[0,1,0,0],[-1,0,0,0],[0,0,0,1]]}]}
JSON
statue="$data/colmap_statue_bartoszek/sparse/0"
if [ -f "$statue/cameras.bin" ]; then
  { printf '\x00'; cat "$statue/cameras.bin"; } >"$seeds/FuzzColmap/cameras.bin"
  { printf '\x01'; head -c 4096 "$statue/images.bin"; } >"$seeds/FuzzColmap/images.bin"
  { printf '\x02'; head -c 4096 "$statue/points3D.bin"; } >"$seeds/FuzzColmap/points3D.bin"
fi
{ printf '\x03'; printf '# c\n1 PINHOLE 640 480 500 500 320 240\n2 OPENCV 640 480 1 2 3 4 5 6 7 8\n'; } \
  >"$seeds/FuzzColmap/cameras.txt"
{ printf '\x04'; printf '1 1 0 0 0 0 0 0 1 a.png\n1.5 2.5 7 3 4 -1\n2 0 1 0 0 1 2 3 1 b.png\n\n'; } \
  >"$seeds/FuzzColmap/images.txt"
{ printf '\x05'; printf '5 1 2 3 255 0 10 0.25 1 0 2 1\n'; } >"$seeds/FuzzColmap/points3D.txt"

# SPZ seeds: four Gaussians with SH degree 1 as v3 (gzip, with extension records after the
# data) and v4 (raw-block zstd frames behind the table of contents, with extension records).
/usr/bin/python3 - "$seeds/FuzzSpz" <<'PY'
import gzip, struct, sys
n = 4
streams = [bytes(range(9 * n)), bytes([10, 128, 200, 255]), bytes(3 * n), bytes([144] * 3 * n),
           struct.pack("<I", 3 << 30) * n, bytes([128] * 9 * n)]
ext = struct.pack("<III", 0xADBE0003, 4, 4) + struct.pack("<II", 0x12340001, 2) + b"xy"
legacy = struct.pack("<IIIBBBB", 0x5053474E, 3, n, 1, 12, 2, 0) + b"".join(streams) + ext
open(sys.argv[1] + "/v3.spz", "wb").write(gzip.compress(legacy))
def zstd_raw(b):  # one frame, single segment, 1-byte content size, one raw last block
    return struct.pack("<IBB", 0xFD2FB528, 0x20, len(b)) + (1 | len(b) << 3).to_bytes(3, "little") + b
frames = [zstd_raw(b) for b in streams]
v4 = struct.pack("<IIIBBBBI", 0x5053474E, 4, n, 1, 12, 2, 6, 32 + len(ext)) + bytes(12) + ext
v4 += b"".join(struct.pack("<QQ", len(f), len(b)) for f, b in zip(frames, streams)) + b"".join(frames)
open(sys.argv[1] + "/v4.spz", "wb").write(v4)
PY

# Compressed PLY: two Gaussians in one 18-float chunk with SH degree 1, and one in a 12-float
# chunk (the layouts of Documentation/file-formats.md).
/usr/bin/python3 - "$seeds/FuzzCompressedPly" <<'PY'
import struct, sys
bounds = ["min_x", "min_y", "min_z", "max_x", "max_y", "max_z", "min_scale_x", "min_scale_y",
          "min_scale_z", "max_scale_x", "max_scale_y", "max_scale_z"]
colour = ["min_r", "min_g", "min_b", "max_r", "max_g", "max_b"]
def seed(name, chunk_props, n, sh):
    h = "ply\nformat binary_little_endian 1.0\nelement chunk 1\n"
    h += "".join("property float %s\n" % p for p in chunk_props)
    h += "element vertex %d\n" % n + "".join("property uint packed_%s\n" % p
                                           for p in ("position", "rotation", "scale", "color"))
    if sh:
        h += "element sh %d\n" % n + "".join("property uchar f_rest_%d\n" % i for i in range(sh))
    body = struct.pack("<%df" % len(chunk_props), *[(-1) ** i * (i + 1) * 0.5 for i in range(len(chunk_props))])
    for g in range(n):
        body += struct.pack("<4I", 0x7ff003ff ^ g, (g % 4) << 30 | 0x200 << 20 | 0x1ff << 10 | 0x201,
                            0x12345678 + g, 0xff00807f - g)
    body += bytes((7 * i) % 256 for i in range(n * sh))
    open(sys.argv[1] + "/" + name, "wb").write((h + "end_header\n").encode() + body)
seed("chunk18-sh1.ply", bounds + colour, 2, 9)
seed("chunk12.ply", bounds, 1, 0)
PY

# SOG: a 24-Gaussian SH-degree-1 scene written by splat-transform 3.7 (Testing/Fuzz/Seeds), as a
# zip (first byte even) and as the fuzzer's list of files (first byte odd).
/usr/bin/python3 - "$root/Testing/Fuzz/Seeds/tiny.sog" "$seeds/FuzzSog" <<'PY'
import struct, sys, zipfile
data = open(sys.argv[1], "rb").read()
open(sys.argv[2] + "/tiny-zip", "wb").write(b"\x00" + data)
out = b"\x01"
with zipfile.ZipFile(sys.argv[1]) as z:
    for name in z.namelist():
        body = z.read(name)
        out += bytes([len(name)]) + name.encode() + struct.pack("<I", len(body)) + body
open(sys.argv[2] + "/tiny-files", "wb").write(out)
PY

# .ksplat seeds: two Gaussians with SH degree 1 at compression level 0 (float32) and level 2
# (one full bucket of 1 record and one partially filled bucket, byte SH).
/usr/bin/python3 - "$seeds/FuzzKsplat" <<'PY'
import struct, sys
def ksplat(level, body, bucket):
    head = bytearray(4096)
    struct.pack_into("<BBxxIIII", head, 0, 0, 1, 1, 1, 2, 2)
    struct.pack_into("<H", head, 20, level)
    struct.pack_into("<ff", head, 36, -1.5, 1.5)
    sec = bytearray(1024)
    struct.pack_into("<IIIIfHxxIIIIH", sec, 0, 2, 2, *bucket[:5], len(body), *bucket[5:], 1)
    return bytes(head) + bytes(sec) + body
rec0 = struct.pack("<3f3f4f4B9f", 1, 2, 3, 0.5, 1, 2, 1, 0, 0, 0, 10, 20, 30, 40, *range(9))
open(sys.argv[1] + "/l0.ksplat", "wb").write(ksplat(0, rec0 * 2, (0, 0, 0.0, 0, 0, 0, 0)))
rec2 = struct.pack("<3H7H4B9B", 32767, 0, 65535, 0x3C00, 0x3800, 0x4000, 0x3C00, 0, 0, 0,
                   10, 20, 30, 40, *range(9))
body2 = struct.pack("<I6f", 1, 0, 0, 0, 5, 5, 5) + rec2 * 2
open(sys.argv[1] + "/l2.ksplat", "wb").write(ksplat(2, body2, (1, 2, 5.0, 12, 32767, 1, 1)))
PY

# glTF: a 6-Gaussian SH-degree-1 GLB with a score attribute written by WriteGltf
# (Testing/Fuzz/Seeds), and the same as JSON with a data URI, a node hierarchy (TRS parent,
# matrix child) and the SPZ extension's nesting pointing at a view of its buffer.
/usr/bin/python3 - "$root/Testing/Fuzz/Seeds/tiny.glb" "$seeds/FuzzGltf" <<'PY'
import base64, json, struct, sys
glb = open(sys.argv[1], "rb").read()
open(sys.argv[2] + "/tiny.glb", "wb").write(glb)
n = struct.unpack_from("<I", glb, 12)[0]
doc = json.loads(glb[20:20 + n])
bin_ = glb[20 + n + 8:]
doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bin_).decode()
doc["nodes"] = [{"children": [1], "translation": [1, 2, 3], "rotation": [0, 0.6, 0, 0.8]},
                {"mesh": 0, "matrix": [2, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}]
open(sys.argv[2] + "/nodes.gltf", "w").write(json.dumps(doc))
ext = doc["meshes"][0]["primitives"][0]["extensions"]["KHR_gaussian_splatting"]
ext["extensions"] = {"KHR_gaussian_splatting_compression_spz_2": {"bufferView": 0}}
open(sys.argv[2] + "/spz-nesting.gltf", "w").write(json.dumps(doc))
PY

status=0
mkdir -p "$build/artifacts"
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  mkdir -p "$corpus"
  echo "== $t: ${seconds}s"
  if ! "$build/fuzz/$t" "$corpus" "$seeds/$t" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$t-" 2>"$build/$t.log"; then
    echo "!! $t found a problem; see $build/$t.log and $build/artifacts/"
    tail -40 "$build/$t.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "$build/$t.log" | tail -2
  fi
done
exit $status
