// `fogpipe import --profile-per frame` (run as $FOGPIPE_BIN): each frame's sidecar sections
// [box.NNNN] and [fog.NNNN] are what importing that frame alone gives in [box] and [fog]:
// the same profile and the same floor and top. A box spanning every frame's support would
// add fog to a frame whose own support is narrower: a slab fills the box, the exponential
// profile is 1 from the box's floor up (frame 2 below: 3.2x the optical depth). The frames:
// a block of fog at y 0..0.5, then one at y 2..2.5. (C++ only to write the grids.)
#include <openvdb/openvdb.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "test_util.h"

static std::string dir;

// A 0.1-voxel block of density 1: x, z in [-0.5, 0.5), y from y0 for 0.5.
static void write_block(const std::string &path, int y0_voxels) {
  openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create();
  g->setName("density");
  g->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
  for (int x = -5; x < 5; x++)
    for (int z = -5; z < 5; z++)
      for (int y = y0_voxels; y < y0_voxels + 5; y++)
        g->tree().setValue(openvdb::Coord(x, y, z), 1.0f);
  openvdb::GridPtrVec grids{g};
  openvdb::io::File(path).write(grids);
}

// section -> its key = value lines, comments and blank lines left out, in order.
static std::map<std::string, std::string> sections(const std::string &path) {
  std::map<std::string, std::string> out;
  std::ifstream in(path);
  std::string line, section;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == ';') continue;
    if (line[0] == '[') {
      section = line.substr(1, line.find(']') - 1);
      continue;
    }
    out[section] += line + "\n";
  }
  return out;
}

static int run(const std::string &args) {
  std::string cmd = std::string("'") + getenv("FOGPIPE_BIN") + "' import " + args + " > '" +
                    dir + "/log.txt' 2>&1";
  int status = system(cmd.c_str());
  if (status != 0) {
    std::ifstream log(dir + "/log.txt");
    std::stringstream text;
    text << log.rdbuf();
    fprintf(stderr, "%s:\n%s\n", cmd.c_str(), text.str().c_str());
  }
  return status;
}

int main() {
  if (!getenv("FOGPIPE_BIN")) {
    fprintf(stderr, "FOGPIPE_BIN is not set to the fogpipe binary\n");
    return 1;
  }
  char root[] = "/tmp/fogpipe-import-per-frame-XXXXXX";
  if (!test_scratch_folder(root)) return 1;
  dir = root;
  openvdb::initialize();
  write_block(dir + "/blk_0001.vdb", 0);
  write_block(dir + "/blk_0002.vdb", 20);
  for (const char *kind : {"exponential", "bspline"}) {
    const std::string seq = dir + "/seq_" + kind, one = dir + "/one_" + kind;
    const std::string options = std::string(" --up y --profile ") + kind;
    CHECK(run("'" + dir + "/blk_####.vdb'" + options + " --profile-per frame --out '" + seq +
              "'") == 0,
          "%s: the sequence import failed", kind);
    CHECK(run("'" + dir + "/blk_0002.vdb'" + options + " --out '" + one + "'") == 0,
          "%s: the frame 2 import failed", kind);
    auto s = sections(seq + "/fog.ini"), o = sections(one + "/fog.ini");
    CHECK(s.count("box.0002") && s.count("fog.0002") && !s.count("box") && !s.count("fog"),
          "%s: no [box.0002] and [fog.0002] (or a [box] or [fog] for all frames)", kind);
    // floor and top: the frame's own (the sequence's origin and cell size may differ)
    auto height = [](const std::string &box) {
      std::string out;
      std::istringstream lines(box);
      for (std::string l; std::getline(lines, l);)
        if (!l.compare(0, 5, "floor") || !l.compare(0, 3, "top")) out += l + "\n";
      return out;
    };
    CHECK(height(s["box.0002"]) == height(o["box"]), "%s: frame 2's box\n%sagainst alone\n%s",
          kind, height(s["box.0002"]).c_str(), height(o["box"]).c_str());
    CHECK(s["fog.0002"] == o["fog"], "%s: frame 2's profile\n%sagainst alone\n%s", kind,
          s["fog.0002"].c_str(), o["fog"].c_str());
  }
  test_remove_tree(root);
  return test_finish("test_vdb_import_profile_per_frame");
}
