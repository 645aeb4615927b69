# Cross-check against PyWavelets (Debian python3-pywt via /usr/bin/python3, not a pyenv
# python on PATH): a small C program writes coefficients, a python script compares.
# Skipped (exit 77) where /usr/bin/python3 has no pywt.
add_executable(transform_pywt_dump ${CMAKE_CURRENT_SOURCE_DIR}/transform/pywt_dump.c)
target_link_libraries(transform_pywt_dump PRIVATE fogpipe_transform test_util m)
add_test(NAME transform/pywt_crosscheck
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/transform/pywt_compare.py
                 $<TARGET_FILE:transform_pywt_dump> ${CMAKE_CURRENT_BINARY_DIR})
set_tests_properties(transform/pywt_crosscheck PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60)
