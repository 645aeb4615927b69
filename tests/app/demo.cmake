# The window test skips (ctest code 77) where xvfb-run is missing.
if(TEST app/test_demo_window)
  set_tests_properties(app/test_demo_window PROPERTIES SKIP_RETURN_CODE 77)
endif()
