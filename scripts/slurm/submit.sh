#!/usr/bin/env bash
# Renders a scene on a Slurm cluster: a job array of pass ranges, then a
# merge that waits for all of them.
#   scripts/slurm/submit.sh SCENE PASSES CHUNK OUTPUT [prismatic render flags...]
# e.g. scripts/slurm/submit.sh sphere 256 8 sphere.exr --photons 1000000 --width 1920 --height 1080
# Partial renders go to ./prismatic-parts-<job> (override with PARTS=...),
# which must be on a file system every node sees.
set -euo pipefail
if [ $# -lt 4 ]; then
    echo "usage: $0 SCENE PASSES CHUNK OUTPUT [prismatic render flags...]" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
export SCENE=$1 PASSES=$2 CHUNK=$3 OUTPUT=$4
shift 4
export RENDER_ARGS="$*"
export PARTS=${PARTS:-$PWD/prismatic-parts-$$}
mkdir -p "$PARTS"
tasks=$(((PASSES + CHUNK - 1) / CHUNK))
array=$(sbatch --parsable --export=ALL --array=0-$((tasks - 1)) "$here/render-range.sbatch")
array=${array%%;*} # --parsable prints "id" or "id;cluster"
merge=$(sbatch --parsable --export=ALL --dependency=afterok:"$array" "$here/merge.sbatch")
echo "array job $array ($tasks tasks of $CHUNK passes), merge job $merge -> $OUTPUT"
