#!/usr/bin/env bash
# The main job: sets up and builds, then draws real volumes with vtkPARCVolumeMapper beside
# the VTK mapper a user would otherwise pick, writes a comparison picture per scene to out/
# and prints a table of warm frame times, speed ratios, samples and errors.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh"
out="$here/out"
mkdir -p "$out"
echo "== $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(date -u +%F)"
PYTHONPATH="$here/build/lib/python3.11/dist-packages${PYTHONPATH:+:$PYTHONPATH}" \
  "$here/scripts/xvfb.sh" /usr/bin/python3 "$here/scripts/demo.py" "$out" "$@"
echo "== pictures in $out (demo-*.png)"
