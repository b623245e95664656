#!/usr/bin/env bash
# Benchmarks of PARC against unaccelerated casting, every mode side by side in one run per
# scene (issues 5 and 6): samples, cells, polygons, projection, casting and total time,
# speedup, and whether the float image is bit-identical; against
# vtkFixedPointVolumeRayCastMapper (interleaved, minimum and median), the casting cost per
# sample and the memory per structure (issue 11). Records the machine and settings.
# Output: a markdown report on stdout and in out/benchmark.md. Scenes from ../shared/data
# are skipped when absent.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh" >/dev/null
data="$here/../shared/data"
head=/usr/share/mricron/templates/ch2.nii.gz
tf="$here/Data/TransferFunctions"
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
# One parc-render measurement per scene at 400x400, sample distance 0.5: the option (words),
# the first and last line of its table to keep, then the scenes (a file and its options,
# one word list each; absent files are skipped).
at400() {
  local option=$1 first=$2 last=$3 args
  shift 3
  for args in "$@"; do
    set -- $args
    [ -f "$1" ] || continue
    echo; echo "### $(basename "$1") $(echo "${*:2}" | sed "s|$here/||g"), 400x400"; echo
    xrun "$here/build/bin/parc-render" "$@" --size 400 --sample-distance 0.5 \
      --output "$here/out/benchmark.png" $option | sed -n "/^$first/,/^$last/p"
  done
}
{
  echo "# PARC benchmark, $(date -u +%Y-%m-%dT%H:%MZ)"
  echo
  echo "- machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB"
  echo "- OpenGL: $(xrun glxinfo -B 2>/dev/null | sed -n 's/^OpenGL renderer string: //p')"
  echo "- commit: $(git -C "$here" rev-parse --short HEAD), build: Release"
  echo "- settings: sample distance 0.25 voxel (spacing 1 in every volume here), 3 timed renders after the warm-up renders (which include the frames on which Auto tries each pass), perspective; supercell 2x2x2 (the default); times are means in seconds; total = the mapper's Render (projection + casting + display)"
  echo
  echo "## Depth-buffer PARC: isosurfaces (issue 5; paper Table 2: 5.6x at 300^2, 6.3x at 600^2)"
  echo
  echo "The paper's isosurface is the positive iron protein; iso value 120 leaves 5.36% of its 1.03-cell supercells possibly contributing, the paper's Table 4 gives 5.35%."
  scene "iron protein, positive (poship), isosurface 120, supercell 2" "$data/poship_66x66x66_uint8.raw" --blend iso --iso 120
  scene "iron protein, negative (neghip), isosurface 60, supercell 2" "$data/neghip_64x64x64_uint8.raw" --blend iso --iso 60
  echo
  echo "## Several volumes: the paper's Table 2 scene (issue 13; paper: 5.7x at 300^2, 6.3x at 600^2; goal 8x at 600^2)"
  echo
  echo "One image of the iron protein through vtkPARCMultiVolume: poship as an isosurface (iso value 120, shaded) inside neghip as a translucent cloud ($tf/iron-protein-cloud.txt), centres aligned. Samples and cells are summed over both volumes (the paper's cells considered); Auto picks a mode per volume and the table names port 0's."
  scene "iron protein, poship isosurface 120 in a neghip cloud" "$data/poship_66x66x66_uint8.raw" --blend iso --iso 120 \
    --second "$data/neghip_64x64x64_uint8.raw" --second-tf "$tf/iron-protein-cloud.txt"
  scene "MRI head ch2, isosurface 60, supercell 2" "$head" --blend iso --iso 60 --elevation -80 --azimuth 30
  echo
  echo "## Shadows: the paper's Table 3 (issue 14; paper: 3.5x primary, about 2x for the shadow rays, 2.5x total; goal: 1.5x each)"
  echo
  echo "The paper's Figure 13 scene: the embryo (3.5% of its 64^3 supercells of 4^3 cells possibly contributing; the paper's neuron: 3.22% of 64^3) as an isosurface (80) over the generated 57x12x57 floor slab (parc-render --floor), two point lights casting shadows; depth PARC, colour PARC and Auto on primary and shadow rays against none, each its own mapper, frames interleaved (medians of 7). Cells are summed over both volumes. Total with shadows counts the light passes (256^2 buffers) as if the lights moved every frame; they are otherwise cached."
  for size in 300 600; do
    if [ ! -f "$data/embryo_256x256x256_uint8.raw" ]; then echo "(embryo not found, skipped)"; break; fi
    echo; echo "### embryo over the floor, two lights, ${size}x${size}"; echo
    xrun "$here/build/bin/parc-render" "$data/embryo_256x256x256_uint8.raw" --blend iso --iso 80 \
      --floor --supercell 4,4,4 --light -250,500,350 --light 550,450,250 --elevation 55 --azimuth 20 \
      --zoom 1.3 --size "$size" --sample-distance 0.25 --output "$here/out/benchmark.png" \
      --shadow-table 7 | sed -n '/^| PARC/,/^7 interleaved/p'
  done
  echo
  echo "## Colour-buffer PARC: composite (issue 6; paper Table 1: 8.8x)"
  echo
  echo "No CT foot is available; the CT tooth stands in for it. Both transfer functions render a translucent surface and something opaque inside, like the paper's skin and bone (files in Data/TransferFunctions)."
  scene "CT tooth, surface and enamel, supercell 2" "$data/tooth_103x94x161_uint8.raw" --tf "$tf/tooth-surface-enamel.txt" --elevation -70
  scene "MRI head ch2, scalp, supercell 2" "$head" --tf "$tf/mri-scalp.txt" --elevation -80 --azimuth 30
  echo
  echo "## Supercell size sweep: polygons against ray steps (600x600, Auto)"
  for args in "$data/poship_66x66x66_uint8.raw --blend iso --iso 120" \
              "$data/tooth_103x94x161_uint8.raw --tf $tf/tooth-surface-enamel.txt --elevation -70" \
              "$head --tf $tf/mri-scalp.txt --elevation -80 --azimuth 30"; do
    set -- $args
    [ -f "$1" ] || continue
    echo; echo "### $(basename "$1") $(echo "${*:2}" | sed "s|$here/||g")"; echo
    render "$@" --size 600 --acceleration auto --sweep-supercells 1,1.5,2,3,4
  done
  echo
  echo "## Against vtkFixedPointVolumeRayCastMapper (issue 11)"
  echo
  echo "Sample distance 0.5 voxel for both mappers, $(nproc) threads, wall time per frame of interleaved rounds (none, Auto, FixedPoint, repeated) after warm-up; the MRI head is dense and shaded or unshaded, the iron protein and the embryo are sparse. Shaded scenes show this mapper with each shading model: exact (the default) and quantized normals (SetShadingModelToQuantizedNormals, FixedPoint's model)."
  for args in "$head --tf mri --shade --elevation -80 --azimuth 30" \
              "$head --tf mri --elevation -80 --azimuth 30" \
              "$data/ironProt_68x68x68_uint8.raw --tf $tf/iron-protein-cloud.txt" \
              "$data/embryo_256x256x256_uint8.raw --tf ct-bone"; do
    set -- $args
    [ -f "$1" ] || { echo; echo "($1 not found, skipped)"; continue; }
    for size in 400 800; do
      echo; echo "### $(basename "$1") $(echo "${*:2}" | sed "s|$here/||g"), ${size}x${size}"; echo
      xrun "$here/build/bin/parc-render" "$@" --size "$size" --sample-distance 0.5 \
        --output "$here/out/benchmark.png" --versus-fixed-point 5 | sed -n '/^| mapper/,/^Auto used/p'
    done
  done
  echo
  echo "## Interaction under a render-time budget (issue 15)"
  echo
  echo "A 30-frame rotation (3 degrees a frame) at a desired update rate of 10 frames per second (a budget of 0.1 s), each mapper with AutoAdjustSampleDistances on, frames interleaved, then a still frame (full quality)."
  for size in 400 800; do
    [ -f "$head" ] || { echo; echo "($head not found, skipped)"; break; }
    echo; echo "### MRI head, shaded, ${size}x${size}"; echo
    xrun "$here/build/bin/parc-render" "$head" --tf mri --shade --elevation -80 --azimuth 30 \
      --size "$size" --sample-distance 0.5 --output "$here/out/benchmark.png" --budget 10 \
      | sed -n '/^| mapper/,/^PARC.s image sample distance/p'
  done
  echo
  echo "## Casting cost per sample (issue 11; goals: 10 ns per sample, 30 ns per contributing shaded sample)"
  echo
  echo "MRI head, 400x400, sample distance 0.5 voxel, acceleration none; the unshaded cast per sample, and the shaded minus the unshaded cast per contributing sample for each shading model, both per thread."
  for threads in 1 "$(nproc)"; do
    echo; echo "### $threads thread(s)"; echo
    xrun "$here/build/bin/parc-render" "$head" --tf mri --elevation -80 --azimuth 30 --size 400 \
      --sample-distance 0.5 --threads "$threads" --output "$here/out/benchmark.png" --sample-cost 5 \
      | sed -n '/^| casting/,/^minimum/p'
  done
  echo
  echo "## Accuracy against time (issue 11)"
  echo
  echo "MRI head, shaded, 400x400: RMSE in grey levels of the window image against this mapper's exact cast at 1/16 voxel (the reference), and against each mapper's own cast at 1/16 voxel (its sampling error alone; the rest is its model: quantized normals, FixedPoint's fixed-point arithmetic and tables), median of 3 interleaved frames per distance, $(nproc) threads."
  echo
  xrun "$here/build/bin/parc-render" "$head" --tf mri --shade --elevation -80 --azimuth 30 --size 400 \
    --output "$here/out/benchmark.png" --accuracy-curve 3 | sed -n '/^| sample distance/,/^3 interleaved/p'
  echo
  echo "## Transfer-function edits (issue 11; goal: the frame after an edit at most 1.2x a warm one)"
  at400 "--edit-cost 8" "| frame" "edit frame" \
    "$head --tf mri --shade --elevation -80 --azimuth 30" \
    "$head --tf mri --elevation -80 --azimuth 30" \
    "$data/ironProt_68x68x68_uint8.raw --tf $tf/iron-protein-cloud.txt"
  echo
  echo "## Auto's trial frames (issue 11; goal: no trial frame slower than 1.2x the settled one)"
  echo
  echo "A fresh mapper in Auto, 3 rounds per scene, 400x400: every frame until Auto has settled, then 3 settled frames. Depth comes first; a mode is tried only when the measured frames predict it faster. The first frame also builds the classification and the models and is not counted."
  at400 "--auto-trials 3" "| round" "slowest" \
    "$head --tf mri --shade --elevation -80 --azimuth 30" \
    "$head --blend iso --iso 60 --elevation -80 --azimuth 30" \
    "$head --tf $tf/mri-scalp.txt --elevation -80 --azimuth 30" \
    "$data/bolt_70x123x66_uint8.raw --blend mip" \
    "$data/embryo_256x256x256_uint8.raw --blend iso --iso 80"
  echo
  echo "## Threads (issue 11; goal: 2 threads at least 1.8x in every mode)"
  echo
  echo "One caster thread against $(nproc), interleaved, median of 7 frames each; llvmpipe runs the GL passes on every core in both."
  if [ -f "$data/ironProt_68x68x68_uint8.raw" ]; then
    echo
    xrun "$here/build/bin/parc-render" "$data/ironProt_68x68x68_uint8.raw" \
      --tf "$tf/iron-protein-cloud.txt" --size 400 --sample-distance 0.5 \
      --output "$here/out/benchmark.png" --thread-scaling 7 | grep '^|'
  fi
  echo
  echo "## Memory held by the mapper, per structure (MRI head, shaded, 400x400, after Auto's trials)"
  echo
  xrun "$here/build/bin/parc-render" "$head" --tf mri --shade --elevation -80 --azimuth 30 --size 400 \
    --sample-distance 0.5 --output "$here/out/benchmark.png" --memory | grep -E '^(Memory|Input)' | sed 's/^/    /'
  echo
  echo "## Reclassification of a 256^3 volume (embryo) after a transfer-function change"
  if [ -f "$data/embryo_256x256x256_uint8.raw" ]; then
    echo
    render "$data/embryo_256x256x256_uint8.raw" --size 300 --tf ct-bone --compare-acceleration | tail -1
  fi
} | tee "$here/out/benchmark.md"
