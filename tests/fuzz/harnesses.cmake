# The libFuzzer harnesses: each one's sources and libraries, in one place for the two builds
# that compile them:
#  - tests/fuzz/CMakeLists.txt: with clang and libFuzzer (make fuzz, make fuzz-regressions);
#  - tests/CMakeLists.txt: with the ordinary compiler and replay_main.c in place of
#    libFuzzer, run by ctest over the corpus and regression inputs, so a harness that no
#    longer compiles or links (a command gained a call the harness does not provide) fails
#    make test, not only CI's fuzz step.
# Paths are relative to the repository root (FOGPIPE_ROOT), harness files to tests/fuzz/.
set(FOGPIPE_FUZZ_HARNESSES config fogmap_png fogmap_exr vdb uni options)

# Scene configs: app/config.c alone, not all of fogpipe_app (commands, pipeline, panel).
# It checks model keys against the renderer's model table and calls the camera and light
# maths, so it links fogpipe_render (the linker takes only the objects it needs from it).
set(FOGPIPE_FUZZ_config_SOURCES tests/fuzz/fuzz_config.c app/config.c)
set(FOGPIPE_FUZZ_config_LIBS fogpipe_render fogpipe_sim PkgConfig::INIH m)
# Fogmaps: PNG (libspng, from memory) and EXR (OpenEXR Core, from a file), each through
# the same checks as fogmap_load.
set(FOGPIPE_FUZZ_fogmap_png_SOURCES tests/fuzz/fuzz_fogmap_png.c)
set(FOGPIPE_FUZZ_fogmap_png_LIBS fogpipe_sim)
set(FOGPIPE_FUZZ_fogmap_exr_SOURCES tests/fuzz/fuzz_fogmap_exr.c)
set(FOGPIPE_FUZZ_fogmap_exr_LIBS fogpipe_sim)
# OpenVDB: vdb_precheck_file, then vdb_list_grids and vdb_read_dense (OpenVDB itself is
# Debian's build: not instrumented, but ASan and LeakSanitizer see its allocations).
set(FOGPIPE_FUZZ_vdb_SOURCES tests/fuzz/fuzz_vdb.c)
set(FOGPIPE_FUZZ_vdb_LIBS fogpipe_vdb)
# Mantaflow config_####.uni (gzip).
set(FOGPIPE_FUZZ_uni_SOURCES tests/fuzz/fuzz_uni.c)
set(FOGPIPE_FUZZ_uni_LIBS fogpipe_sim)
# Command-line options: the parsers of the commands that have a separable parse stage
# (fuzz_options.c says which and why).
set(FOGPIPE_FUZZ_options_SOURCES tests/fuzz/fuzz_options.c tests/fuzz/fuzz_options_import.c
    tests/fuzz/fuzz_options_design.c app/cli.c app/cli_options.c app/out_folder.c
    app/staged_move.c app/stop_signals.c)
set(FOGPIPE_FUZZ_options_LIBS fogpipe_vdb m)
