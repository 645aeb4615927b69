#!/usr/bin/env bash
# scripts/farm/slurm_record.sh as a Slurm job array runs it: three array tasks of 10
# frames (the last one short: 21-24) started at once, as SLURM_ARRAY_TASK_ID 0..2 with a
# fourth task past the shot's end, must give the files of one full 24-frame run, byte for
# byte, and nothing else. Then one task run again (a requeue) keeps its frames.
set -euo pipefail
bin=${FOGPIPE_BIN:?run through ctest}
root=$(mktemp -d /tmp/fogpipe-farm-XXXXXX)
trap 'rm -rf "$root"' EXIT
"$bin" record configs/default.ini --frames 24 --size 64x36 --out "$root/whole" > "$root/whole.log"
pids=()
for task in 0 1 2 3; do
  # the config by its absolute path, as a farm node reaches it: the frames must not depend
  # on how the config's path is spelt (their header holds the scene's fingerprint)
  FOGPIPE=$bin CONFIG=$PWD/configs/default.ini FRAMES=24 CHUNK=10 SIZE=64x36 OUT=$root/farm \
    SLURM_ARRAY_TASK_ID=$task bash scripts/farm/slurm_record.sh > "$root/task$task.log" 2>&1 &
  pids+=($!)
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
if ((status)); then cat "$root"/task*.log; echo "FAIL: an array task failed"; exit 1; fi
grep -q "nothing to do" "$root/task3.log" || { echo "FAIL: task 3 (past the end) rendered"; exit 1; }
diff <(ls -A "$root/whole") <(ls -A "$root/farm") || { echo "FAIL: the folders list different files"; exit 1; }
for f in "$root"/whole/*.exr; do
  cmp -s "$f" "$root/farm/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs"; exit 1; }
done
before=$(stat -c %Y "$root/farm/frame.0011.exr")
FOGPIPE=$bin CONFIG=configs/default.ini FRAMES=24 CHUNK=10 SIZE=64x36 OUT=$root/farm \
  SLURM_ARRAY_TASK_ID=1 bash scripts/farm/slurm_record.sh > "$root/requeue.log" 2>&1
grep -q "already complete" "$root/requeue.log" || { cat "$root/requeue.log"; echo "FAIL: a requeued task re-rendered its frames"; exit 1; }
[[ $(stat -c %Y "$root/farm/frame.0011.exr") == "$before" ]] || { echo "FAIL: frame 11 rewritten"; exit 1; }
# Bad numbers are refused, not read as octal or as an empty shot that "finished".
for bad in "FRAMES=0" "FRAMES=24x" "CHUNK=0" "FRAMES=18446744073709551617" "CHUNK=99999999999999999999"; do
  if env FOGPIPE=$bin CONFIG=configs/default.ini FRAMES=24 CHUNK=10 OUT=$root/bad "$bad" \
    SLURM_ARRAY_TASK_ID=0 bash scripts/farm/slurm_record.sh > "$root/bad.log" 2>&1; then
    echo "FAIL: $bad was accepted"; exit 1
  fi
  grep -q "expected a whole number" "$root/bad.log" || { cat "$root/bad.log"; echo "FAIL: $bad: no message"; exit 1; }
done
[[ ! -e $root/bad ]] || { echo "FAIL: a refused task made its folder"; exit 1; }
# FRAMES=0024 is 24 (not octal 20): task 2 renders 21-24 and says so.
FOGPIPE=$bin CONFIG=configs/default.ini FRAMES=0024 CHUNK=010 SIZE=64x36 OUT=$root/farm \
  SLURM_ARRAY_TASK_ID=2 bash scripts/farm/slurm_record.sh > "$root/octal.log" 2>&1
grep -q "frames 21-24 of 24" "$root/octal.log" || { cat "$root/octal.log"; echo "FAIL: 0024 not read as 24"; exit 1; }
echo "farm_script_check: 24 frames from 4 array tasks equal the full run byte for byte; a requeue keeps them"
