#!/usr/bin/env bash
# Runs every benchmark program one after another (never in parallel: they measure the whole
# machine) and keeps their printed figures in one log. The figures recorded in
# Documentation/performance.md come from this script on an otherwise idle machine.
#   bash Scripts/run-benchmarks.sh [build dir, default build] [log, default benchmarks.log]
# Large temporary files go to ${VIS4GS_BENCH_DIR:-/tmp}; the whole run takes tens of minutes.
set -uo pipefail
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
run "$bin/BenchmarkRasterizer"
run "$bin/BenchmarkRasterizer" --peak
run "$bin/BenchmarkArtifactScores" perf
run "$bin/BenchTrainingLog" "--dir=$dir"
run "$bin/BenchmarkGenealogy"
run "$bin/BenchmarkGenealogyTree"
run "$bin/BenchmarkTrainer" --gaussians=50000 --size=256 --threads=2
run "$bin/BenchmarkSplats"
run "$bin/BenchmarkSelection"
run xvfb-run -a "$bin/BenchmarkGaussianSplatMapper"
