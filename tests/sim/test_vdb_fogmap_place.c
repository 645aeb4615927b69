/* vdb_fogmap_place_fit (sim/vdb_import.h) covers the domain with whole cells: an exact
 * multiple gets no extra empty cell (6 units in cells of 0.5: 12), a domain that is not
 * one gets the cell that holds the rest (6 in cells of 0.7: 9), and a cell wider than the
 * domain is one cell, at any size (`import --cell 1e9` said "a fogmap of -0 x -0 cells"). */
#include <stdio.h>

#include "sim/vdb_import.h"
#include "test_util.h"

static void check(double cell, int expected) {
  vdb_fogmap_place place;
  fog_error err = {0};
  int status = vdb_fogmap_place_fit(-3.0, 3.0, -3.0, 3.0, 0, cell, 0.1, &place, &err);
  CHECK(status == 0 && place.width == expected && place.height == expected &&
            place.cell_size == cell,
        "cell %g over 6 units: %s %dx%d, expected %dx%d", cell, status ? err.message : "",
        place.width, place.height, expected, expected);
}

int main(void) {
  check(0.5, 12);
  check(0.7, 9);
  check(7.0, 1);
  check(1e9, 1);
  check(1e300, 1);
  return test_finish("test_vdb_fogmap_place");
}
