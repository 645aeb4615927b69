# `fogpipe transform` end to end: round trip through a folder and bad input. Needs the
# sim library to read EXRs, hence not one of the globbed test_*.c (transform only).
add_executable(transform_cli_roundtrip ${CMAKE_CURRENT_SOURCE_DIR}/transform/cli_roundtrip.c)
target_link_libraries(transform_cli_roundtrip PRIVATE fogpipe_sim test_util m)
add_dependencies(transform_cli_roundtrip fogpipe)
add_test(NAME transform/cli_roundtrip COMMAND transform_cli_roundtrip)
set_tests_properties(transform/cli_roundtrip PROPERTIES
  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
  ENVIRONMENT "LP_NUM_THREADS=1;FOGPIPE_BIN=$<TARGET_FILE:fogpipe>" TIMEOUT 60)

# `fogpipe transform` stopped by SIGTERM while writing: exit 130, nothing left behind.
add_executable(transform_cli_interrupt ${CMAKE_CURRENT_SOURCE_DIR}/transform/cli_interrupt.c)
target_link_libraries(transform_cli_interrupt PRIVATE fogpipe_sim test_util m)
add_dependencies(transform_cli_interrupt fogpipe)
add_test(NAME transform/cli_interrupt COMMAND transform_cli_interrupt)
set_tests_properties(transform/cli_interrupt PROPERTIES
  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
  ENVIRONMENT "LP_NUM_THREADS=1;FOGPIPE_BIN=$<TARGET_FILE:fogpipe>" TIMEOUT 60)
