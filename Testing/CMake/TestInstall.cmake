# Installs the build tree into a scratch prefix and checks what a user gets: headers, the
# library, the CMake package, parc-render and a Python package that imports.
# Run as: cmake -DBUILD_DIR=... -DPREFIX=... -DPYTHON_DEST=... -P TestInstall.cmake
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
  RESULT_VARIABLE rc OUTPUT_QUIET)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif ()
foreach (f IN ITEMS include/parc/vtkPARCVolumeMapper.h include/parc/PARCRenderingModule.h
    lib/libPARCRendering.so lib/cmake/parc/parc-config.cmake lib/cmake/parc/PARC-targets.cmake
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
message(STATUS "install tree complete and importable")
