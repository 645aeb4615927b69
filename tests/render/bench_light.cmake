# `fogpipe bench light` smoke test: the benchmark runs at a tiny size, exits 0, writes its
# table CSV (58 rows of finite numbers: per scene unlit at full and half resolution, ours
# with midpoints at 5 step counts and with two Gauss nodes at 5, the default setting at 2
# more volume sizes, the live rows at the default steps and half of them, 96^3 x 64, two rows
# at a quarter of the resolution, per piece of the exact walk, marching at 7 sample counts, the
# froxel grid at 1x and 2x), the
# chart CSV and PNG, the images to look at, and ends with its summary line. It asserts no
# speed (and no accuracy: test_fog_shadow and test_gpu_froxel do).
include(${CMAKE_CURRENT_LIST_DIR}/bench_smoke.cmake)
bench_smoke_test(light 300)

bench_smoke_run(light "^light: lit_over_unlit=[0-9.]+ lit_over_unlit_full=[0-9.]+ shadow_volume_ms=[0-9.]+ live_max_error=[0-9.e+-]+ froxel_error_ratio_at_equal_time=([0-9.]+|nan) march_speedup_at_matched_error=([0-9.]+|nan)$"
                --size 48x27 --frames 1)
bench_smoke_expect_files(light.csv light_chart.csv light_chart.png light_default_froxels_1x.png
                         light_plume_ours_live.png)
bench_smoke_read_csv(light.csv "scene,method,volume,steps,nodes,divisor,ms_per_frame,max_error,mean_error" 58
  ROW "^[a-z_.]+,(unlit|ours|pieces|march|froxel_1x|froxel_2x),[0-9]+,[0-9]+,[12],[124],${finite},${finite},${finite}$")
