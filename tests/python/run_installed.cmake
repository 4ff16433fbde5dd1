# cmake -P script run by the "python/installed" CTest: installs the build into a fresh prefix and
# imports isodel from there alone (the package beside libisodel, found through the extension's
# RUNPATH), then meshes the sample. Inputs: BUILD_DIR, WORK_DIR, PYTHON, PYTHON_DIR (relative to
# the prefix), SAMPLE, ISO.
foreach(var BUILD_DIR WORK_DIR PYTHON PYTHON_DIR SAMPLE ISO)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_installed.cmake: ${var} is not set")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}"
                OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed (${rc})")
endif()
foreach(f __init__.py __init__.pyi py.typed)
  if(NOT EXISTS "${prefix}/${PYTHON_DIR}/isodel/${f}")
    message(FATAL_ERROR "not installed: ${PYTHON_DIR}/isodel/${f}")
  endif()
endforeach()
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${prefix}/${PYTHON_DIR}" "${PYTHON}" -c
    "import isodel, sys; assert isodel.__file__.startswith(sys.argv[1]), isodel.__file__; m = isodel.mesh(sys.argv[2], float(sys.argv[3])); assert len(m.triangles) > 0; print(m)"
    "${prefix}" "${SAMPLE}" "${ISO}"
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the installed isodel package failed (${rc})")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
