#!/usr/bin/env bash
# Runs every benchmark program one after another (never in parallel: they measure the whole
# machine) and keeps their printed figures in one log. The figures recorded in
# Documentation/performance.md come from this script on an otherwise idle machine.
#   bash Scripts/run-benchmarks.sh [build dir, default build] [log, default benchmarks.log]
# Large temporary files go to ${VIS4GS_BENCH_DIR:-/tmp}; the whole run takes tens of minutes.
# Start-up as on a newly started machine (cold cache, host-fresh memory): run-startup-fresh.sh.
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
# Spinning OpenMP workers only steal time from each other on 2 cores.
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
build="${1:-build}"
log="${2:-benchmarks.log}"
dir="${VIS4GS_BENCH_DIR:-/tmp}"
bin="$build/benchmarks"

run() {
  echo "=== $* (load: $(cut -d' ' -f1-3 /proc/loadavg))" | tee -a "$log"
  local start=$SECONDS
  timeout 1800 "$@" 2>&1 | tee -a "$log"
  echo "=== finished in $((SECONDS - start)) s" | tee -a "$log"
}

: >"$log"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)," \
  "$(free -g | awk '/Mem/ {print $2}') GiB" | tee -a "$log"
run "$bin/BenchmarkGaussianPly" --gaussians=1000000,5000000 "--dir=$dir" --repeat=3
run "$bin/BenchmarkRasterizer" 1000000
run "$bin/BenchmarkRasterizer" --peak
run "$bin/BenchmarkArtifactScores" perf
run "$bin/BenchmarkTrainingLog" "--dir=$dir"
run "$bin/BenchmarkTrainingLog" "--dir=$dir" --gaussians=0 --events=0 --history-snapshots=60 \
  --history-gaussians=500000
run "$bin/BenchmarkGenealogy"
run "$bin/BenchmarkGenealogyTree"
run "$bin/BenchmarkTrainer" --gaussians=50000 --size=256 --iterations=60 --threads=2
run "$bin/BenchmarkSplats" 1000000 2 5
run "$bin/BenchmarkSelection" 1000000 2 3
run "$bin/BenchmarkRemovalEffect" 1000000 4 1920 1080 2 3 3
# Scene view on software OpenGL: interactive frames at half resolution, then auto-adjusted.
run xvfb-run -a "$bin/BenchmarkGaussianSplatMapper" 1000000 1280 720 5 0 2 1 0 2 2
run xvfb-run -a "$bin/BenchmarkGaussianSplatMapper" 1000000 1280 720 5 0 2 1 0 2 0
# Application start-up (whole process: wall, CPU, peak RSS, page faults) on SYNTHETIC logs of
# 1.06M, 4.89M and 10M final Gaussians (issue 21: 10M is 20M genealogy nodes) and on a
# bicycle-sized SYNTHETIC PLY (6.1M Gaussians, SH degree 3).
for n in 1060000 4890000 10000000; do
  [ -f "$dir/vis4gs-bench-$n.h5" ] || "$build/bin/vis4gsMakeTestLog" "$dir/vis4gs-bench-$n.h5" "$n" 4
  run xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/time -v "$build/bin/vis4gs" view \
    "$dir/vis4gs-bench-$n.h5" --benchmark --resolution=1280,800
done
[ -f "$dir/vis4gs-bench-6.1M.ply" ] || "$bin/MakeBenchmarkPly" "$dir/vis4gs-bench-6.1M.ply" 6100000 3
run xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/time -v "$build/bin/vis4gs" view \
  "$dir/vis4gs-bench-6.1M.ply" --benchmark --resolution=1280,800
# The demo's training run: the command of Data/Demo/README.md, into a temporary file, timed as
# a whole process.
run /usr/bin/time -v "$build/bin/vis4gs" train "$root/Data/Scenes/demo.json" \
  "--output=$dir/vis4gs-bench-demo.h5" --iterations=2000 --schedule-scale --snapshot-interval=200 \
  --snapshot-sh-degree=0 --densify-grad-threshold=0.001 --embed-images --seed=0 --threads=2 \
  --snapshot-deflate=4
