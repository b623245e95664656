#!/usr/bin/env bash
# Sets up and builds, runs every test (ctest under Xvfb), then the core unit tests again in a
# build with AddressSanitizer and UndefinedBehaviorSanitizer. Exits non-zero on any failure.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh"
cd "$here/build"
xvfb-run -a -s "-screen 0 1280x1024x24" ctest --output-on-failure -j 2

asan="$here/build-asan"
echo "== core tests under AddressSanitizer + UndefinedBehaviorSanitizer"
cmake -S "$here" -B "$asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPARC_ENABLE_SANITIZERS=ON -DPARC_WRAP_PYTHON=OFF >/dev/null
cmake --build "$asan" -j "$(nproc)" --target parcCoreTests
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$asan" --output-on-failure -L core
