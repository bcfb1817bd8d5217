#!/bin/bash
# Submits a study as a Slurm job array of N shards, then its merge and
# report once every shard has succeeded.
#   examples/slurm/submit.sh STUDY N OUTDIR
set -euo pipefail
study=$(realpath "$1")
n=$2
outdir=$(realpath -m "$3")
here=$(dirname "$(realpath "$0")")
mkdir -p "$outdir"
array=$(sbatch --parsable --array=1-"$n" "$here/study.sbatch" "$study" "$outdir")
sbatch --dependency=afterok:"$array" "$here/merge.sbatch" "$outdir"
echo "submitted array $array ($n shards) and its merge into $outdir/results.csv"
