#!/bin/bash
# vis4gs train, interrupted with SIGINT (what Ctrl-C sends) while it trains: it must stop after
# the current iteration, exit with 130 and leave a valid log whose last snapshot is the
# iteration it stopped at. Usage: TrainInterrupt.sh VIS4GS SCENE.json WORKDIR
set -u
vis4gs=$1
scene=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir"
fail()
{
  echo "FAILED: $*"
  cat "$dir/train.txt"
  exit 1
}
"$vis4gs" train "$scene" --resolution=32 --iterations=1000000 --snapshot-interval=1000000 \
  --output="$dir/run.h5" --threads=1 >"$dir/train.txt" 2>&1 &
pid=$!
# Wait for the first progress line (iteration 100), at most 5 minutes.
for _ in $(seq 1 3000); do
  grep -q '^  iteration ' "$dir/train.txt" && break
  kill -0 "$pid" 2>/dev/null || fail "vis4gs train ended before it was interrupted"
  sleep 0.1
done
grep -q '^  iteration ' "$dir/train.txt" || { kill -9 "$pid"; fail "no progress line in 5 minutes"; }
kill -INT "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 130 ] || fail "exit status $rc after SIGINT, expected 130"
stopped=$(sed -n 's/^vis4gs train: interrupted at iteration \([0-9]*\),.*/\1/p' "$dir/train.txt")
[ -n "$stopped" ] || fail "no 'interrupted at iteration' line"
[ ! -e "$dir/run.h5.tmp" ] || fail "a temporary file was left behind"
"$vis4gs" analyze "$dir/run.h5" --scores=shape --output="$dir/analyze" >"$dir/analyze.txt" 2>&1 ||
  { cat "$dir/analyze.txt"; fail "the interrupted log does not load"; }
grep -q "snapshot of iteration $stopped," "$dir/analyze.txt" ||
  { cat "$dir/analyze.txt"; fail "the last snapshot is not iteration $stopped"; }
echo "interrupted at iteration $stopped; the log is valid and ends with its snapshot"
