"""The histograms of a `vis4gs analyze`/`demo` report count every finite score and draw their
bars on a log scale exactly when one bin holds most Gaussians (issue 33).

Parses report.html: for every histogram, the counts (each bar's title), the declared scale
(the svg's data-scale) and the bar heights; bins the same score's column of scores.csv again
(40 bins over its finite range) and requires the same counts (up to values moved across a bin
edge by the CSV's 9 significant digits), the scale the rule gives, and heights of
130 * log(1 + count) / log(1 + peak) on a log scale, 130 * count / peak on a linear one.

Usage: ReportHistograms.py REPORT_DIR
"""
import csv
import math
import os
import re
import sys


def bin_counts(values, bins=40):
    finite = [v for v in values if math.isfinite(v)]
    if not finite:
        return [0] * bins
    lo, hi = min(finite), max(finite)
    counts = [0] * bins
    for v in finite:
        b = min(bins - 1, int((v - lo) / (hi - lo) * bins)) if hi > lo else 0
        counts[b] += 1
    return counts


def main(folder):
    html = open(os.path.join(folder, "report.html"), encoding="utf-8").read()
    with open(os.path.join(folder, "scores.csv"), newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    problems = []
    figures = re.findall(r'<figure><svg width="420" height="170"(.*?)</figure>', html, re.S)
    if not figures:
        problems.append("no histogram in report.html")
    scales = []
    for figure in figures:
        name = re.search(r"<figcaption>([^ <]+)", figure).group(1)
        scale = re.search(r'data-scale="(\w+)"', figure)
        bars = re.findall(r'<rect x="[\d.]+" y="[-\d.e+]+" width="9" height="([-\d.e+]+)"[^>]*>'
                          r"<title>(\d+)</title>", figure)
        if not scale or len(bars) != 40:
            problems.append(f"{name}: {len(bars)} bars, scale {scale and scale.group(1)}")
            continue
        scale = scale.group(1)
        counts = [int(c) for _, c in bars]
        heights = [float(h) for h, _ in bars]
        total, peak = sum(counts), max(max(counts), 1)
        want = "log" if 2 * peak > total and total > 0 else "linear"
        scales.append(scale)
        print(f"{name}: {total} Gaussians, highest bin {peak}, {scale} scale")
        if scale != want:
            problems.append(f"{name}: drawn on a {scale} scale, the rule gives {want}")
        for c, h in zip(counts, heights):
            expect = (130 * math.log1p(c) / math.log1p(peak) if scale == "log"
                      else 130 * c / peak)
            if abs(h - expect) > 1e-3 * 130:
                problems.append(f"{name}: a bar of {c} is {h} high, expected {expect}")
                break
        if name not in header:
            problems.append(f"{name}: no such column in scores.csv")
            continue
        column = header.index(name)
        again = bin_counts([float(r[column]) for r in rows])
        if sum(again) != total:
            problems.append(f"{name}: the report counts {total}, scores.csv {sum(again)}")
        slack = 2 + total // 1000
        if any(abs(a - b) > slack for a, b in zip(again, counts)):
            problems.append(f"{name}: bins {counts} against scores.csv's {again}")
    for p in problems:
        print("FAILED: " + p)
    if not problems:
        print(f"{len(figures)} histograms count scores.csv's values, scales {scales}")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: ReportHistograms.py REPORT_DIR")
    sys.exit(main(sys.argv[1]))
