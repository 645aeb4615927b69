# The render-farm script (scripts/farm/slurm_record.sh) run as a job array would run it.
add_test(NAME app/farm_script_check COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/app/farm_script_check.sh)
set_tests_properties(app/farm_script_check PROPERTIES
  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
  ENVIRONMENT "LP_NUM_THREADS=1;FOGPIPE_BIN=$<TARGET_FILE:fogpipe>")
# The same through a private single-node Slurm cluster, where Slurm and munge are installed
# (.ci/run installs them); skipped (77) elsewhere.
add_test(NAME app/farm_slurm_check COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/app/farm_slurm_check.sh)
set_tests_properties(app/farm_slurm_check PROPERTIES
  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
  SKIP_RETURN_CODE 77
  ENVIRONMENT "LP_NUM_THREADS=1;FOGPIPE_BIN=$<TARGET_FILE:fogpipe>")
