# Installs the build tree into a scratch prefix and checks what a user gets: headers, the
# library, the CMake package with its version, parc-render starting without
# LD_LIBRARY_PATH, a Python package that imports and lies where Debian's python3 looks
# under /usr/local, and a C++-only downstream project (Testing/Downstream) that builds
# against the install tree and renders (needs a display).
# Run as: cmake -DBUILD_DIR=... -DPREFIX=... -DPYTHON_DEST=... -DDOWNSTREAM=... -P TestInstall.cmake
cmake_minimum_required(VERSION 3.16)
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
  RESULT_VARIABLE rc OUTPUT_QUIET)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif ()
foreach (f IN ITEMS include/parc/vtkPARCVolumeMapper.h include/parc/PARCRenderingModule.h
    lib/libPARCRendering.so lib/cmake/parc/parc-config.cmake
    lib/cmake/parc/parc-config-version.cmake
    lib/cmake/parc/PARC-targets.cmake
    bin/parc-render "${PYTHON_DEST}/parc/__init__.py" "${PYTHON_DEST}/parc/PARCRendering.so")
  if (NOT EXISTS "${PREFIX}/${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif ()
endforeach ()
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${PREFIX}/${PYTHON_DEST}"
    /usr/bin/python3 -c "from parc import vtkPARCVolumeMapper; print(vtkPARCVolumeMapper().GetClassName())"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if (NOT rc EQUAL 0 OR NOT out MATCHES "vtkPARCVolumeMapper")
  message(FATAL_ERROR "the installed Python package does not import: ${rc} ${out}")
endif ()

# find_package(parc 0.1) accepts this version; 0.2 and 1.0 do not.
foreach (request IN ITEMS "0.1:TRUE" "0.1.0:TRUE" "0.2:FALSE" "1.0:FALSE")
  string(REPLACE ":" ";" request "${request}")
  list(GET request 0 PACKAGE_FIND_VERSION)
  list(GET request 1 expected)
  string(REPLACE "." ";" parts "${PACKAGE_FIND_VERSION}")
  list(GET parts 0 PACKAGE_FIND_VERSION_MAJOR)
  list(GET parts 1 PACKAGE_FIND_VERSION_MINOR)
  set(PACKAGE_VERSION_COMPATIBLE)
  include("${PREFIX}/lib/cmake/parc/parc-config-version.cmake")
  if (NOT "${PACKAGE_VERSION_COMPATIBLE}" STREQUAL "${expected}")
    message(FATAL_ERROR "version ${PACKAGE_FIND_VERSION} requested: compatible is "
      "'${PACKAGE_VERSION_COMPATIBLE}', expected ${expected}")
  endif ()
endforeach ()

execute_process(COMMAND "${CMAKE_COMMAND}" -E env --unset=LD_LIBRARY_PATH
    "${PREFIX}/bin/parc-render" --help
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed parc-render does not start: ${rc} ${err}")
endif ()

execute_process(COMMAND /usr/bin/python3 -c "import sys; print(';'.join(sys.path))"
  OUTPUT_VARIABLE python_path OUTPUT_STRIP_TRAILING_WHITESPACE)
if (NOT "/usr/local/${PYTHON_DEST}" IN_LIST python_path)
  message(FATAL_ERROR "/usr/bin/python3 does not search /usr/local/${PYTHON_DEST}")
endif ()

set(downstream_build "${PREFIX}/../downstream-build")
file(REMOVE_RECURSE "${downstream_build}")
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${DOWNSTREAM}" -B "${downstream_build}"
    "-DCMAKE_PREFIX_PATH=${PREFIX}"
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "the downstream project does not configure: ${err}")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${downstream_build}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "the downstream project does not build: ${out} ${err}")
endif ()
execute_process(COMMAND "${downstream_build}/parcDownstream"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "the downstream program failed: ${rc} ${out} ${err}")
endif ()
message(STATUS "install tree complete: package, parc-render, Python and a downstream build")
