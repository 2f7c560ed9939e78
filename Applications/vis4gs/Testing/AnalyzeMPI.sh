#!/usr/bin/env bash
# vis4gs analyze under mpiexec (issue 18). Usage: AnalyzeMPI.sh MODE VIS4GS MPIEXEC LOG WORKDIR
#  equal   2 processes give the single process's scores.csv (coverage and flags identical,
#          blur/needle equal to the 9 printed digits), 3 processes on one view too; the
#          preparation shared, and the same file when it cannot be
#  killed  process 1 killed in its first view: mpiexec fails, the error names process and
#          view, and the output folder holds no scores.csv, scores.ply or report.html
#  plain   without mpiexec nothing mentions processes (no MPI started)
set -u
mode=$1 vis4gs=$2 mpiexec=$3 log=$4 work=$5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAILED: $*"; exit 1; }
common=(--overlay-views=0 --top=2)

# Compares two scores.csv: same header and ids, integer columns identical, others to 1e-7.
compare() {
  /usr/bin/python3 - "$1" "$2" <<'PY' || fail "scores differ: $1 $2"
import csv, sys
a = list(csv.reader(open(sys.argv[1]))); b = list(csv.reader(open(sys.argv[2])))
assert a[0] == b[0] and len(a) == len(b) and len(a) > 1, "header or row count"
for x, y in zip(a[1:], b[1:]):
    for name, u, v in zip(a[0], x, y):
        if name in ("GaussianId", "NoVisibleView", "ViewCoverage"):
            assert u == v, (name, x[0], u, v)
        else:
            u, v = float(u), float(v)
            assert abs(u - v) <= 1e-7 * max(abs(u), abs(v)), (name, x[0], u, v)
print("same scores:", len(a) - 1, "Gaussians,", a[0][1:])
PY
}

case "$mode" in
  equal)
    "$vis4gs" analyze "$log" "${common[@]}" --output="$work/one" > "$work/one.log" 2>&1 \
      || fail "single process: $(tail -3 "$work/one.log")"
    "$mpiexec" -n 2 --oversubscribe "$vis4gs" analyze "$log" "${common[@]}" \
      --output="$work/two" > "$work/two.log" 2>&1 || fail "2 processes: $(tail -5 "$work/two.log")"
    [ "$(grep -c "preparation made alone" "$work/two.log")" = 2 ] \
      || fail "the preparation was shared without --share-preparation"
    # The views came from the machine's queue (the default): whoever took them, every view was
    # rendered once.
    total="$(sed -n 's/.*process [01] of 2 rendered \([0-9]*\) of \([0-9]*\) views.*/\1 \2/p' \
      "$work/two.log" | awk '{ n += $1; m = $2 } END { print (NR == 2 && n == m && m > 0) }')"
    [ "$total" = 1 ] || fail "the views rendered do not add up: $(grep rendered "$work/two.log")"
    compare "$work/one/scores.csv" "$work/two/scores.csv"
    # The fixed split (the same bits on every run): process 1 renders its part, and the shared
    # preparation and its fallback below give the same file.
    "$mpiexec" -n 2 --oversubscribe "$vis4gs" analyze "$log" "${common[@]}" --static-view-split \
      --output="$work/fixed" > "$work/fixed.log" 2>&1 \
      || fail "2 processes, fixed split: $(tail -5 "$work/fixed.log")"
    grep -q "process 1 of 2 rendered [1-9][0-9]* of" "$work/fixed.log" || fail "process 1 rendered nothing"
    compare "$work/one/scores.csv" "$work/fixed/scores.csv"
    "$mpiexec" -n 2 --oversubscribe "$vis4gs" analyze "$log" "${common[@]}" --share-preparation \
      --static-view-split --output="$work/shared" > "$work/shared.log" 2>&1 \
      || fail "2 processes sharing: $(tail -5 "$work/shared.log")"
    cmp "$work/fixed/scores.csv" "$work/shared/scores.csv" || fail "sharing changed scores.csv"
    # The two processes prepared the projection once between them in shared memory; when
    # process 1 cannot map it, both prepare alone, it says why, and the file is the same.
    [ "$(grep -c "preparation shared by 2 processes of this machine" "$work/shared.log")" = 2 ] \
      || fail "the preparation was not shared: $(grep rendered "$work/shared.log")"
    VIS4GS_TEST_NO_SHARED_MEMORY=1 "$mpiexec" -n 2 --oversubscribe -x VIS4GS_TEST_NO_SHARED_MEMORY \
      "$vis4gs" analyze "$log" "${common[@]}" --share-preparation --static-view-split \
      --output="$work/alone" \
      > "$work/alone.log" 2>&1 \
      || fail "2 processes, shared memory refused: $(tail -5 "$work/alone.log")"
    grep -q "process 1 of 2: the processes of this machine could not share the preparation" \
      "$work/alone.log" || fail "no warning for the refused shared memory"
    [ "$(grep -c "preparation made alone" "$work/alone.log")" = 2 ] || fail "expected the fallback"
    cmp "$work/fixed/scores.csv" "$work/alone/scores.csv" || fail "the fallback changed scores.csv"
    # One view (a stride past the view count) on 3 processes: two of them render none.
    "$vis4gs" analyze "$log" "${common[@]}" --view-stride=1000 --scores=coverage,blur \
      --output="$work/one-view" > "$work/ov1.log" 2>&1 || fail "single process, one view"
    "$mpiexec" -n 3 --oversubscribe "$vis4gs" analyze "$log" "${common[@]}" --view-stride=1000 \
      --scores=coverage,blur --output="$work/one-view-3" > "$work/ov3.log" 2>&1 \
      || fail "3 processes, one view: $(tail -5 "$work/ov3.log")"
    [ "$(grep -c "rendered 0 of 1 views" "$work/ov3.log")" = 2 ] || fail "expected two idle processes"
    compare "$work/one-view/scores.csv" "$work/one-view-3/scores.csv"
    echo "PASSED equal"
    ;;
  killed)
    # (the fixed split: with the queue, process 1 might find no view left to be killed on)
    VIS4GS_TEST_KILL_VIEW=1:any "$mpiexec" -n 2 --oversubscribe -x VIS4GS_TEST_KILL_VIEW \
      "$vis4gs" analyze "$log" "${common[@]}" --static-view-split --output="$work/out" \
      > "$work/killed.log" 2>&1 \
      && fail "mpiexec succeeded although process 1 was killed"
    grep -q "process 1 of 2 stopped by signal 15 while on view [0-9]* ('" "$work/killed.log" \
      || fail "no error naming the process and the view: $(cat "$work/killed.log")"
    for f in scores.csv scores.ply report.html; do
      [ ! -e "$work/out/$f" ] || fail "$f was written although a process was killed"
    done
    echo "PASSED killed"
    ;;
  plain)
    "$vis4gs" analyze "$log" "${common[@]}" --scores=coverage --output="$work/plain" \
      > "$work/plain.log" 2>&1 || fail "plain run failed"
    grep -q "process" "$work/plain.log" && fail "a plain run mentions processes (MPI started?)"
    [ -s "$work/plain/scores.csv" ] || fail "no scores.csv"
    echo "PASSED plain"
    ;;
  *) fail "unknown mode $mode" ;;
esac
