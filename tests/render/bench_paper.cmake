# `fogpipe bench paper` smoke test: the benchmark runs at a tiny size, exits 0, writes
# paper.csv (76 rows of finite numbers: Table 1's 9 grids and the raw map, Table 2's 2
# methods x 4 levels x 6 mu, Table 3's 9 pyramids before and after deconstruction; Table
# 1's and Table 2's rows normalised to 1 in their first cells) and ends with its summary
# line (E is nan while the paper's cells are out of reach; a number once they are not). It asserts no
# speed: the shapes are the benchmark's to print.
include(${CMAKE_CURRENT_LIST_DIR}/bench_smoke.cmake)
bench_smoke_test(paper 300)

bench_smoke_run(paper "^paper: table2_shape_error=(nan|[0-9.]+) table3_deconstruction_gain=[0-9.]+$"
                --size 32x18 --frames 1)
bench_smoke_expect_files(paper.csv)
bench_smoke_read_csv(paper.csv "table,fog,size,levels,mu,method,fps,normalised" 76
  ROW "^[123],(Haar|linear|quadratic|raw|sum|switch),(16|32|64),[0-3],[01](\\.[0-9])?,(-|before|after),${finite},${finite}$")
# every table row starts at 1: Table 2's mu = 1 cells and Table 3's befores
set(firsts 0)
foreach(line IN LISTS bench_rows)
  if(line MATCHES "^(2,[a-z]+,64,[0-3],1\\.0|1,[A-Za-z]+,16,0,1),-,${finite},(${finite})$")
    math(EXPR firsts "${firsts} + 1")
    if(NOT CMAKE_MATCH_3 STREQUAL "1")
      message(FATAL_ERROR "a row's first cell is not 1: '${line}'")
    endif()
  endif()
endforeach()
if(NOT firsts EQUAL 11)
  message(FATAL_ERROR "${firsts} first cells, expected 11: Table 2's 8 (2 methods x 4 levels) "
                      "and Table 1's 3 (a basis each)")
endif()
