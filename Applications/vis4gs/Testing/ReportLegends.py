"""The overlay legends of a `vis4gs analyze`/`demo` report name each score's suspicious end,
and the colour map draws that end bright (it must stand out on the black overlay images).

Parses report.html: for every colour-map gradient, the luminance of its end stops and which
end carries the "(suspicious)" label; View Coverage must be suspicious at its low end, Blur
and Needle scores at their high end, and the suspicious end must be the brightest stop.

Usage: ReportLegends.py REPORT_DIR
"""
import os
import re
import sys

EXPECTED = {"ViewCoverage": "low", "BlurScore": "high", "NeedleScore": "high"}


def luminance(rgb):
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]


def main(folder):
    html = open(os.path.join(folder, "report.html"), encoding="utf-8").read()
    problems = []
    seen = set()
    for figure in re.findall(r"<figure><svg[^>]*height=\"46\".*?</figure>", html, re.S):
        name = re.search(r'id="map-([^"]+)"', figure).group(1)
        seen.add(name)
        stops = [tuple(int(c) for c in m)
                 for m in re.findall(r'stop-color="rgb\((\d+),(\d+),(\d+)\)"', figure)]
        texts = re.findall(r"<text[^>]*>([^<]*)</text>", figure)
        if len(stops) < 2 or len(texts) != 2:
            problems.append(f"{name}: {len(stops)} gradient stops, {len(texts)} end labels")
            continue
        end = ("low" if "(suspicious)" in texts[0] else
               "high" if "(suspicious)" in texts[1] else None)
        bright = stops[0] if end == "low" else stops[-1]
        dark = stops[-1] if end == "low" else stops[0]
        print(f"{name}: suspicious end {end}, luminance {luminance(bright):.0f} against "
              f"{luminance(dark):.0f}")
        if name in EXPECTED and end != EXPECTED[name]:
            problems.append(f"{name}: the legend labels the {end} end suspicious, "
                            f"expected {EXPECTED[name]}")
        if not luminance(bright) > 5 * luminance(dark):
            problems.append(f"{name}: the suspicious end is not the bright end of the map")
        if max(luminance(s) for s in stops) != luminance(bright):
            problems.append(f"{name}: a stop is brighter than the suspicious end")
    missing = set(EXPECTED) - seen
    if missing:
        problems.append("no legend for " + ", ".join(sorted(missing)))
    for p in problems:
        print("FAILED: " + p)
    if not problems:
        print("every legend names its suspicious end, drawn bright")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: ReportLegends.py REPORT_DIR")
    sys.exit(main(sys.argv[1]))
