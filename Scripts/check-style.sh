#!/usr/bin/env bash
# Project rules CTest checks on every run (see Documentation/dev/CODING_STYLE.md):
#   layering  Core/ includes no VTK header (DESIGN §1);
#   modules   VTK modules depend downwards only: IO < Filters < Rendering < Views
#             (Documentation/dev/ARCHITECTURE.md), no exception;
#   deps      each VTK module lists exactly the modules its sources include, no unused one
#             (Scripts/check-module-deps.py);
#   format    our C++ follows VTK 9.1's .clang-format (Debian's clang-format 14);
#   length    a source file (.cxx .h .hxx .txx .cpp .inc .py .glsl) over 1,200 lines says why
#             within its first 25 lines, with the marker "Over 1,200 lines on purpose:"
#             (Documentation/dev/ARCHITECTURE.md, "File size");
#   tests     no CTest test sets PASS_REGULAR_EXPRESSION, which makes CTest ignore the exit
#             status (Documentation/dev/TESTING.md).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
check="${1:-all}"
status=0

if [ "$check" = layering ] || [ "$check" = all ]; then
  bad=$(grep -rlE '^\s*#\s*include\s*[<"](vtk|QVTK)' Core --include='*.h' --include='*.cxx' \
    --include='*.hxx' --include='*.txx' --include='*.inc' || true)
  if [ -n "$bad" ]; then
    echo "FAILED: Core/ must not include VTK headers; found in:"
    echo "$bad"
    status=1
  else
    echo "layering: Core/ includes no VTK header"
  fi
fi

if [ "$check" = modules ] || [ "$check" = all ]; then
  rank() { case "$1" in IO*) echo 1 ;; Filters*) echo 2 ;; Rendering*) echo 3 ;; Views*) echo 4 ;; *) echo 9 ;; esac; }
  bad=()
  count=0
  for m in $(git ls-files '*vtk.module'); do
    own=$(awk '$1 == "NAME" { getline; print $1; exit }' "$m")
    ownRank=$(rank "${m%%/*}")
    # Vis4GS:: names under DEPENDS and PRIVATE_DEPENDS (not TEST_DEPENDS).
    deps=$(awk '/^[A-Z_]+$/ { section = $1; next } section == "DEPENDS" || section == "PRIVATE_DEPENDS" { for (i = 1; i <= NF; ++i) if ($i ~ /^Vis4GS::/) print $i }' "$m")
    for d in $deps; do
      count=$((count + 1))
      dRank=$(rank "${d#Vis4GS::}")
      if [ "$dRank" -gt "$ownRank" ]; then
        bad+=("$m: $own depends on $d, a higher layer")
      fi
    done
  done
  if [ ${#bad[@]} -gt 0 ]; then
    echo "FAILED: VTK modules must depend downwards (IO < Filters < Rendering < Views):"
    printf '  %s\n' "${bad[@]}"
    status=1
  else
    echo "modules: $count Vis4GS module dependencies point downwards"
  fi
fi

if [ "$check" = deps ] || [ "$check" = all ]; then
  /usr/bin/python3 Scripts/check-module-deps.py . || status=1
fi

if [ "$check" = format ] || [ "$check" = all ]; then
  format=$(command -v clang-format-14 || command -v clang-format || true)
  if [ -z "$format" ]; then
    echo "FAILED: clang-format is not installed (bash Scripts/setup-deps.sh installs it)"
    exit 1
  fi
  mapfile -t files < <(git ls-files --cached --others --exclude-standard \
    '*.h' '*.cxx' '*.hxx' '*.txx' '*.cpp' '*.inc' | grep -v '^build' || true)
  bad=()
  for f in "${files[@]}"; do
    [ -f "$f" ] || continue
    if ! "$format" --style=file --dry-run -Werror "$f" >/dev/null 2>&1; then
      bad+=("$f")
    fi
  done
  if [ ${#bad[@]} -gt 0 ]; then
    echo "FAILED: not formatted with .clang-format (run: clang-format -i FILE):"
    printf '  %s\n' "${bad[@]}"
    status=1
  else
    echo "format: ${#files[@]} files follow .clang-format"
  fi
fi
if [ "$check" = length ] || [ "$check" = all ]; then
  mapfile -t files < <(git ls-files --cached --others --exclude-standard \
    '*.h' '*.cxx' '*.hxx' '*.txx' '*.cpp' '*.inc' '*.py' '*.glsl' | grep -v '^build' || true)
  bad=()
  long=0
  for f in "${files[@]}"; do
    [ -f "$f" ] || continue
    lines=$(wc -l <"$f")
    [ "$lines" -gt 1200 ] || continue
    long=$((long + 1))
    if ! head -n 25 "$f" | grep -q 'Over 1,200 lines on purpose:'; then
      bad+=("$f ($lines lines)")
    fi
  done
  if [ ${#bad[@]} -gt 0 ]; then
    echo "FAILED: over 1,200 lines without \"Over 1,200 lines on purpose: <why>\" in the first 25"
    echo "lines (split the file along its responsibilities, or say why it is one file):"
    printf '  %s\n' "${bad[@]}"
    status=1
  else
    echo "length: ${#files[@]} source files, $long over 1,200 lines, each saying why"
  fi
fi

if [ "$check" = tests ] || [ "$check" = all ]; then
  bad=$(git grep -n --untracked -E '^[^#]*PASS_REGULAR_EXPRESSION' -- '*CMakeLists.txt' '*.cmake' || true)
  if [ -n "$bad" ]; then
    echo "FAILED: PASS_REGULAR_EXPRESSION makes CTest ignore the exit status; use"
    echo "vis4gs_add_checked_test(... OUTPUT regex) (CMake/Vis4GSTesting.cmake) instead:"
    echo "$bad"
    status=1
  else
    echo "tests: no test passes on a line of text alone"
  fi
fi
exit $status
