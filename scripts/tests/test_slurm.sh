#!/usr/bin/env bash
# A real Slurm run of a sweep (issue 9) and of a 2-worker tuning study (issue 23): installs Debian's slurm-wlm and munge if missing,
# starts a one-node cluster on localhost (munged, slurmctld, slurmd; no cgroups, no
# accounting), expands a small CartPole sweep (2 learning rates x 2 seeds), submits the
# `rlrun sweep slurm` array script with `sbatch --wait`, and checks that every run finished.
# Stops the daemons it started on exit. Needs root (or sudo) for the packages and munged.
#   scripts/tests/test_slurm.sh            (CI runs it after the test suite)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
SUDO=""
[[ $(id -u) -eq 0 ]] || SUDO=sudo

need=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if ((${#need[@]})); then
  echo "test_slurm: installing ${need[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi
[[ -x build/rlrun ]] || { echo "test_slurm: build/rlrun missing: run scripts/setup.sh first" >&2; exit 1; }

work=$(mktemp -d /tmp/rlrun-slurm.XXXXXX)
chmod 755 "$work"
export SLURM_CONF=$work/slurm.conf
started=()
own_munged=0
cleanup() {
  set +e
  scancel --quiet --name rlrun_slurm_test 2>/dev/null
  for pid in "${started[@]}"; do $SUDO kill "$pid" 2>/dev/null; done
  ((own_munged)) && [[ -s /run/munge/munged.pid ]] && $SUDO kill "$(cat /run/munge/munged.pid)"
  sleep 1
  for pid in "${started[@]}"; do $SUDO kill -9 "$pid" 2>/dev/null; done
  [[ -n "${KEEP:-}" ]] || rm -rf "$work"
}
trap cleanup EXIT

# sbatch --wait exits with the array's worst exit code; when a task failed, its log is the only
# place that says why, so print every task log before failing (CI shows only this output).
submit_and_wait() {  # <sbatch script> <directory of the task logs>
  if ! (cd "$work" && sbatch --wait "$1"); then
    echo "test_slurm: a task of $1 failed" >&2
    for f in "$2/"*.out; do echo "== $f" >&2; tail -20 "$f" >&2; done
    exit 1
  fi
}

# munge: Slurm's authentication. Its own daemon unless one already answers.
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
  [[ -s /etc/munge/munge.key ]] || $SUDO mungekey --create --force 2>/dev/null || $SUDO /usr/sbin/create-munge-key -f
  $SUDO mkdir -p /run/munge && $SUDO chown munge:munge /run/munge
  if [[ -z "$SUDO" ]]; then runuser -u munge -- /usr/sbin/munged --force
  else sudo -u munge /usr/sbin/munged --force; fi
  own_munged=1
fi
for _ in $(seq 50); do munge -n 2>/dev/null | unmunge >/dev/null 2>&1 && break; sleep 0.1; done
munge -n | unmunge >/dev/null || { echo "test_slurm: munge does not work" >&2; exit 1; }

memory=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2 ))
cat >"$SLURM_CONF" <<CONF
ClusterName=rlrun
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
SlurmctldPort=16817
SlurmdPort=16818
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=localhost NodeHostname=localhost CPUs=$(nproc) RealMemory=$memory State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
mkdir -p "$work/state" "$work/spool"
$SUDO env SLURM_CONF="$SLURM_CONF" slurmctld
started+=("$(cat "$work/slurmctld.pid" 2>/dev/null || pgrep -n slurmctld)")
$SUDO env SLURM_CONF="$SLURM_CONF" slurmd -N localhost
sleep 1
started+=("$(cat "$work/slurmd.pid" 2>/dev/null || pgrep -n slurmd)")
for _ in $(seq 60); do
  state=$(sinfo -h -N -o %T 2>/dev/null | head -1 || true)
  [[ "$state" == idle* ]] && break
  sleep 1
done
[[ "$state" == idle* ]] || { echo "test_slurm: the node did not come up ($state)"; tail -20 "$work"/*.log; exit 1; }
echo "test_slurm: one-node cluster up ($(nproc) CPUs, ${memory} MB)"

# A small sweep: CartPole PPO, 2 learning rates x 2 seeds, 20 000 steps each. Its directory's
# name holds a blank, quotes, \$(...), '#' and '%' (issue 15): sbatch and bash must both read the
# generated script's paths as one argument each, and nothing in them may run.
out="$work/sweep dir 'q' \$(touch pwned) #x %j"
cat >"$work/sweep.yaml" <<YAML
name: rlrun_slurm_test
base: $root/configs/cartpole_ppo.yaml
out_dir: "$out"
seeds: [1, 2]
grid: {algo.learning_rate: [lin_0.001, lin_0.0003]}
set: {run.total_timesteps: 20000}
slurm: {time: "00:05:00", cpus_per_task: 1, mem: 500M}
YAML
build/rlrun sweep "$work/sweep.yaml"
build/rlrun sweep slurm "$out/manifest.yaml"
start=$(date +%s)
submit_and_wait "$out/sweep.sbatch" "$out/slurm"
echo "test_slurm: the array job ended after $(( $(date +%s) - start )) s"
build/rlrun sweep status "$out/manifest.yaml"
finished=$(build/rlrun sweep status "$out/manifest.yaml" | grep -c " finished ")
logs=$(ls "$out/slurm/"*.out | wc -l)
echo "test_slurm: $finished of 4 runs finished, $logs task logs"
if [[ $finished -ne 4 || $logs -ne 4 ]]; then
  for f in "$out/slurm/"*.out; do echo "== $f"; tail -5 "$f"; done
  exit 1
fi
if [[ -e "$work/pwned" || -e "$root/pwned" ]]; then
  echo "test_slurm: the \$(touch pwned) in the sweep's directory name ran" >&2
  exit 1
fi
# A local re-run of the same manifest trains nothing more.
build/rlrun sweep run "$out/manifest.yaml" | tail -1 | grep -q "4 of 4 runs finished"
echo "test_slurm: sweep passed"

# A 2-worker `rlrun tune` study through sbatch (issue 23): both array tasks share one study
# journal; together they run n_trials trials, each taken once; Optuna reads the result. (Trials
# of 60 000 steps, a few tenths of a second each, so that a task Slurm starts a little later
# still finds trials to take.)
tune_out="$work/tune dir 'q' #x"
cat >"$work/study.yaml" <<YAML
name: rlrun_slurm_tune
base: $root/configs/cartpole_ppo.yaml
out_dir: "$tune_out"
n_trials: 8
seeds_per_trial: 1
n_timesteps: 60000
n_evaluations: 4
eval_episodes: 2
sampler: {type: tpe, seed: 1, n_startup_trials: 4}
pruner: {type: median, n_startup_trials: 2}
space:
  algo.learning_rate: {float: [1.0e-4, 3.0e-3], log: true}
  algo.n_epochs: {int: [1, 20]}
slurm: {time: "00:10:00", cpus_per_task: 1, mem: 500M}
YAML
build/rlrun tune "$work/study.yaml" --slurm --workers 2
start=$(date +%s)
submit_and_wait "$tune_out/tune.sbatch" "$tune_out/slurm"
echo "test_slurm: the tune array job ended after $(( $(date +%s) - start )) s"
summary=$(/usr/bin/python3 - "$tune_out/study.journal" <<'PY'
import sys, warnings, optuna
warnings.filterwarnings("ignore")
optuna.logging.set_verbosity(optuna.logging.ERROR)
s = optuna.load_study(study_name="rlrun_slurm_tune",
                      storage=optuna.storages.JournalStorage(optuna.storages.JournalFileStorage(sys.argv[1])))
done = [t for t in s.trials if t.state.name in ("COMPLETE", "PRUNED")]
workers = {t.system_attrs["rlrun:worker"]["id"] for t in s.trials}
print(len(s.trials), len(done), len(workers))
PY
)
read -r n_all n_done n_workers <<<"$summary"
echo "test_slurm: study: $n_all trials, $n_done complete or pruned, taken by $n_workers workers"
if [[ $n_all -ne 8 || $n_done -ne 8 || $n_workers -ne 2 ]]; then
  for f in "$tune_out/slurm/"*.out; do echo "== $f"; tail -8 "$f"; done
  exit 1
fi
echo "test_slurm: passed"
