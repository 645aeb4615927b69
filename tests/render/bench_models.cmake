# `fogpipe bench models` smoke test: the benchmark runs at a tiny size, exits 0, writes a
# table CSV of 47 rows of finite numbers (homogeneous, linear and exp2 exact; height, rbf,
# quadric and quadric-noise exact + 6 marching each; the volume exact, exact without skipping, exact with
# hardware filtering and 5 marching; Perlin exact, the paper's single sample and 6
# marching), the chart CSV and PNG, ends with its
# summary line, and its exact rows agree with the CPU model (max tau error <= 1e-4: a bench
# comparing against the wrong reference fails here). It asserts no speed.
include(${CMAKE_CURRENT_LIST_DIR}/bench_smoke.cmake)
bench_smoke_test(models 120)

set(num "[0-9]+[.]?[0-9]*") # no group: CMake keeps at most 9 per match
bench_smoke_run(models "^models: rbf_exact_ms=${num} rbf_march_speedup_at_matched_error=${num} height_exact_ms=${num} height_march_speedup_at_matched_error=${num} volume_exact_ms=${num} volume_march_speedup_at_matched_error=${num} volume_empty_skip_speedup=${num} quadric_exact_ms=${num} quadric_march_speedup_at_matched_error=${num} rbf_64_ms=${num} rbf_3000_ms=${num} fit_s=${num} perlin_exact_ms=${num} perlin_march_speedup_at_matched_error=${num} perlin_paper_error=${num} unmatched=(none|[a-z0-9+]+)$"
                --size 32x18 --frames 1)
bench_smoke_expect_files(models.csv models_chart.csv models_chart.png)
bench_smoke_read_csv(models.csv "model,method,setting,ms_per_frame,rmse,max_error" 47)
foreach(line IN LISTS bench_rows)
  if(NOT line MATCHES "^(homogeneous|height|rbf|volume|quadric|quadric-noise|linear|exp2|perlin),(exact|exact-hardware|exact-no-skip|paper|march),[0-9.]+,${finite},${finite},(${finite})$")
    message(FATAL_ERROR "models.csv row without finite numbers: '${line}'")
  endif()
  set(max_error ${CMAKE_MATCH_5}) # groups: model, method, ms exponent, rmse exponent, max
  # CMake has no float comparison: <= 1e-4 means an exponent of -5 or below, or 0.
  if(line MATCHES ",exact(-hardware|-no-skip)?," AND NOT (max_error MATCHES "e-0*([5-9]|[1-9][0-9])$" OR max_error STREQUAL "0"))
    message(FATAL_ERROR "exact row with max tau error ${max_error}: '${line}'")
  endif()
endforeach()
