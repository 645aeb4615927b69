# `fogpipe bench lights` smoke test: the benchmark runs at a tiny size, exits 0, writes its
# table CSV (27 rows of finite numbers: per scene unlit, ours at 5 piece counts, marching at
# 4 (valley) and 5 (tube) sample counts, Fogshop's on the tube, the valley's T walk at 4 and
# 16 steps, the live demo's rule and its unlit and ours at half resolution; each row's time
# measured, or for marching past the renderer's loop cap extrapolated), the chart CSV and
# PNG, and ends with its summary line; without gnuplot on the PATH, the same but the PNG. It
# asserts no speed (and no accuracy: test_lamp_accuracy does).
include(${CMAKE_CURRENT_LIST_DIR}/bench_smoke.cmake)
bench_smoke_test(lights 600)

bench_smoke_run(lights "^lights: ms_per_light=[0-9.]+ march_speedup_at_matched_error=([0-9.]+|nan) fogshop_halo_error_ratio=[0-9]+ march_time_extrapolated=[01]$"
                --size 32x18 --frames 1)
bench_smoke_expect_files(lights.csv lights_chart.csv lights_chart.png)
bench_smoke_read_csv(lights.csv "scene,method,ms_per_frame,max_error,mean_error,timed" 27
  ROW "^(valley|tube),([a-z0-9+/ ]+,${finite},${finite},${finite}|unlit[ 1/2]*,${finite},,),(measured|extrapolated)$")

# Without gnuplot (the GPU kit ships none): the same figures and summary line, exit 0, the
# chart's points in its CSV and no PNG (a missing gnuplot cost a run of minutes its summary).
set(fogpipe_alone ${FOGPIPE})
set(FOGPIPE ${CMAKE_COMMAND} -E env PATH=${OUT}_no_gnuplot_here ${fogpipe_alone})
bench_smoke_run(lights "^lights: ms_per_light=[0-9.]+ march_speedup_at_matched_error=([0-9.]+|nan) fogshop_halo_error_ratio=[0-9]+ march_time_extrapolated=[01]$"
                --size 32x18 --frames 1)
set(FOGPIPE ${fogpipe_alone})
if(NOT bench_output MATCHES "chart: the PNG is not drawn \\(gnuplot")
  message(FATAL_ERROR "without gnuplot: no note that the PNG is not drawn")
endif()
bench_smoke_expect_files(lights.csv lights_chart.csv)
if(EXISTS ${OUT}/lights_chart.png)
  message(FATAL_ERROR "without gnuplot: a chart PNG ${OUT}/lights_chart.png")
endif()
