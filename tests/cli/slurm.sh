#!/usr/bin/env bash
# A real farm scheduler: Slurm (Debian's slurm-wlm and munge, installed when missing) as a
# one-node cluster on this machine, in a temporary folder: munged, slurmctld and slurmd, no
# systemd. A 24-frame shot (data/elbow's frames over and over, as an OBJ sequence and as one PC2
# point cache) is submitted as `sbatch --array=1-24:10` (tasks_script: tests/cli/slurm_task.sh,
# the README's submission), then a job joining the cache chunks, `--dependency=afterok` on the
# array. Checked: every job completes, within a bounded wait; the OBJ sequence and the joined
# cache are byte-identical to one local run. Then a task is cancelled (scancel) mid-run: it
# leaves no output and no temporary file; resubmitted, the joined cache is still the local
# run's. Every daemon started here is stopped by its pid.
# Needs root (slurmd starts jobs; apt-get installs). Exits 77 (skipped), saying why, where it
# cannot set the cluster up; with SKINSLIDE_REQUIRE_SHARED=1 (CI) that is a failure instead.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/slurm.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
# Checked before anything is installed, started or submitted: with SKINSLIDE unset the jobs
# would run and fail minutes later (a `${SKINSLIDE:?}` inside $(...) ends only the subshell).
# shellcheck source=require.sh
. "$root/tests/cli/require.sh"
require_program SKINSLIDE
require_tools /usr/bin/python3
bin=$(readlink -f "$SKINSLIDE")
export SKINSLIDE=$bin
shot_frames=24
chunk=10
wait_seconds=180  # a bound on every wait for the cluster: jobs here take a few seconds
failed=0
passed=0

# shellcheck source=cannot.sh
. "$(dirname "$0")/cannot.sh"

check() {
  local what=$1
  shift
  if "$@" >"$tmp/check.out" 2>&1; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $what" >&2
    sed 's/^/    /' "$tmp/check.out" >&2
  fi
}

[ "$(id -u)" -eq 0 ] || cannot "slurm.sh needs root: slurmd starts the jobs, apt-get installs slurm-wlm"
for tool in munged slurmctld slurmd sbatch squeue scancel scontrol; do
  if ! command -v "$tool" >/dev/null; then
    install_or_cannot slurm-wlm munge
    break
  fi
done

# munged wants every folder on its socket's path searchable by all (mktemp's is not).
tmp=$(mktemp -d /tmp/skinslide-slurm.XXXXXX)
chmod 755 "$tmp"
mkdir -p "$tmp/key" "$tmp/run" "$tmp/log" "$tmp/state" "$tmp/spool"
chmod 700 "$tmp/key"
pids=()

stop_cluster() {
  if [ -S "$tmp/run/munge.socket" ] && [ -n "${SLURM_CONF:-}" ]; then
    local jobs
    jobs=$(squeue -h -o %i 2>/dev/null | tr '\n' ' ')
    [ -n "$jobs" ] && scancel $jobs 2>/dev/null
    for ((i = 0; i < 30 && $(squeue -h 2>/dev/null | wc -l) > 0; i++)); do sleep 0.5; done
  fi
  # Reverse order: slurmd, slurmctld, munged; each by the pid it was started with.
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    kill "${pids[i]}" 2>/dev/null
    wait "${pids[i]}" 2>/dev/null
  done
  rm -rf "$tmp"
}
trap stop_cluster EXIT

# Two free TCP ports for slurmctld and slurmd.
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
for ((try = 0; try < 50; try++)); do
  port=$((20000 + RANDOM % 30000))
  port_free "$port" && port_free $((port + 1)) && break
done

# --- the cluster ----------------------------------------------------------------------------------
dd if=/dev/urandom of="$tmp/key/munge.key" bs=1024 count=1 2>/dev/null
chmod 600 "$tmp/key/munge.key"
munged -F --key-file="$tmp/key/munge.key" --socket="$tmp/run/munge.socket" \
  --pid-file="$tmp/run/munged.pid" --seed-file="$tmp/run/munged.seed" \
  --log-file="$tmp/log/munged.log" >"$tmp/log/munged.out" 2>&1 &
pids+=($!)
for ((i = 0; i < 40; i++)); do
  [ -S "$tmp/run/munge.socket" ] && break
  sleep 0.25
done
[ -S "$tmp/run/munge.socket" ] || cannot "munged did not start: $(tail -n 1 "$tmp/log/munged.out")"

node=$(hostname -s)
cat >"$tmp/slurm.conf" <<EOF
ClusterName=skinslide
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/run/munge.socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/run/slurmctld.pid
SlurmdPidFile=$tmp/run/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerParameters=sched_interval=1
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
KillWait=5
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=shots Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$tmp/slurm.conf
slurmctld -D -f "$SLURM_CONF" >"$tmp/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$tmp/log/slurmd.out" 2>&1 &
pids+=($!)
for ((i = 0; i < 120; i++)); do
  [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && break
  sleep 0.5
done
if [ "$(sinfo -h -o %T 2>/dev/null)" != idle ]; then
  tail -n 5 "$tmp/log/slurmctld.log" "$tmp/log/slurmd.log" >&2
  cannot "the one-node Slurm cluster did not come up (node: $(sinfo -h -o %T 2>&1))"
fi
echo "slurm: $(sinfo -V), node $node idle, ports $port-$((port + 1))"

# --- the shot ---------------------------------------------------------------------------------
shot=$tmp/shot
mkdir -p "$shot/frames"
cp "$root/data/elbow/bind.obj" "$root/data/elbow/patch.txt" "$shot/"
mapfile -t sample < <(ls "$root"/data/elbow/frames/*.obj)
for ((f = 1; f <= shot_frames; f++)); do
  ln -s "${sample[$(((f - 1) % ${#sample[@]}))]}" "$shot/frames/$(printf 'arm.%04d.obj' "$f")"
done
# The same frames as a PC2 point cache (frames 1-24), written as Blender's exporter writes one.
/usr/bin/python3 "$(dirname "$0")/objs_to_pc2.py" "$shot/shot.pc2" "$shot"/frames/*.obj

slide() { "$bin" -q -j 2 --patch "$shot/patch.txt" "$shot/bind.obj" "$@"; }
check "one local run of the OBJ sequence" slide -o "$tmp/local/obj" "$shot"/frames/*.obj
check "one local run of the cache" slide -o "$tmp/local/pc2" "$shot/shot.pc2"

# wait_jobs ID...: until none of the jobs is pending or running, at most wait_seconds.
wait_jobs() {
  local ids
  ids=$(IFS=,; echo "$*")
  for ((i = 0; i < 2 * wait_seconds; i++)); do
    [ -z "$(squeue -h -j "$ids" -o %i 2>/dev/null)" ] && return 0
    sleep 0.5
  done
  echo "jobs $ids still queued after ${wait_seconds} s:" >&2
  squeue >&2
  return 1
}

# The state of every task of job ID, one "task state" line each.
job_states() {
  scontrol -o show job "$1" | sed -E 's/.*ArrayTaskId=([0-9]+).*JobState=([A-Z_]+).*/\1 \2/; s/^JobId=.*JobState=([A-Z_]+).*/- \1/'
}

# no_temporaries DIR: no .NAME.tmp.XXXXXX left by a write.
no_temporaries() { [ -z "$(find "$1" -name '.*.tmp.*')" ] || { find "$1" -name '.*.tmp.*'; return 1; }; }
same_tree() { [ "$(find "$2" -type f | wc -l)" -eq "$3" ] && diff -r "$1" "$2"; }

# --- an array job and a dependent join ------------------------------------------------------------
task=$root/tests/cli/slurm_task.sh
cd "$tmp"
start=$(date +%s)
array=$(sbatch --parsable --array=1-$shot_frames:$chunk -c 1 -o "$tmp/log/task.%A_%a.out" \
  "$task" "$tmp/farm" "$shot_frames" "$shot")
join=$(sbatch --parsable --dependency=afterok:"$array" -o "$tmp/log/join.%j.out" \
  --wrap "'$bin' join -o '$tmp/farm/pc2' '$tmp/farm/pc2'/shot.*-*.pc2")
check "the array and the join finish within ${wait_seconds} s" wait_jobs "$array" "$join"
check "every task completed" test "$(job_states "$array" | sort -n)" = "$(printf '1 COMPLETED\n11 COMPLETED\n21 COMPLETED')"
check "the join completed" test "$(job_states "$join")" = "- COMPLETED"
check "the tasks wrote chunks 1-10, 11-20 and 21-24 (the last one clamped)" test \
  "$(cd "$tmp/farm/pc2" && echo shot.*-*.pc2)" = "shot.0001-0010.pc2 shot.0011-0020.pc2 shot.0021-0024.pc2"
check "the farm's OBJ sequence is the local run's, byte for byte" same_tree "$tmp/local/obj" "$tmp/farm/obj" $shot_frames
check "the joined cache is the local run's, byte for byte" cmp "$tmp/local/pc2/shot.pc2" "$tmp/farm/pc2/shot.pc2"
echo "slurm: array $array and join $join done in $(($(date +%s) - start)) s"

# --- a task cancelled mid-run, then resubmitted -----------------------------------------------------
# Task 11 slides its cache with options that take minutes a frame; once its cache's temporary
# exists it is cancelled (SIGTERM, SIGKILL after KillWait).
array=$(sbatch --parsable --array=1-$shot_frames:$chunk -c 1 -o "$tmp/log/slow.%A_%a.out" \
  "$task" "$tmp/farm2" "$shot_frames" "$shot" 11)
for ((i = 0; i < 2 * wait_seconds; i++)); do
  [ -n "$(find "$tmp/farm2/pc2" -name '.shot.0011-0020.pc2.tmp.*' 2>/dev/null)" ] && break
  sleep 0.5
done
check "task 11 is running with its cache half written" \
  test -n "$(find "$tmp/farm2/pc2" -name '.shot.0011-0020.pc2.tmp.*' 2>/dev/null)"
scancel "${array}_11"
check "the array's tasks finish or are cancelled within ${wait_seconds} s" wait_jobs "$array"
check "tasks 1 and 21 completed, task 11 was cancelled" test "$(job_states "$array" | sort -n)" = \
  "$(printf '1 COMPLETED\n11 CANCELLED\n21 COMPLETED')"
check "the cancelled task left no chunk" test ! -e "$tmp/farm2/pc2/shot.0011-0020.pc2"
check "the cancelled task left no temporary file" no_temporaries "$tmp/farm2"
check "the cancelled task wrote none of its OBJ frames" test -z "$(cd "$tmp/farm2/obj" && ls arm.001[1-9].obj arm.0020.obj 2>/dev/null)"
# The same task again (one task, its step kept), then the join after it.
again=$(sbatch --parsable --array=11-20:$chunk -c 1 -o "$tmp/log/again.%A_%a.out" \
  "$task" "$tmp/farm2" "$shot_frames" "$shot")
join=$(sbatch --parsable --dependency=afterok:"$again" -o "$tmp/log/join2.%j.out" \
  --wrap "'$bin' join -o '$tmp/farm2/pc2' '$tmp/farm2/pc2'/shot.*-*.pc2")
check "the resubmitted task and the join finish within ${wait_seconds} s" wait_jobs "$again" "$join"
check "the resubmitted task and the join completed" test \
  "$(job_states "$again") $(job_states "$join")" = "11 COMPLETED - COMPLETED"
check "after the cancel and the resubmission, the OBJ sequence is the local run's" same_tree "$tmp/local/obj" "$tmp/farm2/obj" $shot_frames
check "after the cancel and the resubmission, the joined cache is the local run's" cmp "$tmp/local/pc2/shot.pc2" "$tmp/farm2/pc2/shot.pc2"
check "no temporary file anywhere" no_temporaries "$tmp/farm2"
if [ "$failed" -gt 0 ]; then
  for f in "$tmp"/log/*.out "$tmp/log/slurmctld.log"; do
    echo "--- $f" >&2
    tail -n 5 "$f" >&2
  done
fi
echo "slurm: $passed passed, $failed failed ($(($(date +%s) - start)) s of jobs)"
[ "$failed" -eq 0 ]
