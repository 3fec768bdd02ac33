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

# Called at the end of each directory that adds tests (a test's properties can only be set from
# its own directory), for every test of the directory:
# - Sanitized binaries run 2-5 times slower, and a sanitizer check may share the machine: in a
#   TFETI_SANITIZE build every test's time limit is multiplied by TFETI_TEST_TIMEOUT_SCALE
#   (default 5 there, 1 otherwise).
# - Open MPI 4.1 creates its session directory (<tmpdir>/ompi.<host>.<uid>, removed again when
#   the last job using it ends) with a check and then a mkdir: two MPI starts at once (ctest -j,
#   a singleton or mpiexec) can both find it missing, and the second fails with "orte_init
#   failed ... File exists" (a CI run lost bad_pair_no_master_check_same_error to it; 1 start in
#   240 with six at once on this project's machines). Every test gets a directory of its own,
#   OMPI_MCA_orte_tmpdir_base = <build>/mpi-sessions/<n>, under one made at configure time, so
#   that no two tests create the same directory (0 failures in 360 such starts).
if(TFETI_SANITIZE)
  set(TFETI_TEST_TIMEOUT_SCALE 5 CACHE STRING "Factor applied to every test's TIMEOUT")
else()
  set(TFETI_TEST_TIMEOUT_SCALE 1 CACHE STRING "Factor applied to every test's TIMEOUT")
endif()
set(TFETI_MPI_SESSIONS ${CMAKE_BINARY_DIR}/mpi-sessions)
file(MAKE_DIRECTORY ${TFETI_MPI_SESSIONS})
set_property(GLOBAL PROPERTY TFETI_MPI_SESSION_COUNT 0)
function(tfeti_finish_test_directory)
  get_property(tests DIRECTORY PROPERTY TESTS)
  get_property(n GLOBAL PROPERTY TFETI_MPI_SESSION_COUNT)
  foreach(t IN LISTS tests)
    math(EXPR n "${n} + 1")
    set_property(TEST ${t} APPEND PROPERTY ENVIRONMENT
                 "OMPI_MCA_orte_tmpdir_base=${TFETI_MPI_SESSIONS}/${n}")
    if(NOT TFETI_TEST_TIMEOUT_SCALE EQUAL 1)
      get_test_property(${t} TIMEOUT limit)
      if(limit)
        math(EXPR limit "${limit} * ${TFETI_TEST_TIMEOUT_SCALE}")
        set_tests_properties(${t} PROPERTIES TIMEOUT ${limit})
      endif()
    endif()
  endforeach()
  set_property(GLOBAL PROPERTY TFETI_MPI_SESSION_COUNT ${n})
endfunction()
