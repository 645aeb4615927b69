#!/usr/bin/env bash
# Every benchmark stage of bench/stages.def has a smoke run in `make test`: its own
# tests/render/bench_STAGE.cmake (which checks its CSV rows too), or a row of the table
# below. A stage with neither fails this check, so a new stage gets one when it lands.
# A row's stage must run end to end at a smoke size: exit 0, the files it names written,
# and a last line `STAGE: key=value ...` whose values are numbers (the figures the README
# and the issues quote come from these lines). Sizes and frames are the smallest each
# accepts.
set -uo pipefail
bin=${FOGPIPE_BIN:?run through ctest}
root=$(mktemp -d /tmp/fogpipe-bench-XXXXXX)
trap 'rm -rf "$root"' EXIT

# stage | arguments (@OUT@: the stage's own scratch folder) | files expected under @OUT@
# Values that may be nan, as STAGE.KEY: soak's figures of frame 1,000 on (the smoke run
# is shorter), and transform's PyWavelets ratio where python3-pywt is not installed.
may_be_nan=' soak.rss_1k_mb soak.growth_mb soak.growth_per_1k_frames_kb
  soak.heap_growth_per_1k_frames_kb transform.speedup_vs_pywt '
table='
transform |  |
sim | --quick --rounds 1 |
pipeline | --size 64x36 --frames 5 |
soak | --size 32x18 --frames 20 |
import | --runs 1 --preview-runs 1 --images @OUT@ | fogpipe.png vdb_render.png
'

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

stages=$(sed -n 's/^FOG_BENCH(\([a-z_]*\),.*/\1/p' bench/stages.def)
[[ -n $stages ]] || { echo "FAIL: no FOG_BENCH lines in bench/stages.def"; exit 1; }
for stage in $stages; do
  row=$(grep -E "^$stage \|" <<< "$table")
  own=tests/render/bench_$stage.cmake
  if [[ -n $row && -f $own ]]; then
    fail "$stage: a row here and its own $own: one smoke run is enough"
    continue
  elif [[ -f $own ]]; then
    echo "$stage: its own smoke test, $own"
    continue
  elif [[ -z $row ]]; then
    fail "$stage: no smoke run (a row in tests/app/bench_stages_check.sh or $own)"
    continue
  fi
  out=$root/$stage
  args=$(cut -d'|' -f2 <<< "$row")
  files=$(cut -d'|' -f3 <<< "$row")
  start=$SECONDS
  # shellcheck disable=SC2086 # the arguments are words
  "$bin" bench $stage ${args//@OUT@/$out} > "$root/$stage.log" 2>&1
  rc=$?
  echo "$stage: exit $rc in $((SECONDS - start)) s"
  if ((rc != 0)); then
    tail -5 "$root/$stage.log"
    fail "$stage exited $rc"
    continue
  fi
  for f in $files; do
    [[ -s $out/$f ]] || fail "$stage: $f not written under --out"
  done
  last=$(tail -n 1 "$root/$stage.log")
  echo "  $last"
  if [[ $last != "$stage: "* ]]; then
    fail "$stage: the last line is not '$stage: key=value ...'"
    continue
  fi
  pairs=${last#"$stage: "}
  [[ -n $pairs ]] || fail "$stage: no key=value pairs"
  for pair in $pairs; do
    key=${pair%%=*} value=${pair#*=}
    if [[ $pair != *=* || -z $key ]]; then
      fail "$stage: '$pair' is not key=value"
    elif [[ $value == nan && " ${may_be_nan//$'\n'/ } " == *" $stage.$key "* ]]; then
      :
    elif ! [[ $value =~ ^-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?$ ]]; then
      fail "$stage: $key=$value is not a number"
    fi
  done
done
((failures == 0)) || { echo "$failures failure(s)"; exit 1; }
echo "every stage has its smoke run"
