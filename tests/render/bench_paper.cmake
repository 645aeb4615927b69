# `fogpipe bench paper` smoke test: the benchmark runs at a tiny size, exits 0, writes
# paper.csv (76 rows of finite numbers: Table 1's 9 grids and the raw map, Table 2's 2
# methods x 4 levels x 6 mu, Table 3's 9 pyramids before and after deconstruction, each
# row's normalised value 1 in its first cell) and ends with its summary line. It asserts no
# speed: the shapes are the benchmark's to print.
include(${CMAKE_CURRENT_LIST_DIR}/bench_smoke.cmake)
bench_smoke_test(paper 300)

bench_smoke_run(paper "^paper: table2_shape_error=nan table3_deconstruction_gain=[0-9.]+$"
                --size 32x18 --frames 1)
bench_smoke_expect_files(paper.csv)
bench_smoke_read_csv(paper.csv "table,fog,size,levels,mu,method,fps,normalised" 76
  ROW "^[123],(Haar|linear|quadratic|raw|sum|switch),(16|32|64),[0-3],[01](\\.[0-9])?,(-|before|after),${finite},${finite}$")
# every table row starts at 1: Table 2's mu = 1 cells and Table 3's befores
set(firsts 0)
foreach(line IN LISTS bench_rows)
  if(line MATCHES "^2,[a-z]+,64,[0-3],1\\.0,-,${finite},(${finite})$")
    math(EXPR firsts "${firsts} + 1")
    if(NOT CMAKE_MATCH_2 STREQUAL "1")
      message(FATAL_ERROR "a Table 2 row's mu = 1 cell is not 1: '${line}'")
    endif()
  endif()
endforeach()
if(NOT firsts EQUAL 8)
  message(FATAL_ERROR "Table 2 has ${firsts} mu = 1 cells, expected 8 (2 methods x 4 levels)")
endif()
