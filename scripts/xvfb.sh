#!/usr/bin/env bash
# Usage: scripts/xvfb.sh command...   Runs the command under its own Xvfb (a free display,
# 1280x1024x24; GL through Mesa llvmpipe).
#
# -noreset: by default Xvfb resets when its last client disconnects, and a client that
# connects during that reset is dropped before its setup is answered, so XOpenDisplay fails
# and VTK aborts with "bad X server connection". Processes that open and close windows side
# by side (ctest -j 2, pvserver's ranks) hit it now and then: 4 processes running xdpyinfo
# 300 times each failed 47 times of 1200 without -noreset here, and 0 with it.
exec xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$@"
