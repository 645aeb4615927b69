#!/usr/bin/env bash
# Builds (when needed) and runs fogpipe's libFuzzer harnesses (docs/reliability.md, "Fuzzing").
#
#   tests/fuzz/run.sh TARGET|all SECONDS   fuzz each target for SECONDS (make fuzz: all, 60)
#   tests/fuzz/run.sh regressions          run every harness once over its seed corpus and
#                                          its regression inputs (quick; no fuzzing)
#
# TARGET: config fogmap_png fogmap_exr vdb uni options. Targets run one after another.
# Each fuzzing run works on a scratch copy of tests/fuzz/corpus/TARGET (the repository's
# corpus is never written), with tests/fuzz/regressions/TARGET as a second, read-only corpus,
# under -rss_limit_mb=2048 -timeout=10 -detect_leaks=1. What it finds goes to
# BUILD/artifacts/TARGET/ (crash-*, leak-*, timeout-*, oom-*), the log to BUILD/logs/.
#
# Environment: FUZZ_BUILD_DIR (default build-fuzz), FUZZ_JOBS (build jobs, default 2),
# FUZZ_RUNS (also stop after this many executions), FUZZ_FLAGS (more libFuzzer flags),
# FUZZ_TMPDIR (scratch space, default /dev/shm).
set -uo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/tests/fuzz
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
[[ $build == /* ]] || build=$root/$build
all_targets=(config fogmap_png fogmap_exr vdb uni options)

usage() {
  echo "usage: tests/fuzz/run.sh TARGET|all SECONDS | regressions" >&2
  echo "       TARGET: ${all_targets[*]}" >&2
  exit 2
}

dict_of() {
  case $1 in
    config) echo "$here/dict/config.dict" ;;
    fogmap_png) echo "$here/dict/png.dict" ;;
    fogmap_exr) echo "$here/dict/exr.dict" ;;
    vdb) echo "$here/dict/vdb.dict" ;;
    options) echo "$here/dict/options.dict" ;;
    *) echo "" ;;
  esac
}

build_targets() {
  if ! command -v clang >/dev/null 2>&1 || ! command -v clang++ >/dev/null 2>&1; then
    echo "fuzz: clang not found (Debian: apt-get install clang libclang-rt-14-dev, or make deps)" >&2
    exit 1
  fi
  if [[ ! -f $build/CMakeCache.txt ]]; then
    cmake -S "$here" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      >"$build.configure.log" 2>&1 || { cat "$build.configure.log" >&2; exit 1; }
    rm -f "$build.configure.log"
  fi
  local names=()
  for t in "$@"; do names+=("fuzz_$t"); done
  echo "fuzz: building ${names[*]} in $build"
  cmake --build "$build" -j "${FUZZ_JOBS:-2}" --target "${names[@]}" -- --no-print-directory \
    >"$build/build.log" 2>&1 || { tail -40 "$build/build.log" >&2; exit 1; }
}

# Known third-party leaks (lsan.supp says which and why); every other leak is a finding.
export LSAN_OPTIONS="suppressions=$here/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"

# Scratch space: tmpfs when there is one (the config harness writes its input for every run).
tmp_base=${FUZZ_TMPDIR:-/dev/shm}
[[ -d $tmp_base && -w $tmp_base ]] || tmp_base=${TMPDIR:-/tmp}
scratch=
cleanup() { [[ -n $scratch && -d $scratch ]] && rm -rf "$scratch"; }
trap cleanup EXIT

# What a failed run found, from its log.
classify() {
  local log=$1
  if grep -q "ERROR: libFuzzer: timeout" "$log"; then echo timeout
  elif grep -q "ERROR: libFuzzer: out-of-memory" "$log"; then echo out-of-memory
  elif grep -q "ERROR: LeakSanitizer" "$log"; then echo leak
  elif grep -q "ERROR: libFuzzer: fuzz target exited" "$log"; then echo exit
  else echo crash
  fi
}

stat_of() { sed -n "s/^stat::$1: *//p" "$2" | tail -1; }

fuzz_one() {
  local t=$1 seconds=$2
  scratch=$(mktemp -d "$tmp_base/fogpipe-fuzz-$t.XXXXXX")
  mkdir -p "$scratch/corpus" "$scratch/work" "$build/artifacts/$t" "$build/logs"
  cp "$here/corpus/$t"/* "$scratch/corpus/"
  local log=$build/logs/$t.log
  local args=(-rss_limit_mb=2048 -timeout=10 -detect_leaks=1 -max_total_time="$seconds"
              -close_fd_mask=3 -print_final_stats=1 -artifact_prefix="$build/artifacts/$t/")
  local dict
  dict=$(dict_of "$t")
  [[ -n $dict ]] && args+=(-dict="$dict")
  [[ -n ${FUZZ_RUNS:-} ]] && args+=(-runs="$FUZZ_RUNS")
  # shellcheck disable=SC2206
  [[ -n ${FUZZ_FLAGS:-} ]] && args+=($FUZZ_FLAGS)
  local corpora=("$scratch/corpus")
  [[ -d $here/regressions/$t ]] && corpora+=("$here/regressions/$t")
  local start end status
  start=$(date +%s.%N)
  FOGPIPE_FUZZ_TMP=$scratch/work "$build/fuzz_$t" "${args[@]}" "${corpora[@]}" >"$log" 2>&1
  status=$?
  end=$(date +%s.%N)
  local execs rate rss result line
  execs=$(stat_of number_of_executed_units "$log")
  rate=$(stat_of average_exec_per_sec "$log")
  rss=$(stat_of peak_rss_mb "$log")
  if [[ $status -eq 0 ]]; then
    result=ok
  else
    result="$(classify "$log"): $(sed -n 's/.*Test unit written to //p' "$log" | tail -1)"
    failed=1
  fi
  line=$(printf '%-11s %12s %9.0f %9s %8s  %s' "$t" "${execs:-?}" \
    "$(awk "BEGIN { print $end - $start }")" "${rate:-?}" "${rss:-?}" "$result")
  echo "$line"
  echo "$line" >>"$summary"
  cleanup
  scratch=
}

regressions() {
  local t files status any=0
  for t in "${all_targets[@]}"; do
    files=("$here/corpus/$t"/*)
    [[ -d $here/regressions/$t ]] && files+=("$here/regressions/$t"/*)
    scratch=$(mktemp -d "$tmp_base/fogpipe-fuzz-$t.XXXXXX")
    mkdir -p "$build/logs"
    FOGPIPE_FUZZ_TMP=$scratch "$build/fuzz_$t" -rss_limit_mb=2048 -timeout=10 -close_fd_mask=3 \
      "${files[@]}" >"$build/logs/$t.regressions.log" 2>&1
    status=$?
    cleanup
    scratch=
    if [[ $status -eq 0 ]]; then
      printf 'fuzz regressions: %-11s %4d inputs ok\n' "$t" "${#files[@]}"
    else
      printf 'fuzz regressions: %-11s FAILED (%s; log %s)\n' "$t" \
        "$(classify "$build/logs/$t.regressions.log")" "$build/logs/$t.regressions.log"
      sed -n 's/^Running: //p' "$build/logs/$t.regressions.log" | tail -1
      any=1
    fi
  done
  return $any
}

[[ $# -ge 1 ]] || usage
case $1 in
  regressions)
    [[ $# -eq 1 ]] || usage
    build_targets "${all_targets[@]}"
    regressions
    exit $?
    ;;
  all) targets=("${all_targets[@]}") ;;
  *)
    [[ " ${all_targets[*]} " == *" $1 "* ]] || usage
    targets=("$1")
    ;;
esac
[[ $# -eq 2 && $2 =~ ^[0-9]+$ ]] || usage
seconds=$2

build_targets "${targets[@]}"
failed=0
summary=$build/logs/summary.txt
mkdir -p "$build/logs"
: >"$summary"
printf '%-11s %12s %9s %9s %8s  %s\n' target executions seconds exec/s rss_mb result |
  tee -a "$summary"
for t in "${targets[@]}"; do fuzz_one "$t" "$seconds"; done
if [[ $failed -ne 0 ]]; then
  echo "fuzz: findings above (artifacts in $build/artifacts/); minimise one with" >&2
  echo "  $build/fuzz_TARGET -minimize_crash=1 -runs=10000 ARTIFACT, then add it to" >&2
  echo "  tests/fuzz/regressions/TARGET/ (docs/reliability.md)" >&2
fi
exit $failed
