# Fails naming each line outside transform/fog_error.c that writes an error's message
# directly (snprintf/strcpy/memcpy/... into X.message or X->message): such a failure would
# leave the code at FOG_SUCCESS.
file(GLOB_RECURSE sources ${ROOT}/sim/*.c ${ROOT}/sim/*.cpp ${ROOT}/transform/*.c
     ${ROOT}/render/*.c ${ROOT}/app/*.c ${ROOT}/bench/*.c)
set(found "")
foreach(source ${sources})
  if(source MATCHES "transform/fog_error\\.c$")
    continue()
  endif()
  file(STRINGS ${source} lines REGEX "(snprintf|strcpy|strncpy|memcpy|strcat|sprintf)\\([^,;]*(->|\\.)message[^_a-zA-Z]")
  foreach(line ${lines})
    string(APPEND found "\n  ${source}: ${line}")
  endforeach()
endforeach()
if(found)
  message(FATAL_ERROR "messages written without a result code (use fog_fail):${found}")
endif()
message(STATUS "every error site sets a code")
