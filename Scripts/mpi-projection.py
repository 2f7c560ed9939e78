#!/usr/bin/env python3
"""Projects the distributed scores (issue 18) to K = 1 ... 1024 processes on a city-scale
capture from the constants Scripts/run-mpi-benchmark.sh measures; prints the Markdown table of
Documentation/performance.md ("Scores over MPI").

Model (one process = one core, 1 OpenMP thread; DESIGN of the split: every process holds the
whole scene, renders its share of the views, the per-Gaussian partials are all-reduced):

  t_view(G_seen, F)  = a * G_seen + b * F                 seconds per view
      a: projection cost per Gaussian seen, b: rasterisation + footprint cost per fragment
      (pixel-Gaussian pair evaluated); F = P * D with P pixels and D fragments per pixel
  T(K)               = ceil(V / K) * t_view + T_reduce(K) + T_load
  T_reduce(K)        = 2 * B * (K - 1) / K / bandwidth + ceil(log2 K) * latency,
      B = 24 bytes * G (visible-view counts and scored-view counts as uint32, sums of
      omega*L' and of L' as double: ScorePartials), the ring all-reduce of MPI
  M(K)               = m_scene * G + m_view * G + 2 * B + 3 * 4 * P   bytes per process
      (scene held twice: VTK arrays + Core cloud; per-view projection buffers; partials and
      their reduced copy; image, render and loss map), independent of K

The benchmark measures t_view at G_seen = 0.9 * 1M, P = 320 x 180 (1/4 of 1280 x 720),
D = --bench-fragments-per-pixel; --projection-share splits it into a (projection) and b.
"""
import argparse
import math

p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
p.add_argument("--view-seconds", type=float, required=True,
               help="seconds per view of 1 process x 1 thread at 1M Gaussians (RESULT "
                    "view_seconds_max / views of the 1-process, 1-thread run)")
p.add_argument("--reduction-seconds", type=float, default=None,
               help="measured all-reduce seconds of 24 MB on 2 processes (information only)")
p.add_argument("--memory-per-gaussian", type=float, default=700.0,
               help="peak bytes per Gaussian per process (benchmark peak memory / 1M)")
p.add_argument("--projection-share", type=float, default=0.23,
               help="share of t_view spent projecting (performance.md: 132 of 567 ms)")
p.add_argument("--bench-fragments-per-pixel", type=float, default=63.0,
               help="D of the benchmark scene (0.9M Gaussians x ~4 px at 1/4 over 57,600 px)")
p.add_argument("--gaussians", type=float, default=20e6)
p.add_argument("--views", type=int, default=5000)
p.add_argument("--seen", type=float, default=0.1,
               help="share of the Gaussians a view of the city sees")
p.add_argument("--fragments-per-pixel", type=float, default=63.0)
p.add_argument("--width", type=int, default=5472)
p.add_argument("--height", type=int, default=3648)
p.add_argument("--bandwidth", type=float, default=10e9, help="bytes/s between nodes")
p.add_argument("--latency", type=float, default=5e-6)
p.add_argument("--load-seconds", type=float, default=0.0,
               help="seconds to read the scene on every process (file system dependent)")
args = p.parse_args()

bench_seen = 0.9e6
bench_fragments = 320 * 180 * args.bench_fragments_per_pixel
a = args.view_seconds * args.projection_share / bench_seen
b = args.view_seconds * (1 - args.projection_share) / bench_fragments
G = args.gaussians
B = 24 * G
print(f"a = {a:.3e} s per Gaussian seen, b = {b:.3e} s per fragment; "
      f"partials B = {B / 1e6:.0f} MB per process")
print()
print("| K | views per process | time at 1/4 | time at full | reduction | memory per process |")
print("|---|---|---|---|---|---|")
for K in [1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024]:
    per = math.ceil(args.views / K)
    row = []
    for f in (4, 1):
        P = round(args.width / f) * round(args.height / f)
        t_view = a * args.seen * G + b * P * args.fragments_per_pixel
        row.append((t_view, P))
    red = 0.0 if K == 1 else 2 * B * (K - 1) / K / args.bandwidth + math.ceil(
        math.log2(K)) * args.latency
    P_full = row[1][1]
    mem = args.memory_per_gaussian * G + 2 * B + 3 * 4 * P_full

    def fmt(s):
        return f"{s / 3600:.1f} h" if s >= 3600 else (f"{s / 60:.1f} min" if s >= 60
                                                       else f"{s:.1f} s")
    print(f"| {K} | {per} | {fmt(per * row[0][0] + red + args.load_seconds)} | "
          f"{fmt(per * row[1][0] + red + args.load_seconds)} | {red:.2f} s | "
          f"{mem / 2**30:.1f} GiB |")
