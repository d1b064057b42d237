#!/usr/bin/env bash
# A SWA study on a Slurm cluster: one array task per shard (study-shard.sbatch), then a merge job that starts when
# every shard ended well (study-merge.sbatch). See --help.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)

usage() {
  cat <<'USAGE'
Usage: deploy/slurm/submit-study.sh --scenario FILE --out DIR [--shards N] [--cpus-per-task C] [options]
                                    [-- swa_batch arguments: --set k=v, --sweep KEY=V1,V2, --seeds N]

Submits a study (a scenario with a study: section, or --sweep arguments after --) to Slurm as an array job of N
tasks, task I running `swa_batch --shard I/N` on C CPUs, and a merge job that depends on the whole array
(afterok): OUT/study/ then holds runs.csv, points/<k>/summary.json, study.html and study.json, byte for byte what
`swa_batch` writes for the whole study on one machine. OUT must be on a file system every node sees, and so must
the scenario file (the jobs run in the directory this script was started from).

Before anything is submitted, the study is checked here (swa_batch --dry-run: every grid point's scenario).

Options:
  --scenario FILE      the study's scenario (required)
  --out DIR            the study's directory: job.env, shards/<I>/, logs/, study/ (required; must not hold a study)
  --shards N           array tasks (default 4). More shards than runs leaves some empty, which is fine.
  --cpus-per-task C    CPUs per array task, given to swa_batch --jobs (default 1)
  --time T             Slurm time limit per task (sbatch --time, e.g. 01:00:00)
  --partition P        Slurm partition
  --account A          Slurm account
  --bin-dir DIR        where swa_batch is (default: swa_batch on PATH, else this checkout's build/bin)
  --image IMAGE        run swa_batch from a container image instead (the batch image of
                       deploy/containers.sh build: localhost/swa-batch:latest, or an Apptainer .sif)
  --runtime R          podman (default) or apptainer, for --image
  --dry-run            check and print what would be submitted, submit nothing
  -h, --help           this text

Prints the array and merge job ids. Watch them with `squeue -j ID`; a failed shard leaves the merge job never run
(--kill-on-invalid-dep), its log in OUT/logs/shard_<I>.out; re-submitting with a fresh --out redoes the study.

Example (the shipped study, 160 runs):
  deploy/slurm/submit-study.sh --scenario deploy/scenarios/study_drift_vs_n.yaml --out /shared/$USER/drift_vs_n \
      --shards 8 --cpus-per-task 4 --time 00:30:00
USAGE
}

die() {
  echo "submit-study: $*" >&2
  exit 2
}

scenario=
out=
shards=4
cpus=1
bin_dir=
image=
runtime=podman
dry_run=0
sbatch_args=()
batch_args=()
while [ $# -gt 0 ]; do
  case $1 in
    --scenario | --out | --shards | --cpus-per-task | --time | --partition | --account | --bin-dir | --image | \
      --runtime)
      [ $# -ge 2 ] || die "$1 needs a value"
      case $1 in
        --scenario) scenario=$2 ;;
        --out) out=$2 ;;
        --shards) shards=$2 ;;
        --cpus-per-task) cpus=$2 ;;
        --time | --partition | --account) sbatch_args+=("$1=$2") ;;
        --bin-dir) bin_dir=$2 ;;
        --image) image=$2 ;;
        --runtime) runtime=$2 ;;
      esac
      shift 2
      ;;
    --dry-run) dry_run=1; shift ;;
    -h | --help) usage; exit 0 ;;
    --) shift; batch_args=("$@"); break ;;
    *) die "unknown argument '$1' (swa_batch arguments go after --; see --help)" ;;
  esac
done

[ -n "$scenario" ] || die "--scenario FILE is required"
[ -n "$out" ] || die "--out DIR is required"
[ -r "$scenario" ] || die "--scenario $scenario is not a readable file"
[[ $shards =~ ^[1-9][0-9]*$ ]] && [ "$shards" -le 10000 ] || die "--shards must be a whole number in [1, 10000]"
[[ $cpus =~ ^[1-9][0-9]*$ ]] && [ "$cpus" -le 256 ] || die "--cpus-per-task must be a whole number in [1, 256]"
for a in ${batch_args[@]+"${batch_args[@]}"}; do
  case $a in
    --shard | --shard=* | --out | --out=* | --jobs | --jobs=* | --scenario | --scenario=* | --compare | --compare=*)
      die "$a is this script's to set (--shards, --out, --cpus-per-task, --scenario); --compare is not for studies" ;;
    --dry-run | --help | -h | --parameters)
      die "$a after -- would make every shard run nothing (this script has its own --dry-run and --help)" ;;
  esac
done
out=$(realpath -m -- "$out")  # the jobs may start elsewhere
[ ! -e "$out/job.env" ] || die "$out already holds a study (job.env): give a fresh --out"

# What the jobs run: the installed binary, or the batch image through its runtime. The container sees the working
# directory, the scenario's and OUT (`check`: not OUT, which does not exist yet), each at its own path, and each only
# once and not inside another (podman refuses a mount destination given twice).
mounted=()
mount_dir() {
  local d
  for d in ${mounted[@]+"${mounted[@]}"}; do
    case $1/ in "$d"/*) return 0 ;; esac
  done
  mounted+=("$1")
}
# runtime_command DIR...: the runtime's command line for swa_batch in the image, with DIR... mounted.
runtime_command() {
  mounted=()
  local d
  for d in "$@"; do mount_dir "$d"; done
  local args=()
  case $runtime in
    podman)
      for d in "${mounted[@]}"; do args+=(--volume "$d:$d"); done
      printf '%s\0' podman run --rm --network none "${args[@]}" --workdir "$PWD" "$image" swa_batch ;;
    apptainer)
      for d in "${mounted[@]}"; do args+=(--bind "$d"); done
      printf '%s\0' apptainer exec "${args[@]}" --pwd "$PWD" "$image" swa_batch ;;
  esac
}
if [ -n "$image" ]; then
  case $runtime in podman | apptainer) ;; *) die "--runtime must be podman or apptainer, got '$runtime'" ;; esac
  scenario_dir=$(cd "$(dirname "$scenario")" && pwd)
  mapfile -d '' -t check < <(runtime_command "$PWD" "$scenario_dir")
  mapfile -d '' -t batch < <(runtime_command "$PWD" "$scenario_dir" "$out")
else
  if [ -n "$bin_dir" ]; then
    exe=$bin_dir/swa_batch
  elif command -v swa_batch > /dev/null; then
    exe=$(command -v swa_batch)
  else
    exe=$root/build/bin/swa_batch
  fi
  [ -x "$exe" ] || die "$exe is not an executable swa_batch (build first, or give --bin-dir or --image)"
  batch=("$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")")
  check=("${batch[@]}")
fi

# The whole study checked now, not in N array tasks after a wait in the queue (OUT does not exist yet).
echo "submit-study: checking the study with ${check[*]} --dry-run"
"${check[@]}" --scenario "$scenario" ${batch_args[@]+"${batch_args[@]}"} --shard "1/$shards" --dry-run ||
  die "the study's check failed (above); nothing submitted"

# Everything the jobs need, in one file they source: what ran is on record beside the results.
env_text=$(
  echo "# SWA study submitted $(date -u +%Y-%m-%dT%H:%M:%SZ) from $PWD by deploy/slurm/submit-study.sh"
  printf 'SWA_BATCH=(%s)\n' "$(printf '%q ' "${batch[@]}")"
  printf 'SWA_SCENARIO=%q\n' "$scenario"
  # (printf with no arguments would still print one empty word)
  if [ ${#batch_args[@]} -gt 0 ]; then printf 'SWA_ARGS=(%s)\n' "$(printf '%q ' "${batch_args[@]}")"; else
    echo 'SWA_ARGS=()'; fi
  printf 'SWA_SHARDS=%q\n' "$shards"
  printf 'SWA_OUT=%q\n' "$out"
)
if [ "$dry_run" -eq 1 ]; then
  echo "submit-study: --dry-run: would submit $shards array task(s) of $cpus CPU(s) and a merge job with:"
  echo "$env_text"
  exit 0
fi
command -v sbatch > /dev/null || die "sbatch not found: run this on a Slurm login node"
mkdir -p "$out/shards" "$out/logs"
echo "$env_text" > "$out/job.env"

array_id=$(sbatch --parsable --chdir="$PWD" --array="1-$shards" --cpus-per-task="$cpus" \
  --output="$out/logs/shard_%a.out" ${sbatch_args[@]+"${sbatch_args[@]}"} "$here/study-shard.sbatch" "$out/job.env")
array_id=${array_id%%;*}  # "ID;cluster" on multi-cluster sites
merge_id=$(sbatch --parsable --chdir="$PWD" --dependency="afterok:$array_id" --kill-on-invalid-dep=yes \
  --output="$out/logs/merge.out" ${sbatch_args[@]+"${sbatch_args[@]}"} "$here/study-merge.sbatch" "$out/job.env")
merge_id=${merge_id%%;*}
echo "$array_id" > "$out/array.jobid"
echo "$merge_id" > "$out/merge.jobid"
echo "submit-study: array job $array_id ($shards shard(s)), merge job $merge_id (after the array succeeds)"
echo "submit-study: results in $out/study/ once job $merge_id completed; logs in $out/logs/"
