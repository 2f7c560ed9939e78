#!/usr/bin/env bash
# The measurement of "Scores over MPI" in Documentation/performance.md (issue 18): 1 and 2
# processes x 1 and 2 OpenMP threads per process, 1M Gaussians x 200 views of 1280x720
# (coverage at full resolution, blur and needle at 1/4), on an otherwise idle machine.
#   bash Scripts/run-mpi-benchmark.sh [build dir, default build] [log, default mpi-benchmark.log]
# Extra arguments after the log go to the benchmark (e.g. --gaussians=20000 --views=12 for a
# quick check). Each RESULT line gives the constants of the projection model; the first run
# writes the 200 training images (PNG) to /tmp once, outside the timed part.
set -uo pipefail
build="${1:-build}"
log="${2:-mpi-benchmark.log}"
shift $(($# < 2 ? $# : 2))
bench="$build/benchmarks/BenchmarkScoresMPI"
[ -x "$bench" ] || { echo "$bench is missing: build with -DVIS4GS_USE_MPI=ON" >&2; exit 1; }
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
: >"$log"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)," \
  "$(free -g | awk '/Mem/ {print $2}') GiB; $(mpiexec --version | head -1)" | tee -a "$log"
for threads in 1 2; do
  for ranks in 1 2; do
    echo "=== $ranks process(es) x $threads thread(s) (load: $(cut -d' ' -f1-3 /proc/loadavg))" \
      | tee -a "$log"
    # --bind-to none: Open MPI would otherwise pin each process to one core, and 2 threads per
    # process could not use a second one.
    OMP_NUM_THREADS=$threads timeout 1800 mpiexec -n "$ranks" --oversubscribe --bind-to none \
      -x OMP_NUM_THREADS -x OMP_WAIT_POLICY "$bench" "$@" 2>&1 | grep -v "WARN|" | tee -a "$log"
  done
done
# Speed-up at equal threads per process.
awk '/^RESULT/ { for (i = 2; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] }
       wall[v["processes"], v["threads"]] = v["wall"] }
     END { for (t = 1; t <= 2; ++t) if (wall[2, t] > 0)
       printf "speed-up 2 processes vs 1 at %d thread(s) per process: %.2fx\n", t,
         wall[1, t] / wall[2, t] }' "$log" | tee -a "$log"
