# app/vdb_source.c and app/config.c live in the fogpipe executable: the VDB source test
# compiles them in and links the OpenVDB adapter (fogpipe_vdb). The VDB render test runs
# the fogpipe binary.
foreach(name test_vdb_source test_render_vdb)
  if(TARGET ${name})
    target_sources(${name} PRIVATE ${CMAKE_SOURCE_DIR}/app/vdb_source.c
                   ${CMAKE_SOURCE_DIR}/app/config.c)
    target_link_libraries(${name} PRIVATE fogpipe_vdb)
  endif()
endforeach()
foreach(name test_render_vdb test_record_vdb)
  if(TARGET ${name})
    add_dependencies(${name} fogpipe)
  endif()
endforeach()
# The pipeline (demo, record) plays a [fog] vdb sequence through app/vdb_source.c.
if(TARGET pipeline_paint_check)
  target_sources(pipeline_paint_check PRIVATE ${CMAKE_SOURCE_DIR}/app/vdb_source.c)
  target_link_libraries(pipeline_paint_check PRIVATE fogpipe_vdb)
endif()
