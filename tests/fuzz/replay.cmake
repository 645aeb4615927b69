# Every libFuzzer harness (tests/fuzz/harnesses.cmake), built with the ordinary compiler and
# tests/fuzz/replay_main.c in place of libFuzzer, and run once over its seed corpus and its
# regression inputs: the ctest twin of `make fuzz-regressions` (which needs clang and runs
# only in CI), so a harness that stops linking, or an input that starts to fail, shows in
# make test. Under FOGPIPE_SANITIZE it runs with ASan and UBSan like the libFuzzer build.
include(${CMAKE_SOURCE_DIR}/tests/fuzz/harnesses.cmake)
foreach(harness ${FOGPIPE_FUZZ_HARNESSES})
  set(sources)
  foreach(source ${FOGPIPE_FUZZ_${harness}_SOURCES})
    list(APPEND sources ${CMAKE_SOURCE_DIR}/${source})
  endforeach()
  set(target fuzz_replay_${harness})
  add_executable(${target} ${sources} ${CMAKE_SOURCE_DIR}/tests/fuzz/fuzz_util.c
                 ${CMAKE_SOURCE_DIR}/tests/fuzz/replay_main.c)
  target_include_directories(${target} PRIVATE ${CMAKE_SOURCE_DIR} ${CMAKE_SOURCE_DIR}/tests/fuzz)
  target_compile_definitions(${target} PRIVATE GL_GLEXT_PROTOTYPES)
  target_link_libraries(${target} PRIVATE ${FOGPIPE_FUZZ_${harness}_LIBS})
  set(inputs tests/fuzz/corpus/${harness})
  if(IS_DIRECTORY ${CMAKE_SOURCE_DIR}/tests/fuzz/regressions/${harness})
    list(APPEND inputs tests/fuzz/regressions/${harness})
  endif()
  add_test(NAME fuzz/replay_${harness} COMMAND ${target} ${inputs})
  set_tests_properties(fuzz/replay_${harness} PROPERTIES WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
endforeach()
