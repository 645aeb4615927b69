# The pipeline checks (not named test_*: they run without the fogpipe binary's environment,
# no FOGPIPE_BIN, and link the app's library alone, without the sim's and transform's beside):
#   pipeline_paint_check  picking and painting (what the demo's mouse does)
#   pipeline_sun_check    the demo's time of day relights terrain and fog
#   pipeline_rung_check   the demo's model menu: a rung fitted to the fog live
#   pipeline_lamps_check  the live demo draws a frame past the loop cap without its lamps
#   pipeline_controls_check  N while running, and strokes beside the fog's box
foreach(check pipeline_paint_check pipeline_sun_check pipeline_rung_check pipeline_lamps_check
              pipeline_controls_check)
  add_executable(${check} ${CMAKE_CURRENT_SOURCE_DIR}/app/${check}.c)
  target_link_libraries(${check} PRIVATE fogpipe_app test_util m)
  add_test(NAME app/${check} COMMAND ${check})
  set_tests_properties(app/${check} PROPERTIES
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    ENVIRONMENT "LP_NUM_THREADS=1")
endforeach()
