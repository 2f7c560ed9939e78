#!/bin/sh
# Usage: RunIfPresent.sh FILE COMMAND [ARGS...]
# Runs COMMAND when FILE exists. Otherwise says which file is missing and exits 77 (the
# tests' SKIP_RETURN_CODE), or 1 under CI=true, where shared data must be present.
file="$1"
shift
if [ ! -e "$file" ]; then
  echo "skipped: shared data file $file is missing (set VIS4GS_SHARED_DATA_DIR)"
  if [ "$CI" = "true" ]; then
    echo "FAILED: CI=true and $file is missing"
    exit 1
  fi
  exit 77
fi
exec "$@"
