#!/bin/sh
# Usage: RunVis4GS.sh PROGRAM ARGS...
# Runs the main build's vis4gs program (whose outputs the plugin's must equal), or says that
# it is missing and how to get it.
program="$1"
shift
if [ ! -x "$program" ]; then
  echo "FAILED: $program does not exist: build the main build first, or set VIS4GS_PROGRAM"
  exit 1
fi
exec "$program" "$@"
