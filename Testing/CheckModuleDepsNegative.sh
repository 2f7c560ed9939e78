#!/usr/bin/env bash
# The module dependency check (Scripts/check-module-deps.py) on a made-up source tree: exact
# lists pass, an unused and an undeclared dependency each fail with exit status 1.
set -u
check="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir -p "$dir/Views/Fake"
cat > "$dir/Views/Fake/vtkFakeView.h" <<'H'
#include "vtkObject.h"
#include "vtkTable.h"
H
write_module() {
  { printf 'NAME\n  Vis4GS::ViewsFake\nDEPENDS\n'; for d in "$@"; do printf '  %s\n' "$d"; done; } \
    > "$dir/Views/Fake/vtk.module"
}
expect() {
  /usr/bin/python3 "$check" "$dir" > "$dir/out.txt" 2>&1
  local rc=$?
  if [ "$rc" -ne "$1" ]; then
    echo "FAILED: $2: exit status $rc, expected $1"; cat "$dir/out.txt"; exit 1
  fi
}
write_module VTK::CommonCore VTK::CommonDataModel
expect 0 "exact dependencies"
write_module VTK::CommonCore VTK::CommonDataModel VTK::InfovisCore
expect 1 "an unused dependency (VTK::InfovisCore)"
grep -q "VTK::InfovisCore" "$dir/out.txt" || { echo "FAILED: the unused module is not named"; exit 1; }
write_module VTK::CommonCore
expect 1 "an undeclared dependency (VTK::CommonDataModel)"
grep -q "VTK::CommonDataModel" "$dir/out.txt" || { echo "FAILED: the undeclared module is not named"; exit 1; }
echo "module dependency check: exact passes, unused and undeclared fail"
