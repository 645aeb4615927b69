# `fogpipe bench lights` smoke test: the benchmark runs at a tiny size, exits 0, writes its
# table CSV (26 rows of finite numbers: per scene unlit, ours at 5 piece counts, marching at
# 4 (valley) and 5 (tube) sample counts, Fogshop's on the tube, the valley's T walk at 4 and
# 16 steps and its unlit and ours at half resolution), the chart CSV and PNG, and
# ends with its summary line. It asserts no speed (and no accuracy: test_lamp_accuracy does).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME render/bench_lights_smoke
           COMMAND ${CMAKE_COMMAND} -DFOGPIPE=$<TARGET_FILE:fogpipe>
                   -DOUT=${CMAKE_CURRENT_BINARY_DIR}/bench_lights_smoke
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(render/bench_lights_smoke PROPERTIES
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    ENVIRONMENT "LP_NUM_THREADS=1" TIMEOUT 600)
  return()
endif()

file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${FOGPIPE} bench lights --size 32x18 --frames 1 --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fogpipe bench lights exited with ${rc}: ${err}")
endif()
string(STRIP "${out}" out)
string(REGEX MATCH "[^\n]*$" last "${out}")
if(NOT last MATCHES "^lights: ms_per_light=[0-9.]+ march_speedup_at_matched_error=([0-9.]+|nan) fogshop_halo_error_ratio=[0-9]+$")
  message(FATAL_ERROR "last line is not the summary line: '${last}'")
endif()
foreach(f lights.csv lights_chart.csv lights_chart.png)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "missing output ${OUT}/${f}")
  endif()
endforeach()
file(STRINGS ${OUT}/lights.csv lines)
list(LENGTH lines count)
if(NOT count EQUAL 27)
  message(FATAL_ERROR "lights.csv has ${count} lines, expected a header and 26 rows")
endif()
list(GET lines 0 header)
if(NOT header STREQUAL "scene,method,ms_per_frame,max_error,mean_error")
  message(FATAL_ERROR "lights.csv header: '${header}'")
endif()
list(REMOVE_AT lines 0)
set(finite "[0-9.]+(e[-+][0-9]+)?")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^(valley|tube),[a-z0-9+/ ]+,${finite},${finite},${finite}$")
    message(FATAL_ERROR "lights.csv row without finite numbers: '${line}'")
  endif()
endforeach()
