# `fogpipe bench render` smoke test: the benchmark runs at a tiny size, exits 0, writes a
# table CSV whose rows hold finite numbers (all 57 rows: 14 marching, 5 exact and 1 exact of whole rays, 3 ground fog, 2 thresholds, 12 LOD,
# the detailed and the simulated fog's exact walk and 6 marchings each, 6 marchings of the
# ground fog), the
# chart CSV and PNG, and ends with the summary line. It asserts no speed (speed targets
# live in the benchmark itself).
include(${CMAKE_CURRENT_LIST_DIR}/bench_smoke.cmake)
bench_smoke_test(render 120)

set(num "[0-9]+(\\.[0-9]+)?")
bench_smoke_run(render "^render: exact_speedup_at_matched_error=${num} lod_switch_speedup_vs_sum=${num} lod_overhead_at_mu1=${num} empty_skip_speedup=${num} exact_speedup_at_matched_error_detailed=${num}$"
                --size 32x18 --frames 1)

# The upload comparison that decides against a pixel-unpack buffer path (bench_upload.c).
if(NOT bench_output MATCHES "glTexSubImage2D from client memory ${num} ms; through a pixel-unpack buffer ${num} ms")
  message(FATAL_ERROR "no upload comparison (direct vs pixel-unpack buffer) in the output")
endif()

# Empty-space skipping is exact: the ground fog's tau images agree bit for bit.
if(NOT bench_output MATCHES "tau images identical bit for bit")
  message(FATAL_ERROR "the ground fog rows with and without skipping differ")
endif()

# The table: header + 57 rows; every number finite (no nan/inf), errors and times >= 0.
bench_smoke_expect_files(render.csv render_chart.csv render_chart.png render_tau.png)
bench_smoke_read_csv(render.csv "method,setting,ms_per_frame,rmse,max_error,rmse_vs_full,max_error_vs_full" 57)
foreach(line IN LISTS bench_rows)
  # method,setting,ms,rmse,max[,rmse_full,max_full] (the last two only for LOD rows)
  if(NOT line MATCHES "^[^,]+,[^,]+,${finite},${finite},${finite},(${finite},${finite}|,)$")
    message(FATAL_ERROR "render.csv row without finite numbers: '${line}'")
  endif()
  if(line MATCHES "^LOD" AND line MATCHES ",$")
    message(FATAL_ERROR "LOD row without its error against the full model: '${line}'")
  endif()
endforeach()
# The exact rows really are exact (manual fetch, linear basis: float rounding of tau) - the
# smoke test should notice a bench that compares against the wrong reference.
foreach(line IN LISTS bench_rows)
  if(line MATCHES "^exact,linear,${finite},${finite},(${finite}),")
    set(max_error ${CMAKE_MATCH_3})
  endif()
endforeach()
if(NOT DEFINED max_error)
  message(FATAL_ERROR "no exact,linear row in render.csv")
endif()
# CMake has no float comparison: 1e-4 or smaller means an exponent of -5 or below, or 0.
if(NOT (max_error MATCHES "e-0*([5-9]|[1-9][0-9])$" OR max_error STREQUAL "0"))
  message(FATAL_ERROR "exact linear max tau error ${max_error}: expected <= 1e-4")
endif()
# And the detailed and simulated fogs' exact walks (X2's and X's denominators) against
# their own references.
foreach(fog detailed simulated)
  unset(extra_error)
  foreach(line IN LISTS bench_rows)
    if(line MATCHES "^${fog} exact,linear,${finite},${finite},(${finite}),")
      set(extra_error ${CMAKE_MATCH_3})
    endif()
  endforeach()
  if(NOT DEFINED extra_error OR NOT (extra_error MATCHES "e-0*([5-9]|[1-9][0-9])$" OR extra_error STREQUAL "0"))
    message(FATAL_ERROR "${fog} exact max tau error '${extra_error}': expected <= 1e-4")
  endif()
endforeach()
