# Every `fogpipe bench` stage at a smoke size (tests/app/bench_stages_check.sh).
add_test(NAME app/bench_stages_check
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/app/bench_stages_check.sh)
set_tests_properties(app/bench_stages_check PROPERTIES
  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
  ENVIRONMENT "LP_NUM_THREADS=1;FOGPIPE_BIN=$<TARGET_FILE:fogpipe>")
