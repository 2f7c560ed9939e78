#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Plot of the scene view's level of detail, error against run time: reads the output of
BenchmarkSplatLevelOfDetail (one file per scene) and writes an SVG (no dependencies): PSNR of
the moving frame against the exact frame over the frame's CPU milliseconds, one line per scene
and configuration (selected per frame, or kept while the view moves: reuse and colour angles,
transmittance stop),
each point labelled with its budget.

Usage: plot-lod-accuracy.py OUTPUT.svg BENCHMARK_OUTPUT.txt...
"""
import math
import re
import sys


def read(path):
    """The series of one benchmark output: one per configuration of the rows (the older
    11-column rows, or the 15-column rows with the reuse angles and the transmittance stop,
    or the 16-column rows that add the Gaussians a rebuild examined)."""
    name, series = path, {}
    with open(path) as f:
        for line in f:
            m = re.match(r"BenchmarkSplatLevelOfDetail: (\S+), (\d+) Gaussians", line)
            if m:
                scene = m.group(1).rstrip(",")
                name = "synthetic %s" % m.group(2) if scene == "synthetic" else \
                    "%s (%s)" % (scene.split("/")[-2] if "/" in scene else scene, m.group(2))
                d = re.search(r"sample distance ([0-9.]+)", line)
                if d and float(d.group(1)) != 2.0:
                    name += ", sample distance %s" % d.group(1)
            parts = line.split()
            if len(parts) == 11 and parts[0].isdigit():
                key = name
                row = (int(parts[0]), float(parts[7]), float(parts[9]))
            elif len(parts) in (15, 16) and parts[0].isdigit():
                key = "%s, selected per frame" % name if parts[1] == "-" else \
                    "%s, kept %s deg, stop %g" % (name, parts[1], float(parts[2]))
                row = (int(parts[0]), float(parts[9]), float(parts[11]))
            else:
                continue
            series.setdefault(key, []).append(row)
    if not series:
        sys.exit("plot-lod-accuracy: no table rows in %s" % path)
    return list(series.items())


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    series = [s for p in sys.argv[2:] for s in read(p)]
    W, H, L, R, T, B = 720, 420, 70, 20, 30, 50
    xs = [r[1] for _, rows in series for r in rows]
    ys = [r[2] for _, rows in series for r in rows]
    x0, x1 = math.log10(max(0.5, min(xs) / 1.5)), math.log10(max(xs) * 1.5)
    y0, y1 = math.floor(min(ys + [25]) - 1), math.ceil(max(ys) + 1)
    px = lambda x: L + (math.log10(x) - x0) / (x1 - x0) * (W - L - R)
    py = lambda y: H - B - (y - y0) / (y1 - y0) * (H - T - B)
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" '
           'font-size="11"><rect width="100%%" height="100%%" fill="white"/>' % (W, H)]
    out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, H - B, W - R, H - B))
    out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, T, L, H - B))
    for e in range(int(math.floor(x0)), int(math.ceil(x1)) + 1):
        for m in (1, 2, 5):
            v = m * 10 ** e
            if x0 <= math.log10(v) <= x1:
                out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ddd"/>'
                           '<text x="%.1f" y="%d" text-anchor="middle">%g</text>'
                           % (px(v), T, px(v), H - B, px(v), H - B + 14, v))
    for y in range(int(y0), int(y1) + 1, 2):
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>'
                   '<text x="%d" y="%.1f" text-anchor="end">%d</text>'
                   % (L, py(y), W - R, py(y), L - 4, py(y) + 4, y))
    out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#c00" stroke-dasharray="4,3"/>'
               '<text x="%d" y="%.1f" fill="#c00">25 dB</text>' % (L, py(25), W - R, py(25),
                                                                    W - R - 40, py(25) - 4))
    out.append('<text x="%d" y="%d" text-anchor="middle">CPU ms per moving frame (2 threads, '
               'log scale)</text>' % ((L + W - R) // 2, H - 12))
    out.append('<text x="14" y="%d" transform="rotate(-90 14 %d)" text-anchor="middle">PSNR '
               'against the exact frame (dB)</text>' % ((T + H - B) // 2, (T + H - B) // 2))
    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf"]
    for k, (name, rows) in enumerate(series):
        c = colours[k % len(colours)]
        pts = " ".join("%.1f,%.1f" % (px(r[1]), py(r[2])) for r in rows)
        out.append('<polyline points="%s" fill="none" stroke="%s" stroke-width="2"/>' % (pts, c))
        for b, x, y in rows:
            out.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/><text x="%.1f" y="%.1f" '
                       'fill="%s" font-size="9">%d</text>' % (px(x), py(y), c, px(x) + 4,
                                                                 py(y) - 4, c, b))
        out.append('<text x="%d" y="%d" fill="%s">%s</text>' % (L + 10, T + 14 * (k + 1), c, name))
    out.append("</svg>")
    with open(sys.argv[1], "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
