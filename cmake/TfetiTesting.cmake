# Test helpers: every test has a label (unit, integration, scaling); MPI tests run through
# mpiexec with the given rank count. Root may run MPI only with the allow-run-as-root flags.
set(TFETI_MPIEXEC_FLAGS --oversubscribe)
execute_process(COMMAND id -u OUTPUT_VARIABLE _uid OUTPUT_STRIP_TRAILING_WHITESPACE)
if(_uid STREQUAL "0")
  list(APPEND TFETI_MPIEXEC_FLAGS --allow-run-as-root)
endif()

# tfeti_mpi_test(NAME n RANKS r LABELS l COMMAND exe args...)
function(tfeti_mpi_test)
  cmake_parse_arguments(T "" "NAME;RANKS;TIMEOUT" "LABELS;COMMAND" ${ARGN})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  add_test(NAME ${T_NAME}
           COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${T_RANKS} ${TFETI_MPIEXEC_FLAGS}
                   ${T_COMMAND})
  set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}" PROCESSORS ${T_RANKS}
                                            TIMEOUT ${T_TIMEOUT})
endfunction()

# Sanitized binaries run 2-5 times slower, and a sanitizer check may share the machine: in a
# TFETI_SANITIZE build every test's time limit is multiplied by TFETI_TEST_TIMEOUT_SCALE (default
# 5 there, 1 otherwise). Called at the end of each directory that adds tests, since a test's
# properties can only be set from its own directory.
if(TFETI_SANITIZE)
  set(TFETI_TEST_TIMEOUT_SCALE 5 CACHE STRING "Factor applied to every test's TIMEOUT")
else()
  set(TFETI_TEST_TIMEOUT_SCALE 1 CACHE STRING "Factor applied to every test's TIMEOUT")
endif()
function(tfeti_scale_test_timeouts)
  if(TFETI_TEST_TIMEOUT_SCALE EQUAL 1)
    return()
  endif()
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(t IN LISTS tests)
    get_test_property(${t} TIMEOUT limit)
    if(limit)
      math(EXPR limit "${limit} * ${TFETI_TEST_TIMEOUT_SCALE}")
      set_tests_properties(${t} PROPERTIES TIMEOUT ${limit})
    endif()
  endforeach()
endfunction()
