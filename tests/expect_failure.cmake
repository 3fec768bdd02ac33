# Runs CMD (a ;-list), requires a non-zero exit code equal to EXIT_CODE (if given) and output
# matching REGEX: bad input must fail loudly, with a message naming what is wrong.
execute_process(COMMAND ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "expected failure, got exit code 0")
endif()
if(DEFINED EXIT_CODE AND NOT rc EQUAL EXIT_CODE)
  message(FATAL_ERROR "expected exit code ${EXIT_CODE}, got ${rc}")
endif()
if(NOT "${out}${err}" MATCHES "${REGEX}")
  message(FATAL_ERROR "output does not match '${REGEX}'")
endif()
