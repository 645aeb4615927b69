# The window test skips (ctest code 77) where xvfb-run is missing.
if(TEST app/test_demo_window)
  set_tests_properties(app/test_demo_window PROPERTIES SKIP_RETURN_CODE 77)
endif()

# Quick Ctrl+S taps in `fogpipe view` save the brush's scene (tests/app/window_ctrl_s_tap.py:
# XTest keys under Xvfb; skipped where xvfb-run or libXtst is missing).
find_program(FOGPIPE_XVFB_RUN xvfb-run)
if(FOGPIPE_XVFB_RUN)
  add_test(NAME app/window_ctrl_s_tap
           COMMAND ${FOGPIPE_XVFB_RUN} -a -s "-screen 0 640x480x24" python3
                   ${CMAKE_CURRENT_SOURCE_DIR}/app/window_ctrl_s_tap.py $<TARGET_FILE:fogpipe>)
  set_tests_properties(app/window_ctrl_s_tap PROPERTIES
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR} SKIP_RETURN_CODE 77
    ENVIRONMENT "LP_NUM_THREADS=1")
endif()
