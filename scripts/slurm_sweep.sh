#!/usr/bin/env bash
# Runs a sweep on a Slurm cluster: a job array of N shards, each `sortcell sweep SPEC --shard i/N` into
# OUT/shard<i>, and a merge job that starts when all of them have ended (however they ended): it
# concatenates their results.jsonl into OUT/merged and runs `sortcell sweep SPEC --resume` there, which
# runs any episode a failed shard left out and writes the summary (OUT/merged/summary.md).
#   scripts/slurm_sweep.sh SPEC N OUT [sortcell sweep options...]
#   scripts/slurm_sweep.sh scenes/sweeps/paper_objects_100.yaml 8 out/cluster -j 2 --metrics-only
# Options after OUT go to every shard and to the merge (--set ones must, so that the merge's --resume
# matches). The job array and every shard resume (--resume), so a requeued shard continues where it
# stopped. Environment: SORTCELL (the sortcell binary; default build/app/sortcell of this checkout, which
# every node must see at the same path, as it must SPEC and OUT), SORTCELL_SLURM_WAIT=1 (wait for the
# merge job to end and exit with its status), SBATCH_* (Slurm's own, e.g. SBATCH_PARTITION).
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 SPEC N OUT [sortcell sweep options...]" >&2
  exit 2
fi
[ -f "$1" ] || { echo "$0: SPEC '$1': no such file" >&2; exit 2; }
spec=$(realpath "$1")
shards=$2
out=$(realpath -m "$3")
shift 3
case "$shards" in ''|*[!0-9]*|0) echo "$0: N: expected a whole number of shards >= 1, got '$shards'" >&2; exit 2 ;; esac
sortcell=$(realpath "${SORTCELL:-$(dirname "$0")/../build/app/sortcell}")
[ -x "$sortcell" ] || { echo "$0: no sortcell binary at '$sortcell' (build first, or set SORTCELL)" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "$0: sbatch not found: this is not a Slurm login node" >&2; exit 2; }
# -j N among the options: that many CPUs per shard.
cpus=1
args=("$@")
for ((i = 0; i < ${#args[@]}; ++i)); do
  case "${args[i]}" in
    -j|--jobs) cpus=${args[i + 1]:-1} ;;
    -j*) cpus=${args[i]#-j} ;;
    --jobs=*) cpus=${args[i]#--jobs=} ;;
  esac
done

mkdir -p "$out/slurm"
quoted_options=""
[ $# -gt 0 ] && quoted_options=$(printf ' %q' "$@")
cat > "$out/slurm/shard.sh" <<JOB
#!/usr/bin/env bash
set -euo pipefail
exec $(printf %q "$sortcell") sweep $(printf %q "$spec")$quoted_options --resume \\
  --shard "\${SLURM_ARRAY_TASK_ID}/$shards" --out $(printf %q "$out")/shard"\${SLURM_ARRAY_TASK_ID}"
JOB
cat > "$out/slurm/merge.sh" <<JOB
#!/usr/bin/env bash
set -euo pipefail
merged=$(printf %q "$out/merged")
mkdir -p "\$merged"
: > "\$merged/results.jsonl"
for shard in \$(seq 1 $shards); do
  dir=$(printf %q "$out")/shard\$shard
  [ -f "\$dir/spec.yaml" ] && [ ! -f "\$merged/spec.yaml" ] && cp "\$dir/spec.yaml" "\$merged/"
  if [ -f "\$dir/results.jsonl" ]; then
    cat "\$dir/results.jsonl" >> "\$merged/results.jsonl"
    # A shard killed mid-line: end the cut line there, so that the next shard's first record stays whole
    # (--resume reports the cut one as damaged and runs its episode again).
    [ -n "\$(tail -c 1 "\$dir/results.jsonl")" ] && echo >> "\$merged/results.jsonl"
  fi
done
exec $(printf %q "$sortcell") sweep $(printf %q "$spec")$quoted_options --resume --out "\$merged"
JOB
chmod +x "$out/slurm/shard.sh" "$out/slurm/merge.sh"

array=$(sbatch --parsable --job-name=sortcell-sweep --array="1-$shards" --cpus-per-task="$cpus" \
  --output="$out/slurm/shard_%a.log" "$out/slurm/shard.sh")
array=${array%%;*}
echo "Submitted $shards shards as job array $array; the merge waits for them. Results: $out/merged/summary.md"
merge=$(sbatch --parsable --job-name=sortcell-merge --dependency="afterany:$array" --cpus-per-task="$cpus" \
  --output="$out/slurm/merge.log" "$out/slurm/merge.sh")
merge=${merge%%;*}
echo "$merge"
[ "${SORTCELL_SLURM_WAIT:-0}" = 1 ] || exit 0
# Wait for the merge job here rather than with `sbatch --wait`, which polls ever more slowly: a merge that
# ended 10 s after it was submitted was seen 32 s after (the local cluster's test, 2026-12-07). Its exit
# status as sbatch --wait gives it: the job's, 1 if a signal ended it; and 1 if it ended without running
# (cancelled, failed to start) with status 0.
while :; do
  if ! info=$(scontrol show job -o "$merge" 2>/dev/null); then
    echo "$0: merge job $merge is no longer known to Slurm" >&2
    exit 1
  fi
  state=$(sed -n 's/.* JobState=\([A-Z_]*\).*/\1/p' <<<"$info")
  case "$state" in
    PENDING | CONFIGURING | RUNNING | COMPLETING | SUSPENDED | REQUEUED | REQUEUE_HOLD | RESIZING | '') sleep 1 ;;
    *) break ;;
  esac
done
read -r status signal < <(sed -n 's/.* ExitCode=\([0-9]*\):\([0-9]*\).*/\1 \2/p' <<<"$info")
if [ "${signal:-0}" != 0 ]; then exit 1; fi
if [ "$state" != COMPLETED ] && [ "${status:-0}" = 0 ]; then exit 1; fi
exit "${status:-1}"
