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
