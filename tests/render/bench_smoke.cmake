# What the `fogpipe bench STAGE` smoke tests (bench_*.cmake) share. Each of those files is
# both the test's definition (included by tests/CMakeLists.txt: bench_smoke_add) and its
# script (run by that test with `cmake -DFOGPIPE=... -DOUT=... -P bench_STAGE.cmake`: the
# other functions). They assert no speed: the speed targets live in the benchmarks.

# Registers render/bench_STAGE_smoke, running SCRIPT (the including file) as a script.
function(bench_smoke_add stage script timeout)
  add_test(NAME render/bench_${stage}_smoke
           COMMAND ${CMAKE_COMMAND} -DFOGPIPE=$<TARGET_FILE:fogpipe>
                   -DOUT=${CMAKE_CURRENT_BINARY_DIR}/bench_${stage}_smoke -P ${script})
  set_tests_properties(render/bench_${stage}_smoke PROPERTIES
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    ENVIRONMENT "LP_NUM_THREADS=1;FOGPIPE_BIN=$<TARGET_FILE:fogpipe>" TIMEOUT ${timeout})
endfunction()

# The first line of a bench_STAGE.cmake after its include: configuring, it registers the
# test and returns from the file; run as the test's script, it does nothing and the file's
# checks follow. (A macro: its return() leaves the including file.)
macro(bench_smoke_test stage timeout)
  if(NOT CMAKE_SCRIPT_MODE_FILE)
    bench_smoke_add(${stage} ${CMAKE_CURRENT_LIST_FILE} ${timeout})
    return()
  endif()
endmacro()

# Runs `fogpipe bench STAGE ARGS... --out OUT` (OUT emptied first); fails unless it exits 0
# and its last line matches SUMMARY. Sets bench_output (the whole stdout) in the caller.
function(bench_smoke_run stage summary)
  file(REMOVE_RECURSE ${OUT})
  execute_process(COMMAND ${FOGPIPE} bench ${stage} ${ARGN} --out ${OUT}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fogpipe bench ${stage} exited with ${rc}: ${err}")
  endif()
  string(STRIP "${out}" out)
  string(REGEX MATCH "[^\n]*$" last "${out}")
  if(NOT last MATCHES "${summary}")
    message(FATAL_ERROR "last line is not the summary line: '${last}'")
  endif()
  set(bench_output "${out}" PARENT_SCOPE)
endfunction()

# Fails unless every named file is in OUT.
function(bench_smoke_expect_files)
  foreach(f ${ARGN})
    if(NOT EXISTS ${OUT}/${f})
      message(FATAL_ERROR "missing output ${OUT}/${f}")
    endif()
  endforeach()
endfunction()

# Reads OUT/CSV: fails unless it holds HEADER and ROWS rows, and with `ROW REGEX` unless
# every row matches REGEX. Sets bench_rows (the rows without the header) in the caller.
function(bench_smoke_read_csv csv header rows)
  cmake_parse_arguments(ARG "" "ROW" "" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS OR ARG_KEYWORDS_MISSING_VALUES)
    message(FATAL_ERROR "bench_smoke_read_csv(${csv}): unknown or empty arguments "
                        "'${ARG_UNPARSED_ARGUMENTS}${ARG_KEYWORDS_MISSING_VALUES}'")
  endif()
  file(STRINGS ${OUT}/${csv} lines)
  list(LENGTH lines count)
  math(EXPR expected "${rows} + 1")
  if(NOT count EQUAL expected)
    message(FATAL_ERROR "${csv} has ${count} lines, expected a header and ${rows} rows")
  endif()
  list(GET lines 0 first)
  if(NOT first STREQUAL "${header}")
    message(FATAL_ERROR "${csv} header: '${first}'")
  endif()
  list(REMOVE_AT lines 0)
  if(DEFINED ARG_ROW)
    foreach(line IN LISTS lines)
      if(NOT line MATCHES "${ARG_ROW}")
        message(FATAL_ERROR "${csv} row without finite numbers: '${line}'")
      endif()
    endforeach()
  endif()
  set(bench_rows "${lines}" PARENT_SCOPE)
endfunction()

# A finite number as the benchmarks print it (one regex group).
set(finite "[0-9.]+(e[-+][0-9]+)?")
