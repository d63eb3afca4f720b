#!/usr/bin/env bash
# grip farm under a real SLURM: a one-node cluster in a temporary folder
# (scripts/slurm-one-node.sh) runs jobs/slurm/grip-farm.sbatch with a one-minute time limit on
# two ranks. Its first run is stopped by `scancel --signal=TERM` after its first commit and
# requeued by `scontrol requeue`; the second is stopped by the time limit's warning and
# requeues itself; the third, its limit lifted, completes the job. The dataset must then equal
# an uninterrupted run's but for the wall times (h5diff), pass `grip inspect` (every row against
# its checksum), and its journal must list every candidate exactly once.
#
#   test_slurm_farm.sh GRIP_EXECUTABLE SOURCE_DIR MPIEXEC
#
# Exit 77 (skipped) when SLURM, munge or h5diff is not installed, except under CI (the CI
# variable set), where scripts/install-deps.sh has installed them and their absence fails.
set -euo pipefail

usage="usage: test_slurm_farm.sh GRIP_EXECUTABLE SOURCE_DIR MPIEXEC"
grip=$(realpath "${1:?$usage}")
source_dir=$(realpath "${2:?$usage}")
mpiexec=${3:?$usage}
started=$SECONDS
export PATH=$PATH:/usr/sbin  # munged, slurmctld, slurmd (not on a user's PATH in Debian)

for program in munged slurmctld slurmd sbatch h5diff; do
  if ! command -v "$program" >/dev/null; then
    echo "$program is not installed (Debian's slurm-wlm, munge, hdf5-tools: scripts/install-deps.sh)"
    if [[ -n ${CI:-} ]]; then exit 1; fi
    echo "SKIPPED: the SLURM test did not run"
    exit 77
  fi
done

dir=$(mktemp -d -t grip_slurm_XXXXXX)
export SLURM_CONF=$dir/cluster/slurm.conf
passed=0
finish() {
  "$source_dir/scripts/slurm-one-node.sh" stop "$dir/cluster" || true
  if ((!passed)); then
    for f in "$dir"/job.out "$dir"/cluster/log/*.log; do
      [[ -f $f ]] && { echo "== $f"; tail -n 40 "$f"; }
    done
  fi
  rm -rf "$dir"
}
trap finish EXIT
trap "exit 143" TERM INT HUP
fail() {
  echo "FAILED: $*"
  exit 1
}

# The rigid cylinder's trials take 0.05 s, the soft capsules' (tet_edge 5 mm) 0.5 to 8 s each
# (on one core of the 2-core development machine): about 75 s of trials on two ranks, so that
# the one-minute time limit's warning, 10 to 40 s into a run (slurmctld checks time limits every
# 30 s), stops the run after the scancel's. At tet_edge 10 mm the job took 18 s and ended before
# the warning; a machine 1.8 times faster than that one could still do so, and the test then fails
# saying so.
cat >"$dir/job.toml" <<'EOF'
[job]
name = "slurm-test"
seed = 7

[[objects]]
category = "cylinder"

[[objects]]
category = "capsule"
count = 2
soft = true
tet_edge = 0.005

[[grippers]]
name = "parallel-jaw"
candidates = 20

[farm]
batch = 1
EOF
candidates=60

"$mpiexec" -np 2 --oversubscribe "$grip" farm "$dir/job.toml" --output "$dir/reference.h5" --threads 1 \
  >"$dir/reference.log" 2>&1 ||
  fail "the uninterrupted run failed: $(tail -n 5 "$dir/reference.log")"
reference_seconds=$((SECONDS - started))

"$source_dir/scripts/slurm-one-node.sh" start "$dir/cluster"

# Polls `condition` (a command) every 0.2 s for up to $1 s; fails with $2 when it never holds.
wait_until() {
  local seconds=$1 what=$2
  shift 2
  for _ in $(seq 1 $((seconds * 5))); do
    "$@" && return 0
    sleep 0.2
  done
  fail "$what (waited $seconds s)"
}
job_field() { scontrol show job -o "$job" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
# Candidates the journal lists as committed.
journaled() { awk '/^done /{n += NF - 2} END {print n + 0}' "$dir/dataset.h5.journal" 2>/dev/null || echo 0; }
has_commits() { (($(journaled) > 0)); }
state_is() { [[ $(job_field JobState) == "$1" ]]; }
# Whether the job completed; a job that timed out or was cancelled fails the test at once.
completed() {
  local state
  state=$(job_field JobState)
  case $state in
    TIMEOUT | CANCELLED | NODE_FAIL | OUT_OF_MEMORY) fail "the job ended $state" ;;
  esac
  [[ $state == COMPLETED ]]
}

job_started=$SECONDS
job=$(GRIP=$grip sbatch --parsable --time=1 --signal=B:USR1@50 --ntasks-per-node=2 \
  --cpus-per-task=1 --output="$dir/job.out" --chdir="$dir" \
  "$source_dir/jobs/slurm/grip-farm.sbatch" "$dir/job.toml" "$dir/dataset.h5")

# First run: SIGTERM to the ranks once a work unit is committed, well before the time limit's
# warning (which comes 10 s or more into a run).
wait_until 60 "no work unit was committed" has_commits
scancel --signal=TERM "$job"
wait_until 60 "the stopped run did not end" state_is FAILED
[[ $(job_field ExitCode) == 130:0 ]] ||
  fail "the run stopped by SIGTERM ended with $(job_field ExitCode), not 130 (stopped cleanly)"
committed=$(journaled)
((committed < candidates)) || fail "the job ended before the SIGTERM reached it"
echo "stopped by scancel --signal=TERM after $((SECONDS - job_started)) s, $committed candidates committed"
scontrol requeue "$job"

# The second run: the time limit's warning stops it and it requeues itself. The limit is then
# lifted, so that the last run completes and the test does not pay a requeue per minute.
time_limit_requeued() { grep -q 'requeued$' "$dir/job.out"; }
wait_until 200 "no run was stopped by the time limit's warning and requeued" time_limit_requeued
scontrol update JobId="$job" TimeLimit=10
wait_until 300 "the requeued job did not complete" completed
[[ $(job_field ExitCode) == 0:0 ]] || fail "the job ended with $(job_field ExitCode)"
job_seconds=$((SECONDS - job_started))
restarts=$(job_field Restarts)
limit_stops=$(grep -c 'requeued$' "$dir/job.out" || true)
((limit_stops > 0)) || fail "no run was stopped by the time limit's warning and requeued"
((restarts == limit_stops + 1)) ||
  fail "$restarts restarts, expected $((limit_stops + 1)) (one by scontrol, one per time-limit stop)"
# A stopped run exits 130 once its work units in flight are committed, or 143 when the stop
# came while it was still planning (nothing in flight, nothing written; on a loaded machine a
# run's planning can outlast the 10 s before the time limit's warning).
stopped_in_flight=$(grep -c 'grip exited with status 130' "$dir/job.out" || true)
stopped_planning=$(grep -c 'grip exited with status 143' "$dir/job.out" || true)
((stopped_in_flight + stopped_planning == restarts)) ||
  fail "a stopped run ended otherwise than 130 (work units in flight committed) or 143 (stopped while planning): $(grep 'grip exited' "$dir/job.out")"
(($(grep -c 'stopped before any trial ran; nothing was written' "$dir/job.out" || true) >= stopped_planning)) ||
  fail "a run exited 143 without saying it stopped before any trial ran: $(grep 'grip exited' "$dir/job.out")"
# Seconds from each time-limit warning to the limit (a run's start + 60 s): the ranks' grace.
warning_leads() {
  local line stamp start=0
  while IFS= read -r line; do
    stamp=$(date -d "$(cut -d ' ' -f 2 <<<"$line")" +%s)
    case $line in
      *": grip farm "*) start=$stamp ;;
      *"time limit near"*) printf ' %s' $((start + 60 - stamp)) ;;
    esac
  done < <(grep '^grip-farm.sbatch: ' "$dir/job.out")
}
echo "stopped $limit_stops time(s) by the time limit, warned$(warning_leads) s before it;" \
  "$restarts requeues; job done in $job_seconds s"

# Nothing lost, nothing written twice, the same records as the uninterrupted run.
"$grip" inspect "$dir/dataset.h5" >"$dir/inspect.log" 2>&1 || fail "grip inspect: $(cat "$dir/inspect.log")"
grep -q "candidates  $candidates ($candidates done, 0 pending)" "$dir/inspect.log" ||
  fail "not every candidate is done: $(grep candidates "$dir/inspect.log")"
ids=$(awk '/^done /{for (i = 3; i <= NF; ++i) print $i}' "$dir/dataset.h5.journal" | sort -n)
[[ $ids == "$(seq 0 $((candidates - 1)))" ]] ||
  fail "the journal does not list each candidate once: $(echo "$ids" | uniq -c | awk '$1 != 1' | head)"
# wall_time measures the run, and its checksum entry with it; grip inspect checked the rest.
h5diff -r --exclude-path /candidates/wall_time --exclude-path /candidates/checksum \
  "$dir/reference.h5" "$dir/dataset.h5" >"$dir/h5diff.log" 2>&1 ||
  fail "the dataset differs from the uninterrupted run's: $(grep -B3 -E '^[1-9][0-9]* differences found' "$dir/h5diff.log" | head -20)"

passed=1
echo "passed in $((SECONDS - started)) s (uninterrupted run $reference_seconds s, SLURM job $job_seconds s)"
