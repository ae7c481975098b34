#!/usr/bin/env bash
# The Slurm recipe of docs/scale.md against a real Slurm: slurmctld and slurmd (Debian's
# slurm-wlm) on this host in a scratch configuration (AuthType=auth/none, no munge, ports of
# our own), scripts/slurm/submit.sh submits a 3-task array of `brdfit fit --shard` and the
# dependent merge; the merged report must equal the single-process report byte for byte.
#   slurm_localhost.sh BRDFIT_EXE SOURCE_DIR
# Exit 0 pass, 1 fail, 77 skipped (ctest SKIP_RETURN_CODE) when Slurm is absent or cannot start.
set -uo pipefail
exe=$1 src=$2
skip() { echo "SKIP: $*" >&2; exit 77; }
fail() { echo "FAIL: $*" >&2; for f in "$dir"/log/*; do echo "== $f" >&2; tail -20 "$f" >&2; done; exit 1; }

for t in slurmctld slurmd sbatch squeue scontrol sinfo; do
  command -v "$t" >/dev/null || skip "$t is not installed (Debian slurmctld slurmd slurm-client, scripts/setup-deps.sh)"
done
[[ $(id -u) == 0 ]] || skip "slurmd must run as root here (scratch configuration with SlurmdUser=root)"
[[ -f /usr/lib/x86_64-linux-gnu/slurm-wlm/auth_none.so ]] || skip "no auth/none plugin in this Slurm"

dir=$(mktemp -d /tmp/brdfit-slurm-XXXXXX)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null; done
  rm -rf "$dir"
}
trap cleanup EXIT
mkdir -p "$dir"/{state,spool,log,out,tables}
host=$(hostname -s)
base=$((20000 + ($$ % 2000) * 4))  # slurmctld, slurmd ports: away from 6817/6818 and other runs
export SLURM_CONF=$dir/slurm.conf
cat > "$SLURM_CONF" <<CONF
ClusterName=brdfittest
SlurmctldHost=$host
SlurmctldPort=$base
SlurmdPort=$((base + 1))
AuthType=auth/none
CredType=cred/none
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

slurmctld -D -i -f "$SLURM_CONF" > "$dir/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$host" > "$dir/log/slurmd.out" 2>&1 &
pids+=($!)
up=0
for _ in $(seq 1 60); do
  if sinfo -h -o %t 2>/dev/null | grep -qE '^(idle|mix|alloc)'; then up=1; break; fi
  sleep 0.5
done
((up)) || { for f in "$dir"/log/*; do echo "== $f" >&2; tail -5 "$f" >&2; done
            skip "slurmctld/slurmd did not come up on $host (logs above)"; }

# Three small tables, two fast models: the batch takes seconds.
for i in 0 1 2; do
  "$exe" synth -m lambert+ggx -p ggx.alpha=0.$((i + 1)) --grid 16,16,32 --noise 0.03 --seed $i \
    -o "$dir/tables/t$i.h5" >/dev/null || fail "synth"
done
ls "$dir"/tables/*.h5 > "$dir/tables.txt"
opts=(--model ggx,ward --budget full --no-timings)
"$exe" fit "$dir"/tables/*.h5 "${opts[@]}" -q --no-progress -o "$dir/ref.h5" || fail "unsharded fit"

cd "$dir" || fail "cd"
export BRDFIT=$exe
submitted=$("$src/scripts/slurm/submit.sh" 3 "$dir/tables.txt" "$dir/out" "${opts[@]}") ||
  fail "submit: $submitted"
echo "$submitted"
merge=$(sed -n 's/.*merge job \([0-9]*\).*/\1/p' <<<"$submitted")
[[ -n $merge ]] || fail "no merge job id in: $submitted"
state=""
for _ in $(seq 1 240); do
  state=$(scontrol show job "$merge" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
  [[ $state == COMPLETED || $state == FAILED || $state == CANCELLED || $state == TIMEOUT ]] && break
  sleep 0.5
done
[[ $state == COMPLETED ]] || fail "merge job $merge ended $state"
cmp "$dir/out/fits.h5" "$dir/ref.h5" || fail "merged report differs from the single-process one"
# The tasks' logs are job logs: one time-stamped line per finished fit.
lines=$(cat "$dir"/slurm-*_*.out | grep -cE '^[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9:]{8}Z fitting [0-9]+/[0-9]+ done: ')
[[ $lines == 6 ]] || fail "expected 6 fit lines in the array's logs, found $lines"
echo "PASS: 3 shards under Slurm merged into the single-process report (6 fits)"
