#!/usr/bin/env bash
# Sets up and builds, runs every test (ctest under Xvfb), then the core unit tests and the
# C++ image and rendering tests again in a build with AddressSanitizer and
# UndefinedBehaviorSanitizer, then the ParaView plugin's tests (scripts/paraview.sh; said
# and skipped only when ParaView cannot be installed beside VTK). Exits non-zero on any
# failure.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh"
cd "$here/build"
"$here/scripts/xvfb.sh" ctest --output-on-failure -j 2

asan="$here/build-asan"
echo "== core and image tests under AddressSanitizer + UndefinedBehaviorSanitizer"
cmake -S "$here" -B "$asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPARC_ENABLE_SANITIZERS=ON -DPARC_WRAP_PYTHON=OFF >/dev/null
cmake --build "$asan" -j "$(nproc)" --target parcCoreTests parcCxxTests
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$asan" --output-on-failure -L core
# Leak checking stays off for the GL tests: llvmpipe's JIT code leaves allocations that
# LeakSanitizer cannot attribute (an unknown module); every other check is on.
ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 \
  "$here/scripts/xvfb.sh" \
  ctest --test-dir "$asan" --output-on-failure -L "image|rendering"

echo "== the ParaView plugin (scripts/paraview.sh)"
status=0
"$here/scripts/paraview.sh" || status=$?
if [ "$status" = 77 ]; then
  echo "== SKIPPED the ParaView plugin's tests: ParaView cannot be installed beside VTK here" \
    "(reason above)"
elif [ "$status" != 0 ]; then
  exit "$status"
fi
