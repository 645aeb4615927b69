#!/bin/sh
# The device machine's one prepared run (see bench/gpu_kit.sh): on a real GPU, the kit's GL
# tests (GPU against the double-precision CPU references, pixel by pixel) and the render,
# pipeline, models and light benches, their outputs copied to $OUT. Run from the repository
# root with build/gpu-kit carried; 11 minutes on llvmpipe here (2026-12-06), far less on a GPU.
set -u
out=${OUT:-build/gpu-check}
mkdir -p "$out"
kit=${TMPDIR:-/tmp}/fogpipe-gpu-kit # not under build/gpu-kit: that is carried
rm -rf "$kit" && mkdir -p "$kit" && tar -C "$kit" -xJf build/gpu-kit/kit.tar.xz || exit 1
lib=$kit/lib
for f in libstdc++.so.6 libgcc_s.so.1; do
  ldconfig -p | grep -q "$f" || lib=$lib:$kit/fallback
done
export LD_LIBRARY_PATH=$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
# the NVIDIA driver's GLVND vendor file (device README); the kit brings the loader
v=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f "$v" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$v
# the benches read data/ and configs/ under the source path compiled into the kit
src=$(grep -a -o -m1 '/[[:alnum:]_./-]*/configs/default.ini' "$kit/bin/fogpipe" | head -n 1 |
  sed 's,/configs/default.ini$,,')
[ -n "$src" ] && [ ! -e "$src" ] && mkdir -p "$(dirname "$src")" && ln -s "$PWD" "$src"
{
  date
  nvidia-smi -L 2>&1
  ldd "$kit/bin/fogpipe" | grep "not found" || echo "libraries: all found"
  echo "EGL vendor file: ${__EGL_VENDOR_LIBRARY_FILENAMES:-none (GLVND's default folders)}"
  ldconfig -p | grep -E 'libEGL_nvidia|libGLX_nvidia|libEGL_mesa' || echo "no EGL vendor library"
} >"$out/machine.txt" 2>&1
cat "$out/machine.txt"
for test in "$kit"/bin/test_*; do
  t=$(basename "$test")
  "$test" >"$out/$t.txt" 2>&1
  echo "$t: exit $? ($(tail -n 1 "$out/$t.txt"))"
done
"$kit/bin/fogpipe" bench render --frames 20 >"$out/bench_render.txt" 2>&1
echo "bench render: exit $?"; grep -E '^GL:|^render:' "$out/bench_render.txt"
cp build/bench/render/render.csv build/bench/render/render_chart.png "$out/" 2>/dev/null
"$kit/bin/fogpipe" bench pipeline >"$out/bench_pipeline.txt" 2>&1
echo "bench pipeline: exit $?"; grep -E '^GL|^pipeline:' "$out/bench_pipeline.txt"
# the analytic models and the plume volume (its VDB is read from ../shared where present)
"$kit/bin/fogpipe" bench models >"$out/bench_models.txt" 2>&1
echo "bench models: exit $?"; grep -E '^GL|^models:' "$out/bench_models.txt"
cp build/bench/models/models.csv build/bench/models/models_chart.png "$out/" 2>/dev/null
# the sun's light in the fog: ours, marching and the froxel grid side by side (issue 15's
# figures B and C are limited by llvmpipe's costs; this is where a GPU would show them)
"$kit/bin/fogpipe" bench light >"$out/bench_light.txt" 2>&1
echo "bench light: exit $?"; grep -E '^GL|^light:' "$out/bench_light.txt"
cp build/bench/light/light.csv build/bench/light/light_chart.png "$out/" 2>/dev/null
