#!/usr/bin/env bash
# One task of a Slurm job array: renders one frame range of a fogpipe recording into a
# shared folder. Every frame is rendered exactly as one full run renders it (bit for bit,
# on nodes with the same fogpipe build and GL driver: docs/farm.md), so the ranges can run
# on any such machines, in any order, at the same time.
#
#   FOGPIPE=/opt/fogpipe/build/fogpipe CONFIG=shot01.ini FRAMES=240 CHUNK=24 \
#   OUT=/shared/renders/shot01 SIZE=1920x1080 \
#   sbatch --array=0-9 scripts/farm/slurm_record.sh        # 10 tasks = 240 / 24
#
# Task k renders frames k*CHUNK+1 .. min((k+1)*CHUNK, FRAMES). A task that is requeued or
# run again resumes its own range (--resume keeps the frames it already finished, after
# checking each one's identity and data). docs/farm.md has OpenCue and Deadline notes.
#SBATCH --job-name=fogpipe-record
#SBATCH --cpus-per-task=2
#SBATCH --output=fogpipe-record-%A_%a.log
set -euo pipefail

: "${FOGPIPE:?set FOGPIPE to the fogpipe binary}" "${CONFIG:?set CONFIG}" "${OUT:?set OUT}"
: "${FRAMES:?set FRAMES, the last frame of the shot}" "${CHUNK:=24}"
task=${SLURM_ARRAY_TASK_ID:?not run as a Slurm array task (sbatch --array=0-N)}
# Whole decimal numbers (bash reads 0240 as octal; 10# reads it as 240), FRAMES and CHUNK
# at least 1: a task with nothing to do must not pass as a finished one. At most 7 digits
# past leading zeros (record's frames end at 9999999): bash arithmetic wraps at 2^63, and
# FRAMES=18446744073709551617 read as 1 finished "frames 1-1".
for check in FRAMES:1 CHUNK:1 task:0; do
  name=${check%:*} min=${check#*:} value=${!name}
  if [[ ! $value =~ ^0*([0-9]{1,7})$ ]] || ((10#${BASH_REMATCH[1]} < min)); then
    echo "slurm_record.sh: $name='$value': expected a whole number from $min to 9999999" >&2
    exit 2
  fi
  printf -v "$name" '%d' "$((10#${BASH_REMATCH[1]}))"
done
first=$((task * CHUNK + 1))
last=$(((task + 1) * CHUNK))
((last > FRAMES)) && last=$FRAMES
if ((first > FRAMES)); then
  echo "task $task: frames start at $first, past the shot's $FRAMES: nothing to do"
  exit 0
fi
size=()
[[ -n "${SIZE:-}" ]] && size=(--size "$SIZE")
fps=()
[[ -n "${FPS:-}" ]] && fps=(--fps "$FPS")
echo "task $task: frames $first-$last of $FRAMES on $(hostname)"
# ${a[@]+"${a[@]}"}: an empty array under set -u is an error before bash 4.4 (CentOS 7's 4.2)
exec "$FOGPIPE" record "$CONFIG" --frames "$first-$last" --out "$OUT" ${size[@]+"${size[@]}"} \
  ${fps[@]+"${fps[@]}"} --resume
