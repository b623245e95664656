#!/usr/bin/env bash
# The ParaView plugin (Plugin/): installs ParaView 5.11 beside the VTK 9.1 stack, builds
# the plugin against ParaView's own VTK and runs its tests (pvbatch, pvpython with pvserver,
# the GUI).
#
# Debian's python3-paraview (pvpython, ParaView's Python modules) conflicts with
# python3-vtk9, so it is not installed: its files are unpacked into a private prefix
# (build-paraview/prefix) that also holds a copy of ParaView's CMake files and links to the
# rest of ParaView, so that find_package(ParaView) finds every file it names there, and
# pvbatch runs with that prefix's Python modules first on PYTHONPATH. The VTK 9.1 stack
# (libvtk9-dev, python3-vtk9) stays installed and working.
#
# Usage: scripts/paraview.sh [--benchmark] [build-dir]   (default: build-paraview)
#   Runs the test in pvbatch on 1 rank, on 2 ranks (mpiexec) against the 1-rank images, and
#   in pvpython connected to a pvserver on 2 ranks, then loads the plugin in the GUI.
#   --benchmark: then times PARC beside ParaView's own volume mapper on 1 and 2 ranks
#   (out/paraview-benchmark.md).
#   --benchmark-large: then renders the MRI head resized to 1.5 GB (uint8) with "PARC
#   Volume" on 1 and 2 ranks: read, first and warm frame times and each rank's peak
#   memory, and the 2-rank image against the 1-rank one (out/paraview-large.md).
# Exits 77, saying why, when ParaView cannot be installed beside the VTK stack (no package,
# or installing it would remove a package); any failure after a working install exits 1.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
benchmark=0
case "${1:-}" in
  --benchmark) benchmark=1; shift ;;
  --benchmark-large) benchmark=2; shift ;;
esac
build=${1:-"$here/build-paraview"}
prefix="$build/prefix"
lib=/usr/lib/x86_64-linux-gnu
skip() { echo "SKIPPED: the ParaView plugin: $*" >&2; exit 77; }

packages=(paraview paraview-dev qtbase5-dev libqt5svg5-dev qttools5-dev libqt5opengl5-dev
  qtxmlpatterns5-dev-tools openmpi-bin python3-mpi4py)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
sudo_cmd=""
[ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
install=(apt-get install -y -qq --no-install-recommends)
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  $sudo_cmd apt-get update -qq || skip "apt-get update failed"
  # A dry run first: nothing of the VTK stack may go.
  plan=$(apt-get -s "${install[@]:1}" "${missing[@]}" 2>&1) ||
    skip "the packages cannot be installed: $(echo "$plan" | tail -1)"
  if echo "$plan" | grep -q '^Remv '; then
    skip "installing would remove: $(echo "$plan" | awk '/^Remv /{print $2}' | xargs)"
  fi
  DEBIAN_FRONTEND=noninteractive $sudo_cmd "${install[@]}" "${missing[@]}" >/dev/null ||
    skip "apt-get install failed"
fi

echo "== private ParaView prefix in $prefix"
mkdir -p "$build/deb"
if [ ! -d "$build/deb/root" ]; then
  (cd "$build/deb" && apt-get download -qq python3-paraview 2>/dev/null) ||
    skip "apt-get download python3-paraview failed"
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
# pvpython is a copy: it then loads ParaView's libraries through the prefix (its RUNPATH is
# $ORIGIN/../lib/...), and its Python finds the prefix's vtkmodules before VTK 9.1's.
rm -f "$prefix/bin/pvpython"
cp -L "$build/deb/root/usr/bin/pvpython" "$prefix/bin/pvpython"

echo "== building the plugin in $build/Plugin"
# The main project with ParaView_DIR builds the plugin as an external project; only that
# target is built here (the main build's own tests are scripts/test.sh's).
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPARC_BUILD_TESTING=OFF \
  -DPARC_WRAP_PYTHON=OFF -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DParaView_DIR="$prefix/lib/x86_64-linux-gnu/cmake/paraview-5.11" >/dev/null
cmake --build "$build" --target parc_paraview_plugin -j "$(nproc)"

plugin="$build/Plugin/lib/paraview-5.11/plugins/PARC/PARC.so"
output="$build/test-output"
rm -rf "$output"
pythonpath="$prefix/lib/python3/dist-packages"
xrun() { # command...: under Xvfb, with ParaView's Python modules first on PYTHONPATH
  PYTHONPATH="$pythonpath" "$here/scripts/xvfb.sh" "$@"
}
mpi=(mpiexec --allow-run-as-root --oversubscribe -np) # then: ranks command...
pv() { # ranks script arguments...: pvbatch under Xvfb, on that many MPI ranks
  local ranks=$1
  shift
  xrun "${mpi[@]}" "$ranks" pvbatch "$@"
}
test="$here/Plugin/Testing/TestPARCPlugin.py"
checked() { # name command...: runs the test command, failing on its checks and on any
  # warning or error ParaView logs (a GL state the mapper left behind VTK's state cache shows
  # there).
  local log="$output/$1.log" status=0
  shift
  mkdir -p "$output"
  "$@" >"$log" 2>&1 || status=$?
  cat "$log"
  if [ "$status" != 0 ]; then
    echo "FAILED: $(basename "$log" .log) exited with status $status" >&2
    exit 1
  fi
  if grep -qE ' (WARN|ERR)\| |X Error' "$log"; then
    echo "FAILED: ParaView logged warnings or errors (above)" >&2
    exit 1
  fi
}
client_server() { # pvpython connected to 2 pvserver ranks
  local port=$((20000 + RANDOM % 20000)) server_log="$output/pvserver.log" server
  xrun "${mpi[@]}" 2 pvserver --server-port="$port" >"$server_log" 2>&1 &
  server=$!
  for _ in $(seq 60); do
    grep -q "Accepting connection" "$server_log" && break
    sleep 1
  done
  local status=0
  # Not xrun: pvpython finds the prefix's modules itself, and crashes with them on PYTHONPATH.
  "$here/scripts/xvfb.sh" "$prefix/bin/pvpython" "$test" "$plugin" \
    "$here/../shared/data" "$output/client-server" --one-rank "$output" \
    --server "localhost:$port" || status=$?
  if [ "$status" != 0 ]; then # the server may still wait for a client
    pkill -f "pvserver --server-port=$port" || true
  fi
  wait "$server" || true # the server ends with the connection
  cat "$server_log"
  return "$status"
}
echo "== pvbatch test, 1 rank"
checked pvbatch-1 pv 1 "$test" "$plugin" "$here/../shared/data" "$output"
echo "== pvbatch test, 2 ranks"
checked pvbatch-2 pv 2 "$test" "$plugin" "$here/../shared/data" "$output" --one-rank "$output"
for ranks in 1 2; do
  echo "== the stock Volume through the override, $ranks rank(s)"
  PARC_OVERRIDE_GPU_MAPPER=1 checked "override-$ranks" pv "$ranks" \
    "$here/Plugin/Testing/TestPARCPluginOverride.py" "$plugin" "$here/../shared/data" "$output"
done
echo "== pvpython test, connected to pvserver on 2 ranks"
checked pvserver-2 client_server
gui() { # the GUI runs a script and exits; the script writes its result to a file
  local result="$output/gui-result.txt"
  rm -f "$result"
  PARC_PLUGIN="$plugin" PARC_DATA_DIR="$here/../shared/data" PARC_RESULT="$result" \
    pythonpath="$pythonpath:$here/Plugin/Testing" \
    xrun paraview --script="$here/Plugin/Testing/TestPARCPluginGUI.py" --exit
  [ -e "$result" ] || { echo "FAILED: the GUI did not run the script" >&2; return 1; }
  cat "$result"
  echo
  [ "$(cat "$result")" = ok ]
}
echo "== the GUI (paraview --script)"
checked gui gui

if [ "$benchmark" = 2 ]; then
  large="$build/large"
  mkdir -p "$large/volumes"
  raw="$large/head-x6_1081x1297x1081_uint8.raw"
  if [ ! -f "$raw" ]; then
    echo "== resizing the MRI head by 6 (1.5 GB)"
    /usr/bin/python3 "$here/scripts/benchmark_volume_size.py" --make "$large" 6 uint8
    /usr/bin/python3 -c "import numpy, sys; numpy.load(sys.argv[1], mmap_mode='r').tofile(sys.argv[2])" \
      "$large/volumes/head-x6-uint8.npy" "$raw"
    rm -rf "$large/volumes"
  fi
  report="$here/out/paraview-large.md"
  mkdir -p "$here/out"
  {
    echo "### The MRI head resized by 6 ($(du -m "$raw" | cut -f1) MiB, uint8) in pvbatch"
    echo
    echo "| ranks | threads a rank | MiB | read (s) | first frame (s) | warm min (s) | warm median (s) | Auto | samples |"
    echo "|---|---|---|---|---|---|---|---|---|"
  } >"$report"
  for ranks in 1 2; do
    echo "== large volume, $ranks rank(s)"
    xrun "${mpi[@]}" "$ranks" /usr/bin/time -f "rank peak resident: %M KiB" pvbatch \
      "$here/Plugin/Testing/BenchmarkPARCPluginLarge.py" "$plugin" "$raw" 1081 1297 1081 \
      "$large/ranks-$ranks.png" 2>"$large/ranks-$ranks.err" | grep '^|' | tee -a "$report"
    grep 'rank peak resident' "$large/ranks-$ranks.err" | sed "s/^/$ranks rank(s): /" >>"$large/peaks.txt"
  done
  { echo; sed 's/^/- /' "$large/peaks.txt"; rm -f "$large/peaks.txt"; echo
    /usr/bin/python3 "$here/scripts/compare_png.py" "$large/ranks-1.png" "$large/ranks-2.png"
  } | tee -a "$report"
  echo "== written: $report"
fi

if [ "$benchmark" = 1 ]; then
  mkdir -p "$here/out"
  report="$here/out/paraview-benchmark.md"
  : >"$report"
  for ranks in 1 2; do
    echo "== benchmark, $ranks rank(s)"
    pv "$ranks" "$here/Plugin/Testing/BenchmarkPARCPlugin.py" "$plugin" "$here/../shared/data" |
      tee -a "$report"
  done
  echo "== written: $report"
fi
