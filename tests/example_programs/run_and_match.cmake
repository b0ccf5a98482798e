# Run PROGRAM; fail unless it exits 0 and its standard output matches every regular expression of EXPECT (separated
# by @@). Usage: cmake -DPROGRAM=path "-DEXPECT=re1@@re2" -P run_and_match.cmake
execute_process(COMMAND ${PROGRAM} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} exited with ${rc}\n${err}")
endif()
string(REPLACE "@@" ";" expressions "${EXPECT}")
foreach(re IN LISTS expressions)
  if(NOT out MATCHES "${re}")
    message(FATAL_ERROR "the output of ${PROGRAM} does not match \"${re}\"")
  endif()
endforeach()
