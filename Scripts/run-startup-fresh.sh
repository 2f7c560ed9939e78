#!/usr/bin/env bash
# Start-up of the big inputs as on a newly started machine, 5 whole processes each (issue 21).
#   bash Scripts/run-startup-fresh.sh [build dir, default build] [log, default startup-fresh.log]
# Before each run: the page cache is dropped (the input file and the libraries are read from
# disk) and the machine idles for 60 s. On the project's VMs the balloon device reports free
# memory to the host (virtio-balloon free page reporting, blocks of 2 MiB), and the host
# discards it: the huge pages a process takes afterwards are first-touched on the host as on a
# new machine (measured: 4.5-4.8 us per 4 KiB, against 0.7 us on memory just freed). Dropping
# the cache needs root; without it the runs are on a warm cache and the log says so. The inputs
# are those of Scripts/run-benchmarks.sh, made there if absent. Takes about 25 minutes.
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
log="${2:-startup-fresh.log}"
dir="${VIS4GS_BENCH_DIR:-/tmp}"
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}

[ -f "$dir/vis4gs-bench-6.1M.ply" ] ||
  "$build/benchmarks/MakeBenchmarkPly" "$dir/vis4gs-bench-6.1M.ply" 6100000 3
for n in 4890000 10000000; do
  [ -f "$dir/vis4gs-bench-$n.h5" ] ||
    "$build/bin/vis4gsMakeTestLog" "$dir/vis4gs-bench-$n.h5" "$n" 4
done

: >"$log"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)," \
  "$(free -g | awk '/Mem/ {print $2}') GiB, up $(cut -d' ' -f1 /proc/uptime) s" | tee -a "$log"
for input in vis4gs-bench-4890000.h5 vis4gs-bench-10000000.h5 vis4gs-bench-6.1M.ply; do
  for run in 1 2 3 4 5; do
    sync
    if ! (echo 3 >/proc/sys/vm/drop_caches) 2>/dev/null; then
      echo "(could not drop the page cache: not root; this run reads a warm cache)" | tee -a "$log"
    fi
    sleep 60
    echo "=== $input run $run (load: $(cut -d' ' -f1-3 /proc/loadavg))" | tee -a "$log"
    xvfb-run -a -s "-screen 0 1920x1080x24" /usr/bin/time -v "$build/bin/vis4gs" view \
      "$dir/$input" --benchmark --resolution=1280,800 2>&1 | tee -a "$log" |
      grep -E "start to all views ready|first render: scene|Maximum resident|Elapsed"
  done
done
