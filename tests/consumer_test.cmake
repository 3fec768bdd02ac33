# Installs the build tree into a scratch prefix, then configures, builds and runs the consumer
# project against it with find_package. FLAGS (a ;-list, e.g. the sanitizer flags of a
# TFETI_SANITIZE build) are passed on: the consumer must compile and link like the packages.
set(prefix ${WORK}/prefix)
string(REPLACE ";" " " flags "${FLAGS}")
file(REMOVE_RECURSE ${WORK})
foreach(step
    "${CMAKE_COMMAND};--install;${BUILD};--prefix;${prefix}"
    "${CMAKE_COMMAND};-S;${SOURCE};-B;${WORK}/build;-DCMAKE_PREFIX_PATH=${prefix};-DCMAKE_BUILD_TYPE=Release;-DCMAKE_CXX_FLAGS=${flags};-DCMAKE_EXE_LINKER_FLAGS=${flags}"
    "${CMAKE_COMMAND};--build;${WORK}/build"
    "${WORK}/build/consumer")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
message("${out}")
