# The VDB render and record tests run the fogpipe binary.
foreach(name test_render_vdb test_record_vdb)
  if(TARGET ${name})
    add_dependencies(${name} fogpipe)
  endif()
endforeach()
