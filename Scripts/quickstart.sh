#!/usr/bin/env bash
# The README's two commands. Both install what is missing, configure once, build
# incrementally, and are cheap to re-run when nothing changed.
#   bash Scripts/quickstart.sh demo   # build and run `vis4gs demo` on the embedded scene
#   bash Scripts/quickstart.sh test   # build and run every test and check (what CI runs)
# Environment: VIS4GS_BUILD_DIR (default: build), VIS4GS_JOBS (default: nproc),
# VIS4GS_FUZZ_SECONDS (per fuzz target in the test command, default: 15), VIS4GS_PARAVIEW
# (default 1: the test command also builds and tests the ParaView plugin in <build>-paraview;
# 0 leaves it out), VIS4GS_SANITIZERS (default 1: the test command also runs the sanitizers'
# bounded part in <build>-asan-core; 0 leaves it out).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${VIS4GS_BUILD_DIR:-$here/build}"
jobs="${VIS4GS_JOBS:-$(nproc)}"
what="${1:-}"

case "$what" in
  demo|test) ;;
  *)
    echo "usage: bash Scripts/quickstart.sh demo|test" >&2
    exit 2
    ;;
esac

bash "$here/Scripts/setup-deps.sh"

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DVIS4GS_WARNINGS_AS_ERRORS=ON
fi
cmake --build "$build" -j "$jobs"

if [ "$what" = demo ]; then
  # With a display the demo opens the application; without one it writes the batch report.
  exec "$build/bin/vis4gs" demo "${@:2}"
fi

# The parsers' libFuzzer targets, for a bounded time (clang + ASan, Core only, own build dir).
bash "$here/Scripts/run-fuzzers.sh" "${VIS4GS_FUZZ_SECONDS:-15}" "$build-fuzz"

# The sanitizers' bounded part: Core and its tests under ASan + UBSan (GCC, own build dir, about
# 16 minutes on 2 idle cores from scratch, TESTING.md); any report fails the test command.
if [ "${VIS4GS_SANITIZERS:-1}" != 0 ]; then
  bash "$here/Scripts/run-sanitizers.sh" core "$build-asan-core"
fi

# One X server (Xvfb, -noreset: Scripts/with-display.sh says why) for every test that renders.
(cd "$build" && bash "$here/Scripts/with-display.sh" --new \
  ctest --output-on-failure --timeout 900 -j "$jobs" "${@:2}")

# The ParaView plugin (Plugins/ParaView, its own build folder): Debian's ParaView packages
# (setup-deps.sh --paraview), and python3-paraview downloaded for pvbatch (its test is skipped
# without a network, an error under CI=true). About 2 CPU-minutes to build from scratch.
if [ "${VIS4GS_PARAVIEW:-1}" = 1 ]; then
  bash "$here/Scripts/setup-deps.sh" --paraview
  if [ ! -f "$build-paraview/CMakeCache.txt" ]; then
    cmake -S "$here/Plugins/ParaView" -B "$build-paraview" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DVIS4GS_PROGRAM="$build/bin/vis4gs"
  fi
  cmake --build "$build-paraview" -j "$jobs"
  bash "$here/Scripts/with-display.sh" --new \
    ctest --test-dir "$build-paraview" --output-on-failure --timeout 900
fi
