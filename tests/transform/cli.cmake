# `fogpipe transform` end to end (cli_roundtrip: round trip through a folder and bad input;
# cli_interrupt: stopped by SIGTERM while writing, exit 130 and nothing left behind). They
# need the sim library to read EXRs, hence not globbed test_*.c (transform only).
foreach(check cli_roundtrip cli_interrupt)
  add_executable(transform_${check} ${CMAKE_CURRENT_SOURCE_DIR}/transform/${check}.c)
  target_link_libraries(transform_${check} PRIVATE fogpipe_sim test_util m)
  add_dependencies(transform_${check} fogpipe)
  add_test(NAME transform/${check} COMMAND transform_${check})
  set_tests_properties(transform/${check} PROPERTIES
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    ENVIRONMENT "LP_NUM_THREADS=1;FOGPIPE_BIN=$<TARGET_FILE:fogpipe>" TIMEOUT 60)
endforeach()
