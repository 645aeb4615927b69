// A VDB sequence whose first and last frames hold an empty density grid (a cache's frames
// before the smoke is emitted and after it is gone: Mantaflow writes the grid with no
// active voxels). `fogpipe import` and a scene's [fog] vdb play them as frames without fog:
// their fogmaps are 0, and the sequence's fogmap grid is the footprint of the frames with
// fog (an empty frame has none: it did not widen the grid). A sequence whose every frame is
// empty, and a single empty file, are refused naming the grid. A frame whose voxels are all
// 0 is one without fog too, and `model = volume` plays both as no fog. Before, the first
// empty frame stopped the whole import ("grid 'density' is empty"). `fogpipe fit` over the
// frames: an empty one leaves the domain as it was; all empty, refused. With
// --skip-missing over frames 1, 2 and 9, the empty frame 2 takes frame 1's profile (the
// nearest by number, not by place in the list). (C++ to write the grids.)
#include <openvdb/openvdb.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

extern "C" {
#include "sim/sim.h" /* fogmap.h has no C++ guard of its own */
}
#include "test_util.h"

static std::string dir;

/* x0 < 0: no active voxel; else a 4^3 blob of `value` from index x0 along x, y0 along y,
 * times 1 + rise j at its j-th layer up */
static void write_frame(const std::string &path, int x0, float value = 1.0f, int y0 = 20,
                        float rise = 0.0f) {
  openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create();
  g->setName("density");
  g->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
  for (int i = 0; i < 4 && x0 >= 0; i++)
    for (int j = 0; j < 4; j++)
      for (int k = 0; k < 4; k++)
        g->tree().setValue(openvdb::Coord(x0 + i, y0 + j, 30 + k), value * (1.0f + rise * j));
  openvdb::GridPtrVec grids;
  grids.push_back(g);
  openvdb::io::File(path).write(grids);
}

// Runs a shell command, its stdout and stderr into out; the exit status.
static int run(const std::string &command, std::string &out) {
  out.clear();
  FILE *p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, p)) out += buffer;
  const int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static double fogmap_sum(const std::string &path, int *width) {
  fogmap map{};
  fog_error err{};
  if (fogmap_load(path.c_str(), nullptr, &map, &err)) {
    CHECK(false, "%s", err.message);
    return -1;
  }
  double sum = 0;
  for (int i = 0; i < map.width * map.height; i++) sum += map.density[i];
  *width = map.width;
  fogmap_destroy(&map);
  return sum;
}

int main() {
  const char *bin = getenv("FOGPIPE_BIN");
  CHECK(bin != nullptr, "FOGPIPE_BIN is not set (run through ctest)");
  char tmpl[] = "/tmp/test_vdb_empty_XXXXXX";
  if (!bin || !mkdtemp(tmpl)) return test_finish("test_vdb_empty_frames");
  dir = tmpl;
  openvdb::initialize();
  // frames 1 and 4 empty; 2 and 3 a 4^3 blob of density 1, the second 2 voxels further in x
  mkdir((dir + "/seq").c_str(), 0755);
  write_frame(dir + "/seq/s_0001.vdb", -1);
  write_frame(dir + "/seq/s_0002.vdb", 10);
  write_frame(dir + "/seq/s_0003.vdb", 12);
  write_frame(dir + "/seq/s_0004.vdb", -1);
  write_frame(dir + "/seq/s_0005.vdb", 0, 0.0f); /* active voxels, all 0: no fog either */
  std::string out;
  const std::string import = std::string("'") + bin + "' import '" + dir +
                             "/seq/s_####.vdb' --config none --up y --out '" + dir + "/out'";
  int status = run(import, out);
  CHECK(status == 0, "import of a sequence with empty frames (%d): %s", status, out.c_str());
  CHECK(out.find("no fog in 3 frames (grid 'density' empty or all 0): 1 4 5") !=
            std::string::npos,
        "the empty frames are not named: %s", out.c_str());
  if (status == 0) {
    int widths[5] = {0, 0, 0, 0, 0};
    double sums[5];
    for (int f = 0; f < 5; f++) {
      char name[64];
      snprintf(name, sizeof name, "/out/fog.%04d.exr", f + 1);
      sums[f] = fogmap_sum(dir + name, &widths[f]);
    }
    CHECK(sums[0] == 0 && sums[3] == 0 && sums[4] == 0, "the empty frames' fogmaps hold %g, "
          "%g and %g", sums[0], sums[3], sums[4]);
    CHECK(sums[1] > 0 && sums[2] > 0 && fabs(sums[1] - sums[2]) < 1e-5 * sums[1],
          "the blob's frames hold %g and %g (the same blob, moved)", sums[1], sums[2]);
    // the footprint of the blobs: x 1.0 .. 1.6 at the native 0.1 (an empty frame's voxel at
    // index 0 would have stretched it to 16 cells)
    CHECK(widths[0] == 6 && widths[1] == 6, "the sequence's fogmap is %d cells wide, expected "
          "6 (the blobs' footprint alone)", widths[1]);
  }
  // --skip-missing over frames 1, 2 (empty) and 9, each its own profile: frame 2 takes
  // frame 1's, the nearest by number (it took 9's, as near in the list)
  {
    mkdir((dir + "/gap").c_str(), 0755);
    write_frame(dir + "/gap/g_0001.vdb", 10, 1.0f, 20); /* even */
    write_frame(dir + "/gap/g_0002.vdb", -1);
    write_frame(dir + "/gap/g_0009.vdb", 10, 1.0f, 20, 3.0f); /* denser upward */
    const std::string gap = std::string("'") + bin + "' import '" + dir +
                            "/gap/g_####.vdb' --config none --up y --skip-missing "
                            "--profile-per frame --out '" + dir + "/gap_out'";
    status = run(gap, out);
    CHECK(status == 0, "import of frames 1, 2, 9 (%d): %s", status, out.c_str());
    std::string sidecar, line;
    FILE *f = fopen((dir + "/gap_out/fog.ini").c_str(), "r");
    char buffer[4096];
    while (f && fgets(buffer, sizeof buffer, f)) sidecar += buffer;
    if (f) fclose(f);
    // each frame's section's profile line
    auto profile_of = [&](const char *section) {
      const size_t at = sidecar.find(section);
      if (at == std::string::npos) return std::string();
      const size_t key = sidecar.find("profile_coefficients", at);
      return key == std::string::npos ? std::string()
                                      : sidecar.substr(key, sidecar.find('\n', key) - key);
    };
    const std::string one = profile_of("[fog.0001]"), two = profile_of("[fog.0002]"),
                      nine = profile_of("[fog.0009]");
    CHECK(!one.empty() && one != nine && two == one,
          "frame 2's profile '%s', frame 1's '%s', frame 9's '%s'", two.c_str(), one.c_str(),
          nine.c_str());
  }
  // fit over the frames: an empty frame adds nothing to the domain (its one zero voxel at
  // index 0 stretched it 3.4 times a side), and frames that are all empty are refused (a
  // linear fog past the domain, or homogeneous fog of 0, was chosen)
  {
    std::string domains[2];
    const char *ranges[2] = {"2-3", "1-3"};
    for (int i = 0; i < 2; i++) {
      const std::string fit = std::string("'") + bin + "' fit '" + dir +
                              "/seq/s_####.vdb' --frames " + ranges[i] +
                              " --tolerance 0.05 --rays 4 --samples 8 --size 16x9 --timed 1";
      status = run(fit, out);
      const size_t at = out.find("domain [");
      CHECK(status == 0 && at != std::string::npos, "fit --frames %s (%d): %s", ranges[i],
            status, out.c_str());
      if (at != std::string::npos) domains[i] = out.substr(at, out.find(';', at) - at);
    }
    CHECK(!domains[0].empty() && domains[0] == domains[1],
          "fit's domain over frames 2-3 '%s', over 1-3 '%s'", domains[0].c_str(),
          domains[1].c_str());
    const std::string empty_fit = std::string("'") + bin + "' fit '" + dir +
                                  "/seq/s_####.vdb' --frames 4-5 --tolerance 0.05 --rays 4 "
                                  "--samples 8 --size 16x9 --timed 1";
    status = run(empty_fit, out);
    CHECK(status == 1 && out.find("every frame's grid is empty") != std::string::npos &&
              out.find("chosen") == std::string::npos,
          "fit over empty frames 4-5 (%d): %s", status, out.c_str());
  }
  // an empty frame with a quadric volume beside it has fog: fitted, its domain the
  // sphere's box (the empty grid adds nothing)
  {
    const std::string scene = dir + "/quadric_beside.ini";
    FILE *f = fopen(scene.c_str(), "w");
    if (f) {
      fprintf(f, "[fog]\nmodel = volume\nvdb = %s/seq/s_####.vdb\nvdb_frame = 1\nvdb_up = y\n"
              "quadric = sphere 5 6 -7 2 0.3\n", dir.c_str());
      fclose(f);
    }
    status = run(std::string("'") + bin + "' fit '" + scene +
                     "' --tolerance 0.05 --rays 4 --samples 8 --size 16x9 --timed 1",
                 out);
    CHECK(status == 0 && out.find("domain [3, 7] x [4, 8] x [-9, -5]") != std::string::npos,
          "an empty frame beside a sphere (%d): %s", status, out.c_str());
  }
  // a scene playing the sequence as a fogmap and as a volume: its empty frames 1 and 4 look
  // alike (no fog), frame 2 (fog) does not; the camera looks at the blob
  for (int volume = 0; volume < 2; volume++) {
    std::string images[3];
    const int shown[3] = {1, 4, 2};
    for (int i = 0; i < 3; i++) {
      const std::string scene = dir + "/scene.ini";
      images[i] = dir + "/scene_" + std::to_string(i) + ".png";
      FILE *f = fopen(scene.c_str(), "w");
      if (f) {
        fprintf(f, "[camera]\nposition = 1.3 2.2 -1\nlook_at = 1.3 2.2 3.2\n"
                "[fog]\n%svdb = %s/seq/s_####.vdb\nvdb_up = y\nvdb_frame = %d\n"
                "density_scale = 40\n",
                volume ? "model = volume\n" : "", dir.c_str(), shown[i]);
        fclose(f);
      }
      status = run(std::string("'") + bin + "' render '" + scene + "' --size 32x18 --out '" +
                       images[i] + "'", out);
      CHECK(status == 0, "a %s scene at frame %d of the sequence (%d): %s",
            volume ? "volume" : "fogmap", shown[i], status, out.c_str());
    }
    std::string same, differ;
    run("cmp -s '" + images[0] + "' '" + images[1] + "' && echo same", same);
    run("cmp -s '" + images[0] + "' '" + images[2] + "' || echo differ", differ);
    CHECK(same == "same\n" && differ == "differ\n", "%s: frames 1 and 4 %s, frames 1 and 2 "
          "%s", volume ? "volume" : "fogmap", same.empty() ? "differ" : "look alike",
          differ.empty() ? "look alike (the blob not seen?)" : "differ");
  }
  // every frame empty: refused naming the grid, nothing written
  mkdir((dir + "/none").c_str(), 0755);
  write_frame(dir + "/none/s_0001.vdb", -1);
  write_frame(dir + "/none/s_0002.vdb", -1);
  status = run(std::string("'") + bin + "' import '" + dir +
                   "/none/s_####.vdb' --config none --up y --out '" + dir + "/out_none'",
               out);
  CHECK(status != 0 && out.find("every frame's grid 'density' is empty") != std::string::npos,
        "a sequence of empty frames (%d): %s", status, out.c_str());
  struct stat st;
  CHECK(stat((dir + "/out_none").c_str(), &st) != 0, "the refused import left its --out");
  // one empty file: still an error
  status = run(std::string("'") + bin + "' import '" + dir +
                   "/none/s_0001.vdb' --config none --up y --out '" + dir + "/out_one'",
               out);
  CHECK(status != 0 && out.find("is empty") != std::string::npos, "one empty file (%d): %s",
        status, out.c_str());
  // one file whose voxels are all 0: the error says the grid holds no fog (it said only
  // "cannot fit a vertical profile: total mass 0")
  status = run(std::string("'") + bin + "' import '" + dir +
                   "/seq/s_0005.vdb' --config none --up y --out '" + dir + "/out_zero'",
               out);
  CHECK(status != 0 && out.find("active voxels are all 0: the grid holds no fog") !=
                           std::string::npos,
        "one file of zeros (%d): %s", status, out.c_str());
  std::string cmd = "rm -rf '" + dir + "'";
  if (system(cmd.c_str()) != 0) fprintf(stderr, "could not remove %s\n", dir.c_str());
  return test_finish("test_vdb_empty_frames");
}
