# End-to-end check of `grip ccd-bench`: run as
#   cmake -DGRIP=<grip executable> -DWORK=<scratch dir> -P ccd_bench_cli.cmake
# It writes the hard query set, scores it (exit 0, zero false negatives, the JSON object as the
# last line), and checks the exit codes of a malformed file (1, naming file and line) and of a
# usage error (2).
file(REMOVE_RECURSE ${WORK})

execute_process(COMMAND ${GRIP} ccd-bench --write-hard ${WORK} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "grip ccd-bench --write-hard exited ${rc}")
endif()

foreach(type vf ee)
  if(type STREQUAL "vf")
    set(csv ${WORK}/hard-vertex-face.csv)
  else()
    set(csv ${WORK}/hard-edge-edge.csv)
  endif()
  execute_process(COMMAND ${GRIP} ccd-bench --type ${type} ${csv}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  string(STRIP "${out}" out)
  string(REGEX REPLACE ".*\n" "" last "${out}")
  if(NOT rc EQUAL 0 OR NOT last MATCHES
     "^\\{\"queries\":[0-9]+,\"false_negatives\":0,\"false_positives\":[0-9]+,\"ns_per_query\":[0-9.]+\\}$")
    message(FATAL_ERROR "grip ccd-bench --type ${type}: exit ${rc}, last line '${last}'")
  endif()
endforeach()

file(WRITE ${WORK}/bad.csv "1,2,3,4,5,6,1\n1,2,3,0,5,6,1\n")
execute_process(COMMAND ${GRIP} ccd-bench --type vf ${WORK}/bad.csv
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "bad.csv:2: column 4 is a zero denominator")
  message(FATAL_ERROR "malformed file: exit ${rc} (want 1), stderr '${err}'")
endif()

execute_process(COMMAND ${GRIP} ccd-bench ${WORK}/bad.csv RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "missing --type: exit ${rc} (want 2)")
endif()
execute_process(COMMAND ${GRIP} ccd-bench --type xy ${WORK}/bad.csv RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "--type xy: exit ${rc} (want 2)")
endif()
