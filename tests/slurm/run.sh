#!/usr/bin/env bash
# The Slurm test: a real single-node Slurm (munge, slurmctld, slurmd on localhost) runs
# examples/slurm/submit.sh with the built binary: an array of 4 shards, then the merge.
# The merged file must equal, byte for byte, the same sweep run in one process.
#
#   bash tests/slurm/run.sh target/release/touchdown
#
# It installs Slurm from Debian's packages, so it needs root and apt; where it has neither
# it says so and skips (exit 0). `.ci/run` runs it after the test suite.
set -euo pipefail
cd "$(dirname "$0")/../.."
BIN=$(realpath "${1:-target/release/touchdown}")
W=${SLURM_TEST_DIR:-/tmp/touchdown-slurm-test}
SHARDS=4
now() { date +%s.%N; }
skip() { echo "SKIPPED: the Slurm test: $*"; exit 0; }
T0=$(now)

[ -x "$BIN" ] || { echo "the Slurm test needs the built binary: no $BIN" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || skip "not root, so Slurm cannot be installed and started here"
command -v apt-get >/dev/null || skip "no apt-get to install Slurm with"
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
   || ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends \
           slurmctld slurmd slurm-client munge; } >"${W}.apt.log" 2>&1; then
    tail -n 5 "${W}.apt.log"
    skip "apt-get could not install slurmctld, slurmd, slurm-client and munge"
  fi
fi
T1=$(now)

rm -rf "$W"; mkdir -p "$W"/state "$W"/spool "$W"/run
chmod 0711 "$W"                    # munged wants its socket folder o+x
/usr/sbin/mungekey --create --keyfile="$W/munge.key"
cat > "$W/slurm.conf" <<CONF
ClusterName=touchdown-test
SlurmctldHost=localhost
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$W/munge.sock
StateSaveLocation=$W/state
SlurmdSpoolDir=$W/spool
SlurmctldPidFile=$W/slurmctld.pid
SlurmdPidFile=$W/slurmd.pid
SlurmctldLogFile=$W/slurmctld.log
SlurmdLogFile=$W/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
MailProg=/bin/true
SchedulerParameters=batch_sched_delay=0
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
NodeName=localhost CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$W/slurm.conf"

MUNGE_PID= CTLD_PID= SLURMD_PID= JOBS=
cleanup() {
  local rc=$?
  if [ "$rc" -ne 0 ]; then
    tail -n 15 "$W"/slurmctld.log "$W"/slurmd.log "$W"/run/*.log 2>/dev/null || true
    [ -n "$JOBS" ] && { scancel $JOBS; sleep 2; } 2>/dev/null || true
  fi
  [ -n "$CTLD_PID" ] && scontrol shutdown >/dev/null 2>&1 || true
  for p in $SLURMD_PID $CTLD_PID; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.2; done
    kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true
  done
  [ -n "$MUNGE_PID" ] && { kill "$MUNGE_PID" 2>/dev/null; wait "$MUNGE_PID" 2>/dev/null; } || true
  return "$rc"
}
trap cleanup EXIT

/usr/sbin/munged -F --socket="$W/munge.sock" --key-file="$W/munge.key" \
  --pid-file="$W/munged.pid" --log-file="$W/munged.log" --seed-file="$W/munged.seed" \
  >"$W/munged.stderr" 2>&1 &
MUNGE_PID=$!
timeout 10 bash -c "until [ -S '$W/munge.sock' ]; do sleep 0.1; done"
/usr/sbin/slurmctld -D >"$W/slurmctld.stderr" 2>&1 & CTLD_PID=$!
/usr/sbin/slurmd -D    >"$W/slurmd.stderr"    2>&1 & SLURMD_PID=$!
timeout 60 bash -c 'until sinfo -h -o %T 2>/dev/null | grep -qx idle; do sleep 0.5; done'
T2=$(now)

# The sweep: short flights, a sample count that does not divide by 4, more rows than one
# record batch.
printf '[simulation]\nt_max_s = 5.0\n' > "$W/short.toml"
SAMPLES=70001 SEED=7
"$BIN" sweep --scenario "$W/short.toml" --samples $SAMPLES --seed $SEED --quiet \
  --out "$W/single.arrow" >/dev/null 2>&1

out=$(SHARDS=$SHARDS SAMPLES=$SAMPLES SEED=$SEED SCENARIO="$W/short.toml" \
      TOUCHDOWN="$BIN" OUT_DIR="$W/run" examples/slurm/submit.sh)
echo "$out"
JOBS=$(echo "$out" | grep -o 'job [0-9]*' | awk '{print $2}' | tr '\n' ' ')
timeout 600 bash -c "while squeue -h -j ${JOBS// /,} 2>/dev/null | grep -q .; do sleep 1; done"
T3=$(now)

shards_ok=$(scontrol -o show job "${JOBS%% *}" | grep -c 'JobState=COMPLETED .* ExitCode=0:0' || true)
merge_ok=$(scontrol -o show job "$(echo $JOBS | awk '{print $2}')" | grep -c 'JobState=COMPLETED .* ExitCode=0:0' || true)
echo "shard tasks completed with exit 0: $shards_ok/$SHARDS; merge completed: $merge_ok/1"
[ "$shards_ok" -eq "$SHARDS" ] && [ "$merge_ok" -eq 1 ] || { echo "FAILED: a Slurm job did not complete" >&2; exit 1; }
cmp "$W/single.arrow" "$W/run/sweep.arrow" \
  || { echo "FAILED: the merged shards differ from the one-process sweep" >&2; exit 1; }
awk -v a="$T0" -v b="$T1" -v c="$T2" -v d="$T3" 'BEGIN {
  printf "Slurm test passed: %d shards merged equal the one-process sweep byte for byte (install %.1f s, start %.1f s, array and merge %.1f s)\n", 4, b-a, c-b, d-c }'
