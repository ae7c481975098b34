#!/usr/bin/env bash
# Peak resident memory of `brdfit fit` and `brdfit factor` (docs/reliability.md, "Memory"),
# with /usr/bin/time:
#   1. one full MERL-grid table (90 x 90 x 180 = 1,458,000 cells) fitted with one model, and
#      factored (the default: four candidate forms; and one form, --param mccool);
#   2. batches of 10, 50 and 100 materials (NBRDF networks tabulated on the MERL grid), one
#      model each, one job: the peak must not grow with the number of materials.
# Usage: scripts/measure_memory.sh [BUILD_DIR]   (default: build; needs BUILD_DIR/brdfit)
# Environment: MODEL (default ggx, e.g. MODEL=lambert+ggx), WORK (scratch folder,
# default a temporary one, removed at the end), BATCHES (default "10 50 100").
# Step 2 needs ../shared/data/merl_nbrdf.zip (or $BRDFIT_NBRDF_ZIP); without it, step 1 uses a
# synthetic lambert+ggx table and step 2 is skipped with a message.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
BRDFIT=$PWD/$BUILD/brdfit
MODEL=${MODEL:-ggx}
BATCHES=${BATCHES:-10 50 100}
[[ -x $BRDFIT ]] || { echo "measure_memory: no $BRDFIT (build first)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "measure_memory: needs /usr/bin/time (package time)" >&2; exit 2; }

if [[ -n ${WORK:-} ]]; then
  mkdir -p "$WORK"
else
  WORK=$(mktemp -d)
  trap 'rm -rf "$WORK"' EXIT
fi
cd "$WORK"

# peak_rss LABEL CMD...: runs CMD, prints "| label | peak RSS MB | wall s |".
peak_rss() {
  local label=$1
  shift
  /usr/bin/time -f "%M %e" -o time.txt "$@" >run.log 2>&1 || {
    tail -n 20 run.log >&2
    echo "measure_memory: '$*' failed" >&2
    exit 1
  }
  read -r kb secs <time.txt
  awk -v l="$label" -v kb="$kb" -v s="$secs" 'BEGIN { printf "| %s | %.1f | %s |\n", l, kb / 1024, s }'
}

have_nbrdf=0
if "$BRDFIT" synth --list-nbrdf >materials.txt 2>/dev/null && [[ -s materials.txt ]]; then
  have_nbrdf=1
fi

echo "| run | peak RSS (MB) | wall (s) |"
echo "|---|---|---|"
if ((have_nbrdf)); then
  "$BRDFIT" synth --nbrdf gold-metallic-paint -o one.binary >/dev/null
else
  "$BRDFIT" synth --model lambert+ggx --param ggx.alpha=0.1 -o one.binary >/dev/null
fi
peak_rss "1 MERL-grid table, brdfit fit --model $MODEL" \
  "$BRDFIT" fit one.binary --model "$MODEL" --no-progress -o one.h5
peak_rss "1 MERL-grid table, brdfit factor (four candidate forms)" \
  "$BRDFIT" factor one.binary -q -o factor-auto
peak_rss "1 MERL-grid table, brdfit factor --param mccool (one form)" \
  "$BRDFIT" factor one.binary --param mccool -q -o factor-one

if ((!have_nbrdf)); then
  echo "measure_memory: no NBRDF archive (../shared/data/merl_nbrdf.zip): batches skipped" >&2
  exit 0
fi
mkdir -p tables
max=0
for n in $BATCHES; do ((n > max)) && max=$n; done
head -n "$max" materials.txt | while read -r m; do
  [[ -f tables/$m.binary ]] || "$BRDFIT" synth --nbrdf "$m" -o "tables/$m.binary" >/dev/null
done
for n in $BATCHES; do
  mapfile -t files < <(head -n "$n" materials.txt | sed 's|^|tables/|; s|$|.binary|')
  rm -f batch.h5
  peak_rss "batch of $n MERL-grid tables, $MODEL, --jobs 1" \
    "$BRDFIT" fit "${files[@]}" --model "$MODEL" --no-progress -o batch.h5
done
