# `fogpipe bench light` smoke test: the benchmark runs at a tiny size, exits 0, writes its
# table CSV (52 rows of finite numbers: per scene unlit at full and half resolution, ours
# with midpoints at 5 step counts and with two Gauss nodes at 5, the default setting at 2
# more volume sizes, the live rows at the default steps and half of them, 96^3 x 64, two rows
# at a quarter of the resolution, per piece of the exact walk, marching at 4 sample counts, the
# froxel grid at 1x and 2x), the
# chart CSV and PNG, the images to look at, and ends with its summary line. It asserts no
# speed (and no accuracy: test_fog_shadow and test_gpu_froxel do).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME render/bench_light_smoke
           COMMAND ${CMAKE_COMMAND} -DFOGPIPE=$<TARGET_FILE:fogpipe>
                   -DOUT=${CMAKE_CURRENT_BINARY_DIR}/bench_light_smoke
                   -P ${CMAKE_CURRENT_LIST_FILE})
  set_tests_properties(render/bench_light_smoke PROPERTIES
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    ENVIRONMENT "LP_NUM_THREADS=1" TIMEOUT 300)
  return()
endif()

file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${FOGPIPE} bench light --size 48x27 --frames 1 --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fogpipe bench light exited with ${rc}: ${err}")
endif()
string(STRIP "${out}" out)
string(REGEX MATCH "[^\n]*$" last "${out}")
if(NOT last MATCHES "^light: lit_over_unlit=[0-9.]+ lit_over_unlit_full=[0-9.]+ shadow_volume_ms=[0-9.]+ live_max_error=[0-9.e+-]+ froxel_error_ratio_at_equal_time=([0-9.]+|nan) march_speedup_at_matched_error=([0-9.]+|nan)$")
  message(FATAL_ERROR "last line is not the summary line: '${last}'")
endif()
foreach(f light.csv light_chart.csv light_chart.png light_default_froxels_1x.png
          light_plume_ours_live.png)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "missing output ${OUT}/${f}")
  endif()
endforeach()
file(STRINGS ${OUT}/light.csv lines)
list(LENGTH lines count)
if(NOT count EQUAL 53)
  message(FATAL_ERROR "light.csv has ${count} lines, expected a header and 52 rows")
endif()
list(GET lines 0 header)
if(NOT header STREQUAL "scene,method,volume,steps,nodes,divisor,ms_per_frame,max_error,mean_error")
  message(FATAL_ERROR "light.csv header: '${header}'")
endif()
list(REMOVE_AT lines 0)
set(finite "[0-9.]+(e[-+][0-9]+)?")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^[a-z_.]+,(unlit|ours|pieces|march|froxel),[0-9]+,[0-9]+,[12],[124],${finite},${finite},${finite}$")
    message(FATAL_ERROR "light.csv row without finite numbers: '${line}'")
  endif()
endforeach()
