#!/usr/bin/env bash
# Submits a sharded touchdown sweep to Slurm: an array of SHARDS tasks, then the merge,
# which runs once every task has succeeded. Prints the two job ids.
#
#   SHARDS=16 SAMPLES=1e7 TOUCHDOWN=$PWD/target/release/touchdown OUT_DIR=$PWD/run1 \
#     examples/slurm/submit.sh
#
# Settings: see sweep-array.sbatch; extra sbatch options (partition, account, time) go in
# SBATCH_OPTS, e.g. SBATCH_OPTS="--partition=short --time=00:30:00".
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
SHARDS=${SHARDS:-4}
export TOUCHDOWN=${TOUCHDOWN:-touchdown} SAMPLES=${SAMPLES:-1e6} OUT_DIR=${OUT_DIR:-$PWD}
export SCENARIO=${SCENARIO:-} SEED=${SEED:-}
mkdir -p "$OUT_DIR"
# shellcheck disable=SC2086 # SBATCH_OPTS is a list of options
array=$(sbatch --parsable ${SBATCH_OPTS:-} --array=0-$((SHARDS - 1)) \
        --output="$OUT_DIR/shard-%a.log" "$here/sweep-array.sbatch")
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTS:-} --dependency=afterok:"$array" --kill-on-invalid-dep=yes \
        --output="$OUT_DIR/merge.log" "$here/merge.sbatch")
echo "array job $array ($SHARDS shards), merge job $merge -> $OUT_DIR/sweep.arrow"
