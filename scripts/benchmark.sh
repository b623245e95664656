#!/usr/bin/env bash
# The benchmark a user reads: what accuracy costs in time beside VTK's own mappers, the
# paper's tables on real data, how the cost grows with the work, numerical stability of hard
# cases, and the supercell sweep. Not a timed test: every ratio is measured side by side in
# one run, frames interleaved across mappers.
#
# Usage: scripts/benchmark.sh [--quick]
#   Writes out/benchmark/index.md (and shows it as it goes), its PNG plots and CSV data.
#   --quick: smaller images, fewer rounds and scenes (about 10 minutes); the full run takes
#   about 75 (60 of them the large volumes of section 3). Data sets from ../shared/data are
#   skipped, and said so, when absent.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
quick=0
case "${1:-}" in
  --quick) quick=1 ;;
  "") ;;
  *) echo "usage: scripts/benchmark.sh [--quick]" >&2; exit 2 ;;
esac
"$here/scripts/setup.sh" >/dev/null
data="$here/../shared/data"
head=/usr/share/mricron/templates/ch2.nii.gz
tf="$here/Data/TransferFunctions"
out="$here/out/benchmark"
mkdir -p "$out"
rm -f "$out"/*.png "$out"/*.csv
render_bin="$here/build/bin/parc-render"
scratch="$out/last-render.png"
export PYTHONPATH="$here/build/lib/python3.11/dist-packages${PYTHONPATH:+:$PYTHONPATH}"

if [ "$quick" = 1 ]; then
  size=200 rounds=1 finest=0.25 reference=0.0625 tables="300" sweep_size=300 repeat=1
else
  size=400 rounds=3 finest=0.0625 reference=0.015625 tables="300 600" sweep_size=600 repeat=3
fi

xrun() { "$here/scripts/xvfb.sh" "$@"; }
parc() { xrun "$render_bin" "$@" --output "$scratch"; }
plot() { xrun /usr/bin/python3 "$here/scripts/benchmark_report.py" "$@"; }
# A scene's title: the file's name and its options, without this checkout's path.
title() { echo "$(basename "$1") $(echo "${*:2}" | sed "s|$here/||g")"; }
# Whether a data set is here; says so when it is not.
present() { [ -f "$1" ] && return 0; echo; echo "($1 not found: skipped)"; return 1; }
# One table per scene at sample distance 0.5: for each scene (a file and its options, one
# word list; an absent file is said and skipped), parc-render at the image size with the
# option words, its output from the line starting with `first` to the one starting with
# `last`.
per_scene() { # size, option words, first, last, scenes...
  local pixels=$1 option=$2 first=$3 last=$4 args
  shift 4
  for args in "$@"; do
    set -- $args
    present "$1" || continue
    echo; echo "#### $(title "$@")"; echo
    parc "$@" --size "$pixels" --sample-distance 0.5 $option | sed -n "/^$first/,/^$last/p"
  done
}
# The median of a mapper's row in a --versus-fixed-point table on stdin.
median_of() { awk -F'|' -v row="$1" '$2 ~ row { gsub(/ /, "", $4); print $4; exit }'; }

header() {
  echo "# PARC for VTK: benchmark report ($([ "$quick" = 1 ] && echo quick || echo full) run)"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%MZ); commit $(git -C "$here" rev-parse --short HEAD), Release build"
  echo "- machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB; this mapper and FixedPoint use $(nproc) threads unless a table says otherwise"
  local gl
  gl=$(xrun glxinfo -B 2>/dev/null)
  echo "- VTK $(dpkg-query -W -f='${Version}' libvtk9-dev); OpenGL: $(echo "$gl" | sed -n 's/^OpenGL renderer string: //p'), $(echo "$gl" | sed -n 's/^OpenGL version string: //p'). There is no GPU here: vtkGPUVolumeRayCastMapper runs on Mesa's llvmpipe, on the same CPU cores."
  echo "- data: MRI head \`$head\` (mricron-data, 181x217x181, 8-bit, dense); from \`../shared/data\`: $(for f in ironProt_68x68x68 poship_66x66x66 neghip_64x64x64 tooth_103x94x161 embryo_256x256x256; do [ -f "$data/${f}_uint8.raw" ] && printf '%s ' "$f" || printf '%s (absent) ' "$f"; done)"
  echo "- settings: images ${size}x${size} for the accuracy study (parallel projection there, perspective elsewhere), linear interpolation; offscreen windows without multisampling (--multisamples 0, as VTK's volume tests set it); sample distances in voxels of the smallest spacing; times are wall-clock seconds of warm frames (window->Render() until the GL work is done), interleaved across mappers (A B C A B C), median and spread (minimum-maximum) of $rounds rounds unless a table says otherwise"
  echo
}

accuracy_section() {
  echo "## 1. What accuracy costs in time"
  echo
  echo "Every mapper renders each scene, in a parallel view (VolPack has no other), at sample distances from 2 voxels down to $finest, at image sample distance 1 (solid) and 2 (dashed). VolPack, the shear-warp renderer the paper cites (Debian libvolpack1-dev, driven by Examples/Cxx/parcVolPack.cxx), takes one sample per slice: it is one point at sample distance 1, where its model allows the scene (8-bit composite; one thread). The error is the RMSE, in grey levels, of the 8-bit RGB window image against a reference: this mapper's exact cast at $reference voxel (its convergence is shown first). FixedPoint runs with automatic adjustment off at the same world sample distance; FixedPoint has no isosurface mode. The full tables give the maximum error, the float-image RMSE of this mapper, and each mapper's error against its own image at the reference distance: what is left beside that is its model (gradient estimation, quantized tables, fixed-point arithmetic), not its sampling."
  local scenes=("$head --tf mri --shade --elevation -80 --azimuth 30 --parallel"
    "$data/ironProt_68x68x68_uint8.raw --tf $tf/iron-protein-cloud.txt --parallel")
  [ "$quick" = 1 ] || scenes+=("$data/poship_66x66x66_uint8.raw --blend iso --iso 120 --parallel"
    "$data/embryo_256x256x256_uint8.raw --tf ct-bone --parallel")
  local names=("MRI head, dense, shaded" "iron protein, sparse cloud" "iron protein, isosurface 120"
    "embryo 256^3, CT bone")
  local i=0 args
  for args in "${scenes[@]}"; do
    set -- $args
    local name=${names[$i]}
    i=$((i + 1))
    present "$1" || continue
    parc "$@" --size "$size" --accuracy-curve "$rounds" --finest-distance "$finest" \
      --reference-distance "$reference" --csv "$out/accuracy.csv" --scene "$name" \
      > "$out/accuracy-$i.md"
  done
  [ -f "$out/accuracy.csv" ] || return 0
  echo
  plot accuracy "$out/accuracy.csv" "$out"
  echo "<details><summary>The full tables</summary>"
  i=0
  for args in "${scenes[@]}"; do
    i=$((i + 1))
    [ -f "$out/accuracy-$i.md" ] || continue
    echo; echo "#### ${names[$((i - 1))]}: $(title $args), ${size}x${size}"; echo
    sed -n '/^Reference/,/^[0-9]* interleaved/p' "$out/accuracy-$i.md"
    rm "$out/accuracy-$i.md"
  done
  echo; echo "</details>"; echo
}

# Every acceleration mode of one scene side by side, at each of the table sizes.
modes_table() { # title, file, options...
  local name=$1 file=$2 s
  shift 2
  present "$file" || return 0
  for s in $tables; do
    echo; echo "#### $name, ${s}x${s}"; echo
    parc "$file" --size "$s" "$@" --sample-distance 0.25 --repeat "$repeat" --compare-acceleration \
      | sed -n '/^| mode/,/^PC supercells/p'
  done
}

paper_section() {
  echo "## 2. The paper's tables on real data"
  echo
  echo "Sample distance 0.25 voxel, supercells of 2^3 cells unless named, perspective; every mode's float image is compared bit for bit with acceleration None (last column). Times are means of $repeat renders after the warm-up (which includes Auto's trial frames); total = the mapper's Render (projection + casting + display)."
  echo
  echo "### Table 1: composite (paper: colour PARC 8.8x at 600^2 on a CT foot: samples 189.7M against 13.3M, 674 s against 75.9 s)"
  echo
  echo "No CT foot is available: the CT tooth and the MRI head stand in, each with a translucent surface over something opaque, like the paper's skin and bone (Data/TransferFunctions)."
  modes_table "CT tooth, surface and enamel" "$data/tooth_103x94x161_uint8.raw" --tf "$tf/tooth-surface-enamel.txt" --elevation -70
  modes_table "MRI head, scalp" "$head" --tf "$tf/mri-scalp.txt" --elevation -80 --azimuth 30
  echo
  echo "### Table 2: two volumes in one image (paper: 5.7x at 300^2, 6.3x at 600^2; cells 10.4M against 1.3M at 600^2)"
  echo
  echo "The iron protein through vtkPARCMultiVolume: poship as a shaded isosurface (120) inside neghip as a translucent cloud ($(basename "$tf")/iron-protein-cloud.txt), centres aligned. Samples and cells are summed over both volumes; Auto picks a mode per volume and the table names port 0's."
  modes_table "poship isosurface in a neghip cloud" "$data/poship_66x66x66_uint8.raw" --blend iso --iso 120 \
    --second "$data/neghip_64x64x64_uint8.raw" --second-tf "$tf/iron-protein-cloud.txt"
  echo
  echo "### Table 3: shadows (paper: 3.5x on primary rays, about 2x on shadow rays, 2.5x in total)"
  echo
  echo "The paper's Figure 13 scene: the embryo as an isosurface (80, supercells of 4^3 cells) over the generated 57x12x57 floor slab, two point lights casting shadows; each mode its own mapper, frames interleaved (medians of 7). Cells are summed over both volumes. Total with shadows counts the light passes (256^2 buffers) as if the lights moved every frame; they are otherwise cached."
  local s
  for s in $tables; do
    present "$data/embryo_256x256x256_uint8.raw" || break
    echo; echo "#### embryo over the floor, two lights, ${s}x${s}"; echo
    parc "$data/embryo_256x256x256_uint8.raw" --blend iso --iso 80 --floor --supercell 4,4,4 \
      --light -250,500,350 --light 550,450,250 --elevation 55 --azimuth 20 --zoom 1.3 --size "$s" \
      --sample-distance 0.25 --shadow-table 7 | sed -n '/^| PARC/,/^7 interleaved/p'
  done
  echo
  echo "### Table 4: data statistics"
  echo
  echo "| volume | stands for | size in samples | size in units | supercell | possibly contributing supercells | paper |"
  echo "|---|---|---|---|---|---|---|"
  statistics_row "$data/poship_66x66x66_uint8.raw" "iron protein (positive), Figure 12" 1.03 "5.35% (1.03^3)" --blend iso --iso 120
  statistics_row "$data/neghip_64x64x64_uint8.raw" "iron protein (negative), Figure 12" 1 "6.2% (1^3)" --tf "$tf/iron-protein-cloud.txt"
  statistics_row "$data/tooth_103x94x161_uint8.raw" "CT foot, Figure 11" 2 "6.79% (3x5x5)" --tf "$tf/tooth-surface-enamel.txt"
  statistics_row "$head" "CT foot, Figure 11" 2 "6.79% (3x5x5)" --tf "$tf/mri-scalp.txt"
  statistics_row "$data/embryo_256x256x256_uint8.raw" "hippocampal cell, Figure 13" 4 "3.22% (6x4x3.125)" --blend iso --iso 80
  echo
}

statistics_row() { # file, stands for, supercell, the paper's figure, options...
  local file=$1 stands=$2 cell=$3 paper=$4 json
  shift 4
  [ -f "$file" ] || { echo "| $(basename "$file") (absent) | $stands | | | | | $paper |"; return 0; }
  json=$(parc "$file" "$@" --size 100 --sweep-supercells "$cell" --json)
  local pc dims spacing
  pc=$(echo "$json" | awk -F'|' '/^\| [0-9.]+ \|/ {print $3; exit}')
  dims=$(echo "$json" | sed -n 's/.*"dimensions": \[\(.*\)\].*/\1/p' | tr -d ' ' | tr , x)
  spacing=$(echo "$json" | sed -n 's/.*"spacing": \[\(.*\)\].*/\1/p' | tr -d ' ')
  local units
  units=$(awk -v d="$dims" -v s="$spacing" 'BEGIN { split(d, n, "x"); split(s, h, ",");
    printf "%gx%gx%g", (n[1]-1)*h[1], (n[2]-1)*h[2], (n[3]-1)*h[3] }')
  echo "| $(basename "$file") | $stands | $dims | $units | $cell^3 |$pc| $paper |"
}

growth_section() {
  echo "## 3. Cost as the work grows"
  echo
  echo "The MRI head, shaded, sample distance 0.5 voxel: this mapper with acceleration None and Auto (exact and quantized-normal shading) against FixedPoint, interleaved rounds (--versus-fixed-point), medians."
  present "$head" || return 0
  local sizes="300 600 1200" factors="0.5 1 2" s f table
  [ "$quick" = 1 ] && sizes="150 300" && factors="0.5 1"
  echo "series,x,y" > "$out/image-size.csv"
  echo; echo "### Image size"; echo
  echo "| image | PARC None (s) | PARC Auto (s) | PARC Auto, quantized normals (s) | FixedPoint (s) | FixedPoint / Auto |"
  echo "|---|---|---|---|---|---|"
  for s in $sizes; do
    table=$(parc "$head" --tf mri --shade --elevation -80 --azimuth 30 --size "$s" --sample-distance 0.5 --versus-fixed-point "$rounds")
    growth_row "${s}^2" "$((s * s))" "$table" "$out/image-size.csv"
  done
  plot lines "$out/image-size.csv" "$out/image-size.png" "MRI head, shaded: frame time against image size" "pixels" "median frame time (s)" --log-x --log-y
  echo; echo "![time against image size](image-size.png)"
  echo; echo "### Cost as the volume grows (the head resized up to 1.5-2 GB, uint8 and CT-like int16)"; echo
  echo "This mapper in Auto against vtkFixedPointVolumeRayCastMapper at half a voxel, perspective, unshaded and shaded: first frames of new mappers in a window whose GL context exists, warm frames interleaved (A B A B, median and minimum of $rounds rounds), the frame after a transfer-function edit, this mapper's chosen mode and supercell size, its casting cost, and the resident size each mapper adds in a process of its own against GetMemorySize."; echo
  xrun /usr/bin/python3 "$here/scripts/benchmark_volume_size.py" "$out" $([ "$quick" = 1 ] && echo --quick)
  echo; echo "### Threads (iron protein cloud, ${size}x${size}; one caster thread against $(nproc), medians of 7 interleaved frames: the whole frame, the mapper's casting and its GL passes, which llvmpipe runs on every core at either setting)"; echo
  present "$data/ironProt_68x68x68_uint8.raw" && parc "$data/ironProt_68x68x68_uint8.raw" --tf "$tf/iron-protein-cloud.txt" --size "$size" --sample-distance 0.5 --thread-scaling 7 | grep '^|'
  echo; echo "### The first frame after a transfer-function change against a warm frame (${size}x${size})"
  per_scene "$size" "--edit-cost $((rounds + 3))" "| frame" "edit frame" \
    "$head --tf mri --shade --elevation -80 --azimuth 30" \
    "$data/ironProt_68x68x68_uint8.raw --tf $tf/iron-protein-cloud.txt"
  echo; echo "### Memory: peak resident size of the process, and the bytes the mapper holds per structure (MRI head, shaded, ${size}x${size}, after Auto's trials)"; echo
  local peak
  for f in $factors; do
    peak=$( { xrun /usr/bin/time -f "PEAK %M" "$render_bin" "$head" --tf mri --shade --elevation -80 --azimuth 30 --size "$size" --resample "$f" --memory --output "$scratch" > "$out/memory.txt"; } 2>&1 | sed -n 's/^PEAK //p')
    echo "#### resampled by $f: peak resident size $((peak / 1024)) MiB"; echo
    grep -E '^(Memory|Input)' "$out/memory.txt" | sed 's/^/    /'
    echo
  done
  rm -f "$out/memory.txt"
}

growth_row() { # label, x, --versus-fixed-point table, csv
  local none auto quantized fixed
  none=$(echo "$3" | median_of "acceleration none, Exact")
  auto=$(echo "$3" | median_of "Auto, Exact")
  quantized=$(echo "$3" | median_of "Auto, QuantizedNormals")
  fixed=$(echo "$3" | median_of "vtkFixedPoint")
  echo "| $1 | $none | $auto | $quantized | $fixed | $(awk -v a="$auto" -v f="$fixed" 'BEGIN{printf "%.2fx", f/a}') |"
  printf 'PARC None,%s,%s\nPARC Auto,%s,%s\nPARC Auto quantized normals,%s,%s\nvtkFixedPointVolumeRayCastMapper,%s,%s\n' \
    "$2" "$none" "$2" "$auto" "$2" "$quantized" "$2" "$fixed" >> "$4"
}

stability_section() {
  echo "## 4. Numerical stability of hard cases"
  echo
  xrun /usr/bin/python3 "$here/scripts/benchmark_stability.py" $([ "$quick" = 1 ] && echo --quick)
}

sweep_section() {
  echo "## 5. Supercell sweep: polygons against ray steps (${sweep_size}x${sweep_size}, Auto)"
  echo
  echo "Each row is Auto at one supercell size (its choice in the last column); the optimum, the smallest total, is named below each table and marked with a large dot in the plot. The default is 4."
  local args i=0 table best
  echo "series,x,y" > "$out/sweep.csv"
  local scenes=("$data/tooth_103x94x161_uint8.raw --tf $tf/tooth-surface-enamel.txt --elevation -70")
  [ "$quick" = 1 ] || scenes+=("$data/poship_66x66x66_uint8.raw --blend iso --iso 120"
    "$head --tf $tf/mri-scalp.txt --elevation -80 --azimuth 30")
  for args in "${scenes[@]}"; do
    set -- $args
    present "$1" || continue
    echo; echo "### $(title "$@")"; echo
    table=$(parc "$@" --size "$sweep_size" --sample-distance 0.25 --repeat "$repeat" --sweep-supercells 1,2,3,4,6,8 | grep '^|')
    echo "$table"
    best=$(echo "$table" | awk -F'|' '$2 ~ /[0-9]/ { gsub(/ /, "", $2); gsub(/ /, "", $8); gsub(/ /, "", $9);
      if (min == "" || $8 < min) { min = $8; at = $2; mode = $9 } } END { print at, min, mode }')
    echo; echo "Optimum: supercell ${best%% *} ($(echo "$best" | cut -d' ' -f2) s total; Auto chose $(echo "$best" | cut -d' ' -f3) there)."
    echo "$table" | awk -F'|' -v name="$(basename "$1")" '$2 ~ /[0-9]/ { gsub(/ /, "", $2); gsub(/ /, "", $8); print name "," $2 "," $8 }' >> "$out/sweep.csv"
  done
  plot lines "$out/sweep.csv" "$out/sweep.png" "Total frame time against supercell size (Auto)" "supercell edge (cells)" "total (s)" --log-y --mark-minimum
  echo; echo "![supercell sweep](sweep.png)"
}

caster_section() {
  echo "## 6. The caster against FixedPoint, and Auto's choices"
  echo
  echo "Sample distance 0.5 voxel; wall time per frame of interleaved rounds."
  local args s
  for args in "$head --tf mri --shade --elevation -80 --azimuth 30" \
              "$head --tf mri --elevation -80 --azimuth 30" \
              "$data/ironProt_68x68x68_uint8.raw --tf $tf/iron-protein-cloud.txt" \
              "$data/embryo_256x256x256_uint8.raw --tf ct-bone"; do
    set -- $args
    present "$1" || continue
    for s in 400 800; do
      echo; echo "### $(title "$@"), ${s}x${s}"; echo
      parc "$@" --size "$s" --sample-distance 0.5 --versus-fixed-point 5 | sed -n '/^| mapper/,/^Auto used/p'
    done
  done
  echo; echo "### Casting cost per sample (MRI head, 400x400, acceleration None: the unshaded cast per sample, and the shaded minus the unshaded cast per contributing sample, per thread)"
  for threads in 1 "$(nproc)"; do
    echo; echo "#### $threads thread(s)"; echo
    parc "$head" --tf mri --elevation -80 --azimuth 30 --size 400 --sample-distance 0.5 \
      --threads "$threads" --sample-cost 5 | sed -n '/^| casting/,/^minimum/p'
  done
  echo; echo "### Interaction under a budget of 0.1 s (a 30-frame rotation, AutoAdjustSampleDistances on, then a still frame)"
  echo; parc "$head" --tf mri --shade --elevation -80 --azimuth 30 --size 400 --sample-distance 0.5 \
    --budget 10 | sed -n '/^| mapper/,/^PARC.s image sample distance/p'
  echo; echo "### Auto's trial frames (a fresh mapper, 3 rounds, 400x400; the first frame also builds the classification and models and is not counted)"
  per_scene 400 "--auto-trials 3" "| round" "slowest" \
    "$head --tf mri --shade --elevation -80 --azimuth 30" \
    "$head --blend iso --iso 60 --elevation -80 --azimuth 30" \
    "$data/embryo_256x256x256_uint8.raw --blend iso --iso 80"
}

# The sections in order, with what each took in a run on this machine (minutes, quick and
# full): the time left is estimated from them, scaled by how this run keeps to them.
sections=(accuracy_section paper_section growth_section stability_section sweep_section)
quick_minutes=(3 2 3 1 1)
full_minutes=(8 4 60 1 2 4)
[ "$quick" = 1 ] || sections+=(caster_section)
# Runs section i of the list, saying on stderr (not in the report) which section runs, how
# far along the run is and about how long is left.
run_section() {
  local i=$1 n=${#sections[@]} planned=0 done_planned=0 k elapsed left
  for ((k = 0; k < n; ++k)); do
    local m; m=$([ "$quick" = 1 ] && echo "${quick_minutes[$k]}" || echo "${full_minutes[$k]}")
    planned=$((planned + m))
    ((k < i)) && done_planned=$((done_planned + m))
  done
  elapsed=$((($(date +%s) - start) / 60))
  if ((done_planned > 0 && elapsed > 0)); then
    left=$(((planned - done_planned) * elapsed / done_planned))
  else
    left=$((planned - done_planned))
  fi
  echo "[benchmark] section $((i + 1))/$n: ${sections[$i]%_section} ($((100 * done_planned / planned))% done, ${elapsed} min so far, about ${left} min left)" >&2
  "${sections[$i]}"
}

start=$(date +%s)
{
  header
  for ((i = 0; i < ${#sections[@]}; ++i)); do
    run_section "$i"
  done
  echo
  echo "---"
  echo "The run took $(( ($(date +%s) - start) / 60 )) min $(( ($(date +%s) - start) % 60 )) s."
} | tee "$out/index.md"
rm -f "$scratch"
