#!/usr/bin/env bash
# The ParaView plugin (Plugin/): installs ParaView 5.11 beside the VTK 9.1 stack, builds
# the plugin against ParaView's own VTK and runs its pvbatch test.
#
# Debian's python3-paraview (pvpython, ParaView's Python modules) conflicts with
# python3-vtk9, so it is not installed: its files are unpacked into a private prefix
# (build-paraview/prefix) that also holds a copy of ParaView's CMake files and links to the
# rest of ParaView, so that find_package(ParaView) finds every file it names there, and
# pvbatch runs with that prefix's Python modules first on PYTHONPATH. The VTK 9.1 stack
# (libvtk9-dev, python3-vtk9) stays installed and working.
#
# Usage: scripts/paraview.sh [build-dir]   (default: build-paraview)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$here/build-paraview"}
prefix="$build/prefix"
lib=/usr/lib/x86_64-linux-gnu

packages=(paraview paraview-dev qtbase5-dev libqt5svg5-dev qttools5-dev libqt5opengl5-dev
  qtxmlpatterns5-dev-tools openmpi-bin python3-mpi4py)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
sudo_cmd=""
[ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

echo "== private ParaView prefix in $prefix"
mkdir -p "$build/deb"
if [ ! -d "$build/deb/root" ]; then
  (cd "$build/deb" && apt-get download -qq python3-paraview 2>/dev/null)
  dpkg -x "$build"/deb/python3-paraview_*.deb "$build/deb/root"
fi
rm -rf "$prefix"
mkdir -p "$prefix/bin" "$prefix/lib/python3" "$prefix/lib/x86_64-linux-gnu/cmake"
ln -s /usr/include "$prefix/include"
ln -s /usr/share "$prefix/share"
ln -s "$build/deb/root/usr/lib/python3/dist-packages" "$prefix/lib/python3/dist-packages"
ln -s "$build/deb/root/usr/lib/x86_64-linux-gnu/vtk" "$prefix/lib/x86_64-linux-gnu/vtk"
# A copy, not a link: CMake's export files see through links to the original prefix.
cp -r "$lib/cmake/paraview-5.11" "$prefix/lib/x86_64-linux-gnu/cmake/"
named() { # the files under $1 of the prefix that ParaView's CMake files name
  grep -rhoE "\\\$\\{_IMPORT_PREFIX\\}/$1/[^\" ;]+" "$prefix/lib/x86_64-linux-gnu/cmake" |
    sed "s|\${_IMPORT_PREFIX}/$1/||" | cut -d/ -f1 | sort -u
}
for f in $(named lib/x86_64-linux-gnu); do
  [ -e "$lib/$f" ] && [ ! -e "$prefix/lib/x86_64-linux-gnu/$f" ] &&
    ln -s "$lib/$f" "$prefix/lib/x86_64-linux-gnu/$f"
done
for f in $(named bin); do
  for dir in /usr/bin "$build/deb/root/usr/bin"; do
    if [ -e "$dir/$f" ]; then ln -s "$dir/$f" "$prefix/bin/$f"; break; fi
  done
done

echo "== building the plugin in $build/plugin"
cmake -S "$here/Plugin" -B "$build/plugin" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DParaView_DIR="$prefix/lib/x86_64-linux-gnu/cmake/paraview-5.11" \
  -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build "$build/plugin" -j "$(nproc)"

echo "== pvbatch test"
PYTHONPATH="$prefix/lib/python3/dist-packages" xvfb-run -a -s "-screen 0 1280x1024x24" \
  pvbatch "$here/Plugin/Testing/TestPARCPlugin.py" \
  "$build/plugin/lib/paraview-5.11/plugins/PARC/PARC.so" "$here/../shared/data" \
  "$build/test-output"
