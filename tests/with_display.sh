#!/bin/sh
# Runs a test that renders (VTK draws through X) on the display there is, or, without one, on
# a virtual display started by xvfb-run, as `rbcflow` does for itself (apps/display.cpp): the
# render tests pass with or without a display.
if [ -n "${DISPLAY:-}" ]; then exec "$@"; fi
exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$@"
