# Every failure sets a result code: a library fills a fog_error only through fog_fail,
# fog_error_wrap or fog_error_pass (transform/fog_error.c), never by writing its message.
add_test(NAME transform/error_sites
         COMMAND ${CMAKE_COMMAND} -DROOT=${CMAKE_SOURCE_DIR}
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/transform/check_error_sites.cmake)
