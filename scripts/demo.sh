#!/usr/bin/env bash
# The main job: sets up and builds, then renders real volumes to PNG files in out/ and prints
# a table of times for vtkPARCVolumeMapper and vtkFixedPointVolumeRayCastMapper side by side.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
"$here/scripts/setup.sh"
out="$here/out"
mkdir -p "$out"
render() { "$here/scripts/xvfb.sh" "$here/build/bin/parc-render" "$@" --compare-fixed-point; }

head=/usr/share/mricron/templates/ch2.nii.gz
echo "== MRI head $head (181x217x181)"
for blend in composite mip iso; do
  tf=mri; [ "$blend" = mip ] && tf=mip
  render "$head" --blend "$blend" --tf "$tf" --iso 60 --elevation -80 --azimuth 30 \
    --size 300 --output "$out/ch2_$blend.png"
done

ct="$here/../shared/data/tooth_103x94x161_uint8.raw"
if [ -f "$ct" ]; then
  echo "== CT tooth $ct"
  render "$ct" --blend composite --tf ct-bone --elevation -70 --size 300 \
    --output "$out/tooth_composite.png"
else
  echo "== CT volume not found at $ct: skipped"
fi
echo "== images in $out"
