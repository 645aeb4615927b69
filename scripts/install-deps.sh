#!/usr/bin/env bash
# Installs the Debian 12 packages fogpipe needs, and only the missing ones.
# Idempotent and quiet when everything is present; used by `make demo` and `make test`.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  # fogmaps and recordings: OpenEXR 3 C API, PNG
  libopenexr-dev libspng-dev
  # Mantaflow configs are gzip; the VDB pre-check decodes tree topology chunks (zip, blosc)
  zlib1g-dev libblosc-dev
  # simulation
  libfftw3-dev
  # VDB import (Debian's libopenvdb-dev misses boost headers), vdb_render for the bench
  libopenvdb-dev libboost-dev libboost-iostreams-dev libopenvdb-tools
  # rendering: headless EGL on Mesa llvmpipe, a GLFW window, the ImGui panel
  libegl-dev libopengl-dev libgl1-mesa-dri libegl-mesa0 libglfw3-dev libimgui-dev
  # scene configs
  libinih-dev
  # references used only by tests and benchmarks: GSL, PyWavelets (Debian's python3)
  libgsl-dev python3 python3-numpy python3-pywt
  # speed/accuracy charts (CSV -> PNG)
  gnuplot-nox
  # screenshots of the real window without a display; XTest keys for the window's tests
  xvfb xauth libxtst6
  # fuzzing (make fuzz): clang and its libFuzzer/sanitizer runtimes (only recommended by clang)
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  [[ $p == \#* ]] && continue
  # one line per installed architecture ("ii" installed, "hi" installed and held): the full
  # ${Status} of a package held, or installed for two architectures (i386 multiarch), read
  # as missing, and every run asked sudo again
  status=$(dpkg-query -W -f='${db:Status-Abbrev}\n' "$p" 2>/dev/null || true)
  [[ $status =~ (^|$'\n')[ih]i ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "install-deps: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then sudo=(sudo); else
    echo "install-deps: not root and no sudo; install these packages first: ${missing[*]}" >&2
    exit 1
  fi
  # sudo asking for a password with no terminal to ask on failed as "apt-get update
  # failed (no network...)": say what it is
  if ! sudo -n true 2>/dev/null && ! [[ -t 0 ]]; then
    echo "install-deps: sudo needs a password and there is no terminal to ask on; run" \
         "'sudo apt-get install ${missing[*]}' first (or make from a terminal)" >&2
    exit 1
  fi
fi
if ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: apt-get not found; fogpipe's set-up expects Debian 12. Missing: ${missing[*]}" >&2
  exit 1
fi
# through env: sudo's default policy drops the caller's environment, and a debconf question
# (libc6's restart prompt) would wait, unseen behind the silenced output
apt=(env DEBIAN_FRONTEND=noninteractive apt-get)
"${sudo[@]}" "${apt[@]}" update -qq ||
  { echo "install-deps: apt-get update failed (no network to the Debian mirror?)" >&2; exit 1; }
"${sudo[@]}" "${apt[@]}" install -y -qq --no-install-recommends "${missing[@]}" >/dev/null \
  || { echo "install-deps: apt-get install failed for: ${missing[*]}" >&2; exit 1; }
echo "install-deps: done"
