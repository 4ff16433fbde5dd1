# cmake -P script run by the "consumer" CTest (label "install"): installs the current build into a
# fresh prefix, then configures, builds and runs tests/consumer against that prefix only.
# Inputs: BUILD_DIR, CONSUMER_SOURCE, WORK_DIR, SAMPLE, ISO.
foreach(var BUILD_DIR CONSUMER_SOURCE WORK_DIR SAMPLE ISO)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_consumer.cmake: ${var} is not set")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()

step("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")
# Only the install prefix is searched for isodel: the build tree must not leak in.
step("${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE}" -B "${WORK_DIR}/build" -G Ninja
     -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON)
step("${CMAKE_COMMAND}" --build "${WORK_DIR}/build" -j 1)
step("${WORK_DIR}/build/consumer" "${SAMPLE}" "${ISO}")
file(REMOVE_RECURSE "${WORK_DIR}")
