#!/usr/bin/env bash
# Submits a sharded brdfit batch to Slurm: an array of N shards, then the merge once all of them
# ended well (docs/scale.md).
#   scripts/slurm/submit.sh N LIST OUTDIR [brdfit fit options...]
set -euo pipefail
n=$1 list=$2 outdir=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
array=$(N=$n sbatch --parsable --export=ALL,N="$n" --array=0-$((n - 1)) \
  "$here/fit-shards.sbatch" "$list" "$outdir" "$@")
array=${array%%;*}  # "jobid;cluster" on federated clusters
merge=$(sbatch --parsable --dependency=afterok:"$array" "$here/merge-shards.sbatch" "$outdir" "$n")
echo "array job $array ($n shards), merge job $merge -> $outdir/fits.h5"
