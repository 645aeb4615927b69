# The Debian packages the fogpipe libraries build on, found once for the main build and for
# the fuzz build (tests/fuzz/CMakeLists.txt). Each adds the GL and window packages after
# them (fogpipe_render); the main build also the panel's.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
pkg_check_modules(OPENEXR REQUIRED IMPORTED_TARGET OpenEXR)
pkg_check_modules(SPNG REQUIRED IMPORTED_TARGET spng)
pkg_check_modules(FFTW3F REQUIRED IMPORTED_TARGET fftw3f)
pkg_check_modules(INIH REQUIRED IMPORTED_TARGET inih)
# Debian's OpenVDB ships only a find module (docs/platform.md), in the multiarch folder
# (x86_64-linux-gnu, aarch64-linux-gnu, ...).
file(GLOB FOGPIPE_OPENVDB_MODULES /usr/lib/*/cmake/OpenVDB)
list(APPEND CMAKE_MODULE_PATH /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB
     ${FOGPIPE_OPENVDB_MODULES})
find_package(OpenVDB REQUIRED)
