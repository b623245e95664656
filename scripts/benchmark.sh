#!/usr/bin/env bash
# Benchmarks of PARC against unaccelerated casting, every mode side by side in one run per
# scene (issues 5 and 6): samples, cells, polygons, projection, casting and total time,
# speedup, and whether the float image is bit-identical. Records the machine and settings.
# Output: a markdown report on stdout and in out/benchmark.md. Scenes from ../shared/data
# are skipped when absent.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh" >/dev/null
data="$here/../shared/data"
head=/usr/share/mricron/templates/ch2.nii.gz
mkdir -p "$here/out"
xrun() { xvfb-run -a -s "-screen 0 1280x1024x24" "$@"; }
render() { xrun "$here/build/bin/parc-render" "$@" --repeat 3 --sample-distance 0.25 \
  --output "$here/out/benchmark.png" | grep -v '^mapper\|^PARC \|^sample distance'; }
scene() { # title, file, options...
  local title=$1 file=$2; shift 2
  if [ ! -f "$file" ]; then echo "($title: $file not found, skipped)"; return; fi
  for size in 300 600; do
    echo; echo "### $title, ${size}x${size}"; echo
    render "$file" --size "$size" "$@" --compare-acceleration
  done
}
{
  echo "# PARC benchmark, $(date -u +%Y-%m-%dT%H:%MZ)"
  echo
  echo "- machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB"
  echo "- OpenGL: $(xrun glxinfo -B 2>/dev/null | sed -n 's/^OpenGL renderer string: //p')"
  echo "- commit: $(git -C "$here" rev-parse --short HEAD), build: Release"
  echo "- settings: sample distance 0.25 voxel (spacing 1 in every volume here), 3 timed renders after a warm-up, perspective; times are means in seconds; total = the mapper's Render (projection + casting + display)"
  echo
  echo "## Depth-buffer PARC: isosurfaces (issue 5; paper Table 2: 5.6x)"
  scene "iron protein neghip, isosurface 60, supercell 2" "$data/neghip_64x64x64_uint8.raw" --blend iso --iso 60 --supercell 2,2,2
  scene "MRI head ch2, isosurface 60, supercell 4" "$head" --blend iso --iso 60 --elevation -80 --azimuth 30 --supercell 4,4,4
  echo
  echo "## Colour-buffer PARC: composite (issue 6; paper Table 1: 8.8x)"
  scene "CT tooth, ct-bone, supercell 4" "$data/tooth_103x94x161_uint8.raw" --tf ct-bone --elevation -70 --supercell 4,4,4
  scene "MRI head ch2, mri, supercell 4" "$head" --tf mri --elevation -80 --azimuth 30 --supercell 4,4,4
  echo
  echo "## Supercell size sweep: polygons against ray steps (600x600, depth PARC)"
  for args in "$data/tooth_103x94x161_uint8.raw --tf ct-bone --elevation -70" \
              "$data/neghip_64x64x64_uint8.raw --blend iso --iso 60"; do
    set -- $args
    [ -f "$1" ] || continue
    echo; echo "### $(basename "$1") ${*:2}"; echo
    render "$@" --size 600 --acceleration depth --sweep-supercells 1,1.5,2,3,4,6,8
  done
  echo
  echo "## Reclassification of a 256^3 volume (embryo) after a transfer-function change"
  if [ -f "$data/embryo_256x256x256_uint8.raw" ]; then
    echo
    render "$data/embryo_256x256x256_uint8.raw" --size 300 --tf ct-bone --compare-acceleration | tail -1
  fi
} | tee "$here/out/benchmark.md"
