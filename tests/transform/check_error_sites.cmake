# Fails naming each call outside transform/fog_error.c that writes an error's message
# directly (snprintf/strcpy/memcpy/... into X.message or X->message, its arguments on one
# line or several): such a failure would leave the code at FOG_SUCCESS.
file(GLOB_RECURSE sources ${ROOT}/sim/*.c ${ROOT}/sim/*.cpp ${ROOT}/transform/*.c
     ${ROOT}/render/*.c ${ROOT}/app/*.c ${ROOT}/bench/*.c)
set(found "")
foreach(source ${sources})
  if(source MATCHES "transform/fog_error\\.c$")
    continue()
  endif()
  file(READ ${source} text)
  string(REGEX MATCHALL
         "(snprintf|strcpy|strncpy|memcpy|strcat|sprintf)\\([^,;()]*(->|\\.)message[^_a-zA-Z]"
         calls "${text}")
  foreach(call ${calls})
    string(REPLACE "\n" " " call "${call}")
    string(APPEND found "\n  ${source}: ${call}")
  endforeach()
endforeach()
if(found)
  message(FATAL_ERROR "messages written without a result code (use fog_fail):${found}")
endif()
message(STATUS "every error site sets a code")
