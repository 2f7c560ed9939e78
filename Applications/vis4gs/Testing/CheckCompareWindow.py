"""Checks the comparison window of `vis4gs view A --compare=B` (issue 20) against `vis4gs
compare` run on the same states.

Usage:
  CheckCompareWindow.py SETS_CSV VIS4GS A B [compare options...]
SETS_CSV is the window's self-test output (compare-sets.csv: per set, the count its legend
entry shows, the number of ids a click on it selected and those ids). The script runs
`VIS4GS compare A B [options] --no-metrics` into a folder beside SETS_CSV and checks, per set
(born, died, moved, opacity changed, scale changed, unchanged, a Gaussian of both states in
each of the sets its status names), that the shown count, the selected count and the ids equal
what differences.csv lists. Prints "FAILED: ..." for each failed check and exits 1.
"""
import csv
import os
import subprocess
import sys

problems = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        problems.append(what)


def main():
    if len(sys.argv) < 5:
        print(__doc__)
        return 2
    sets_csv, vis4gs, a, b = sys.argv[1:5]
    output = os.path.join(os.path.dirname(os.path.abspath(sets_csv)), "vis4gs-compare")
    args = [vis4gs, "compare", a, b] + sys.argv[5:] + ["--no-metrics", "--output=" + output]
    result = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(result.stdout)
    if result.returncode != 0:
        print("FAILED: " + " ".join(args) + " exited with " + str(result.returncode))
        return 1

    expected = {name: set() for name in
                ("born", "died", "moved", "opacity changed", "scale changed", "unchanged")}
    words = {"moved": "moved", "opacity": "opacity changed", "scale": "scale changed"}
    with open(os.path.join(output, "differences.csv"), newline="") as f:
        for row in csv.DictReader(f):
            status, gid = row["status"], int(row["id"])
            if status in ("born", "died", "unchanged"):
                expected[status].add(gid)
            else:
                for word in status.split("+"):
                    expected[words[word]].add(gid)

    seen = set()
    with open(sets_csv, newline="") as f:
        for row in csv.DictReader(f):
            name = row["set"]
            seen.add(name)
            ids = [int(v) for v in row["ids"].split()]
            want = expected.get(name)
            if want is None:
                check(False, "the window lists an unknown set '%s'" % name)
                continue
            check(int(row["shown"]) == len(want),
                  "%s: the legend shows %s, vis4gs compare counts %d" % (name, row["shown"], len(want)))
            check(int(row["selected"]) == len(ids) and set(ids) == want and ids == sorted(ids),
                  "%s: its click selects the %d ids of differences.csv" % (name, len(want)))
    check(seen == set(expected), "the window lists every set (%s)" % ", ".join(sorted(seen)))
    if problems:
        return 1
    print("the comparison window's sets equal vis4gs compare's: " +
          ", ".join("%s %d" % (k, len(v)) for k, v in expected.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
