# The pipeline's picking and painting check needs the app's own sources (the plain
# tests/app/test_*.c executables link only the libraries).
add_executable(pipeline_paint_check ${CMAKE_CURRENT_SOURCE_DIR}/app/pipeline_paint_check.c
               ${CMAKE_SOURCE_DIR}/app/pipeline.c ${CMAKE_SOURCE_DIR}/app/pipeline_fog.c
               ${CMAKE_SOURCE_DIR}/app/config.c)
target_include_directories(pipeline_paint_check PRIVATE ${CMAKE_SOURCE_DIR})
target_link_libraries(pipeline_paint_check PRIVATE fogpipe_render fogpipe_sim fogpipe_transform
                      test_util m)
add_test(NAME app/pipeline_paint_check COMMAND pipeline_paint_check)
set_tests_properties(app/pipeline_paint_check PROPERTIES
  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
  ENVIRONMENT "LP_NUM_THREADS=1")
