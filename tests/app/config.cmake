# The render tests run the fogpipe binary: build it with them.
foreach(name test_render_golden test_render_errors test_view_window test_render_fog_models test_fit_cli)
  if(TARGET ${name})
    add_dependencies(${name} fogpipe)
  endif()
endforeach()
