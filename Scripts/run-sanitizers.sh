#!/usr/bin/env bash
# The project under sanitizers (issue 35, part 1), each part in its own build folder:
#
#   bash Scripts/run-sanitizers.sh core   [build dir, default build-asan-core]
#       Core only (no VTK), with AddressSanitizer + UndefinedBehaviorSanitizer, and every
#       Core test (GoogleTest): the bounded part, which Scripts/quickstart.sh test runs.
#   bash Scripts/run-sanitizers.sh full   [build dir, default build-asan]
#       The whole project with ASan + UBSan; runs the Core, IO, filter and Python tests (ctest -L
#       Core|IO|Filters|Python; Python loads the instrumented modules with libasan preloaded).
#       A cold build of everything: about 20-40 minutes on 2 cores.
#   bash Scripts/run-sanitizers.sh thread [build dir, default build-tsan]
#       The vis4gs program's own code with ThreadSanitizer (VIS4GS_TSAN_WHOLE=1: the whole
#       project), and the scripted session of `vis4gs view` on the demo log (worker-thread
#       load, scores in the background, iteration changes, the clean-up panel's measurement and
#       fine-tune): vis4gs view --self-test under Xvfb; and the sort worker's GoogleTests
#       (its thread, instrumented in that build too). Suppressions: tsan-suppressions.txt.
#
# Any report fails the run (halt_on_error, exit status 1), naming the part. ccache is used when
# installed. VIS4GS_JOBS sets the build's parallelism (default: nproc).
set -euo pipefail

part="${1:-}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${VIS4GS_JOBS:-$(nproc)}"
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# Suppressions for what is not ours (none needed so far) would go next to this script.
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:abort_on_error=0:exitcode=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=1:${UBSAN_OPTIONS:-}"
export TSAN_OPTIONS="halt_on_error=1:exitcode=1:second_deadlock_stack=1:${TSAN_OPTIONS:-}"

# GCC by default, the compiler of every other build: Core's SIMD kernels use GCC's vector
# builtins (__builtin_shuffle) that clang does not have. VIS4GS_SANITIZER_CC=clang tries clang.
cc="${VIS4GS_SANITIZER_CC:-gcc}"
case "$cc" in
  clang*) cxx="${cc/clang/clang++}" asanlib=libclang_rt.asan-x86_64.so ;;
  *) cxx="${cc/gcc/g++}" asanlib=libasan.so ;;
esac

configure()
{
  local build="$1" flags="$2"
  shift 2
  CC="$cc" CXX="$cxx" cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DVIS4GS_WARNINGS_AS_ERRORS=OFF "${launcher[@]}" \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" "$@" >/dev/null
}

asan="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
case "$part" in
  core)
    build="${2:-$root/build-asan-core}"
    configure "$build" "$asan" -DVIS4GS_CORE_ONLY=ON
    # The GoogleTest programs, and the converter the decoders' reference tests (label Core)
    # drive: the benchmarks are not run here, so they are not built.
    mapfile -t targets < <(ninja -C "$build" -t targets all |
      sed -n 's/^\(vis4gsCore[A-Za-z]*Tests\): phony$/\1/p')
    targets+=(vis4gsSceneConvert)
    cmake --build "$build" -j "$jobs" --target "${targets[@]}"
    ctest --test-dir "$build" --output-on-failure --timeout 1800 -j "$jobs" -L '^Core$'
    ;;
  full)
    build="${2:-$root/build-asan}"
    configure "$build" "$asan"
    cmake --build "$build" -j "$jobs"
    # Python is not instrumented: the sanitizer runtimes come first, leaks of the interpreter
    # itself are not ours.
    libasan="$("$cc" -print-file-name="$asanlib")"
    (cd "$build" && LD_PRELOAD="$libasan" ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" \
      bash "$root/Scripts/with-display.sh" --new \
      ctest --output-on-failure --timeout 1800 -j "$jobs" -L "Core|IO|Filters|Python")
    ;;
  thread)
    build="${2:-$root/build-tsan}"
    # history_size=7 (the most): the earlier access of a race is reported with its stack (which
    # the suppressions file matches) even after the many accesses of a long session.
    # detect_deadlocks=0: Mesa's GLX holds more than the 64 mutexes at once that TSan's lock-order
    # detector can track per thread, and TSan then stops on an internal CHECK.
    export TSAN_OPTIONS="suppressions=$root/Scripts/tsan-suppressions.txt:detect_deadlocks=0:history_size=7:$TSAN_OPTIONS"
    # OpenMP's runtime (libgomp) is not built with TSan: the start and barriers of a parallel
    # loop are invisible to it, so that every loop (the splat sort, the log's chunk decoding)
    # shows as a race. One OpenMP thread; the program's own threads are what is under test.
    # OMP_THREAD_LIMIT=1: also a loop whose num_threads asks for more (the sort worker's test
    # asks for 2) runs on one thread.
    export OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
    if [ "${VIS4GS_TSAN_WHOLE:-0}" = 1 ]; then
      # Everything instrumented (a cold build of the whole project).
      configure "$build" "-fsanitize=thread -fno-omit-frame-pointer"
    else
      # The program's own code only: its threads, what they share and how they hand results
      # over; the libraries configured as quickstart.sh does, so that ccache has them.
      cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DVIS4GS_WARNINGS_AS_ERRORS=ON "${launcher[@]}" -DVIS4GS_PROGRAM_SANITIZER=thread \
        >/dev/null
    fi
    start=$SECONDS
    cmake --build "$build" -j "$jobs" --target vis4gs vis4gsCoreSplatsTests \
      vis4gsRenderingSplatsCxxTests vis4gsFiltersSelectionCxxTests MakeBenchmarkPly
    echo "run-sanitizers.sh thread: built in $((SECONDS - start)) s"
    # The GPU renderer's sort worker (Core/Splats/SplatSortWorker) runs on hardware OpenGL
    # only, not in the session under Xvfb: its GoogleTests drive its thread instead, with those
    # of the moving set (the builder's spare buffers) and the level of detail.
    "$build/bin/vis4gsCoreSplatsTests" \
      --gtest_filter='SplatSortWorker.*:SplatMovingSet.*:SplatLevelOfDetail.*'
    # The mapper's frame worker and level-of-detail builder (the level-of-detail test: rebuilds
    # ahead on and off; the asynchronous frames: worker, newest request, scene replaced, modes
    # switched, and an orbit with rebuilds ahead) and the frustums' background count.
    (cd "$build" && bash "$root/Scripts/with-display.sh" --new ctest --output-on-failure \
      --timeout 1800 -R 'RenderingSplatsCxx-TestGaussianSplatMapper(LevelOfDetail|AsyncFrames)$|FiltersSelectionCxx-TestGaussianCameraFrustums$')
    echo "run-sanitizers.sh thread: tests done at $((SECONDS - start)) s"
    bash "$root/Scripts/with-display.sh" --new "$build/bin/vis4gs" view \
      "$root/Data/Demo/vis4gs-demo.h5" "--self-test=$build/self-test" --resolution=1200,800
    echo "run-sanitizers.sh thread: self-test done at $((SECONDS - start)) s"
    # The scene view's orbit and the four picks: frames made on the mapper's worker while the
    # GUI thread moves the camera and the selector reads the last exact frame's kept blends;
    # the demo log's tree and linked views answer the picks through the hub.
    bash "$root/Scripts/with-display.sh" --new "$build/bin/vis4gs" view \
      "$root/Data/Demo/vis4gs-demo.h5" --benchmark --resolution=800,600
    echo "run-sanitizers.sh thread: demo benchmark done at $((SECONDS - start)) s"
    # The same on a SYNTHETIC scene larger than the window's moving budget (400,000), so the
    # orbit's frames are reduced (the level of detail made on the worker after the first exact
    # frame, the moving set), with a ring of training cameras (cameras.json beside it) so that
    # the frustums are shown and the Frame pick's selection, above BackgroundCountMinimum
    # (20,000), is counted on the frustums' worker: the view starts at the first camera, at 7
    # from the scene's centre, whence the Frame pick selects 49,149 Gaussians (3.5: 6,775).
    scene="$build/tsan-scene"
    mkdir -p "$scene"
    [ -f "$scene/scene.ply" ] || "$build/benchmarks/MakeBenchmarkPly" "$scene/scene.ply" 450000 1 3
    python3 - "$scene/cameras.json" <<'PY'
import json, math, sys
cams = []
for k in range(12):
    a = 2 * math.pi * k / 12
    pos = [-7 * math.sin(a) * math.cos(-0.35), 7 * math.sin(-0.35),
           -7 * math.cos(a) * math.cos(-0.35)]
    n = math.sqrt(sum(v * v for v in pos))
    z = [-v / n for v in pos]  # looks at the origin; y (down) is world +y made orthogonal
    y = [0.0 - z[1] * z[0], 1.0 - z[1] * z[1], 0.0 - z[1] * z[2]]
    n = math.sqrt(sum(v * v for v in y))
    y = [v / n for v in y]
    x = [y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0]]
    cams.append({"id": k, "img_name": "ring%02d" % k, "width": 640, "height": 480,
                 "position": pos, "rotation": [[x[i], y[i], z[i]] for i in range(3)],
                 "fx": 554.0, "fy": 554.0})
json.dump(cams, open(sys.argv[1], "w"))
PY
    bash "$root/Scripts/with-display.sh" --new "$build/bin/vis4gs" view "$scene/scene.ply" \
      --benchmark --resolution=800,600
    echo "run-sanitizers.sh thread: scene benchmark done at $((SECONDS - start)) s"
    ;;
  *)
    echo "usage: bash Scripts/run-sanitizers.sh core|full|thread [build dir]" >&2
    exit 2
    ;;
esac
echo "run-sanitizers.sh $part: no report"
