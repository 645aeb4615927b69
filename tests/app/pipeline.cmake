# The pipeline's picking and painting check (not named test_*: it runs without the
# fogpipe binary's environment).
add_executable(pipeline_paint_check ${CMAKE_CURRENT_SOURCE_DIR}/app/pipeline_paint_check.c)
target_link_libraries(pipeline_paint_check PRIVATE fogpipe_app test_util m)
add_test(NAME app/pipeline_paint_check COMMAND pipeline_paint_check)
set_tests_properties(app/pipeline_paint_check PROPERTIES
  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
  ENVIRONMENT "LP_NUM_THREADS=1")

# The demo's time of day (the panel's sun sliders) relights terrain and fog.
add_executable(pipeline_sun_check ${CMAKE_CURRENT_SOURCE_DIR}/app/pipeline_sun_check.c)
target_link_libraries(pipeline_sun_check PRIVATE fogpipe_app test_util m)
add_test(NAME app/pipeline_sun_check COMMAND pipeline_sun_check)
set_tests_properties(app/pipeline_sun_check PROPERTIES
  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
  ENVIRONMENT "LP_NUM_THREADS=1")
