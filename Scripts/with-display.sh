#!/usr/bin/env bash
# Usage: bash Scripts/with-display.sh [--new] COMMAND...
# Runs COMMAND with an X server. Without --new, the one in $DISPLAY when there is one (the test
# command starts one for the whole run and every test that renders uses it); else, and always
# with --new, a private Xvfb (1920x1080x24) for COMMAND alone, stopped when it ends.
#
# Why not plain `xvfb-run -a` (issue 35): Xvfb resets itself whenever its last client
# disconnects, and a client that connects during that reset is dropped before its setup is
# answered, so XOpenDisplay returns NULL and VTK aborts with "bad X server connection.
# DISPLAY=:99". pvbatch opens and closes the display before it makes its render window, and
# tests running in parallel under one server open and close theirs at any time; a loaded
# machine widens the window. Measured here: 4 processes opening and closing a display 300 times
# each lose 58 of 1200 connections against xvfb-run's default server and none with -noreset.
# xvfb-run picks the display number and retries when another server took it; -noreset removes
# the reset.
set -euo pipefail

new=0
if [ "${1:-}" = --new ]; then
  new=1
  shift
fi
if [ $# -eq 0 ]; then
  echo "usage: bash Scripts/with-display.sh [--new] COMMAND..." >&2
  exit 2
fi
if [ "$new" = 0 ] && [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
if ! command -v xvfb-run >/dev/null; then
  echo "with-display.sh: xvfb-run is not installed (Debian package xvfb; Scripts/setup-deps.sh" \
    "installs it)" >&2
  exit 1
fi
exec xvfb-run -a -s "-noreset -screen 0 1920x1080x24" "$@"
