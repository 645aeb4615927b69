#!/bin/sh
# Packs what bench/gpu_check.sh needs on the device machine (a GPU, none of Debian's
# packages, no registry reachable) into build/gpu-kit, to be carried there:
#   bench/gpu_kit.sh            (here, after a build: make test or make demo)
#   device run, carry ["build/gpu-kit"]:  sh bench/gpu_check.sh
# The kit: fogpipe, the GL test binaries, and every shared library they load except
# glibc's, xz-packed (libopenvdb alone is 57 MB; the carry limit is 64 MiB). libstdc++ and
# libgcc_s go to a fallback folder that gpu_check.sh uses only where the machine lacks them.
set -eu
cd "$(dirname "$0")/.."
kit=build/gpu-kit
# GPU against the CPU references: the fog pass (every basis, LOD method, camera), far
# cameras, the marcher, reduced resolution, and the scene pass's distances
tests="test_gpu_fog_vs_cpu test_gpu_far_camera test_gpu_march_vs_cpu test_gpu_fog_resolution
  test_scene_distance test_gpu_volume_march test_gpu_lod_every_level_count"
for f in build/fogpipe $(for t in $tests; do echo build/tests/$t; done); do
  [ -x "$f" ] || { echo "gpu_kit: $f is missing: build first (make test)" >&2; exit 1; }
done
rm -rf "$kit" build/gpu-kit.tmp
# a failed copy or xz leaves neither the staging folder nor a partial kit behind
trap 'status=$?; rm -rf build/gpu-kit.tmp; [ $status -eq 0 ] || rm -rf "$kit"' EXIT
mkdir -p build/gpu-kit.tmp/bin build/gpu-kit.tmp/lib build/gpu-kit.tmp/fallback
cp build/fogpipe build/gpu-kit.tmp/bin/
for t in $tests; do cp build/tests/$t build/gpu-kit.tmp/bin/; done
ldd build/gpu-kit.tmp/bin/* | awk '$2 == "=>" && $3 ~ /^\// {print $3}' | sort -u |
  while read -r lib; do
    case $(basename "$lib") in
      libc.so* | libm.so* | libpthread.so* | libdl.so* | librt.so* | libresolv.so* | ld-linux*) ;;
      libstdc++.so* | libgcc_s.so*) cp -L "$lib" build/gpu-kit.tmp/fallback/ ;;
      *) cp -L "$lib" build/gpu-kit.tmp/lib/ ;;
    esac
  done
mkdir -p "$kit"
tar -C build/gpu-kit.tmp -cJf "$kit/kit.tar.xz" bin lib fallback
rm -rf build/gpu-kit.tmp
echo "gpu_kit: $kit/kit.tar.xz ($(du -h "$kit/kit.tar.xz" | cut -f1));" \
  "carry build/gpu-kit and run" \
  "sh bench/gpu_check.sh on the device machine"
