#!/usr/bin/env bash
# Project rules CTest checks on every run (see Documentation/dev/CODING_STYLE.md):
#   layering  Core/ includes no VTK header (DESIGN §1);
#   format    our C++ follows VTK 9.1's .clang-format (Debian's clang-format 14).
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
exit $status
