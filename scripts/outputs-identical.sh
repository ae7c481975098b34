#!/usr/bin/env bash
# Behaviour unchanged, shown byte for byte: runs the commands whose outputs are deterministic
# with --no-timings (fit reports HDF5 + JSON, factor EXRs + sidecars, bench CSVs, compare JSON,
# exports, the HTML report) with two brdfit executables and compares every file.
#
#   scripts/outputs-identical.sh BEFORE_BRDFIT AFTER_BRDFIT [WORK_DIR]
#
# Inputs: the demo's synthetic materials (synth of three catalog models, one with noise and
# holes) and 10 NBRDF proxies of ../shared/data (skipped with a message when absent).
# Exit 0 when every output is identical, 1 naming the files that differ.
# Refactors of the upper layers (io/, report/, pipeline/, cli/) are checked with it: build the
# commit before, copy its build/brdfit aside, build the change, run this.
set -euo pipefail

if [[ $# -lt 2 ]]; then
  echo "usage: $0 BEFORE_BRDFIT AFTER_BRDFIT [WORK_DIR]" >&2
  exit 2
fi
before=$(realpath "$1")
after=$(realpath "$2")
work=${3:-$(mktemp -d /tmp/brdfit-identical.XXXXXX)}
mkdir -p "$work"
work=$(realpath "$work")

# The NBRDF archive's default is relative to the working directory; the runs change it.
repo=$(cd "$(dirname "$0")/.." && pwd)
if [[ -z "${BRDFIT_NBRDF_ZIP:-}" && -f "$repo/../shared/data/merl_nbrdf.zip" ]]; then
  export BRDFIT_NBRDF_ZIP="$repo/../shared/data/merl_nbrdf.zip"
fi

proxies=(gold-metallic-paint pink-felt chrome blue-acrylic white-paint
         alum-bronze red-fabric violet-rubber green-latex black-oxidized-steel)

# run_all BRDFIT OUT: every command writes under OUT; inputs are written there first.
run_all() {
  local b=$1
  rm -rf "$2" && mkdir -p "$2/t"
  # Relative paths: reports record their inputs' paths, the same in both runs.
  cd "$2"
  local out=.
  "$b" synth --model lambert+ggx --param ggx.alpha=0.15 --param kd_r=0.5 --grid 45,45,90 \
    -o "$out/t/plastic.h5" >/dev/null
  "$b" synth --model burley+ggx --grid 45,45,90 --noise 0.05 --missing 0.2 --seed 3 \
    -o "$out/t/noisy-burley.h5" >/dev/null
  "$b" synth --model beckmann -o "$out/t/beckmann.binary" >/dev/null
  local tables=(t/plastic.h5 t/noisy-burley.h5 t/beckmann.binary)
  local nbrdf=()
  if "$b" synth --list-nbrdf >/dev/null 2>&1; then
    for p in "${proxies[@]}"; do nbrdf+=("nbrdf:$p"); done
  else
    echo "note: no NBRDF archive (../shared/data/merl_nbrdf.zip): synthetic inputs only" >&2
  fi

  "$b" fit "${tables[@]}" "${nbrdf[@]}" -q --no-timings --no-progress \
    -o "$out/fits.h5" --json "$out/fits.json"
  "$b" fit "${tables[@]}" --model ggx,lambert+ggx,lambert+ggx+sheen,ward -q --no-timings \
    --no-progress --polish none -o "$out/models.h5" --json "$out/models.json"
  "$b" fit "${tables[@]:0:2}" --model lambert+ggx,factorization -q --no-timings --no-progress \
    -j 2 -o "$out/candidates.h5" --json "$out/candidates.json"
  "$b" factor "${tables[@]}" -q --no-timings --no-progress -o "$out/factors" 2>/dev/null ||
    "$b" factor "${tables[@]}" -q --no-timings -o "$out/factors"
  "$b" bench "${tables[@]:0:2}" --models ggx,lambert+ggx --budgets stride:8 --losses log,rel \
    -q --no-timings -o "$out/bench.csv" --plot "$out/bench.html"
  "$b" compare "$out/models.h5" "$out/fits.h5" --json >"$out/compare.json" || true
  "$b" compare "$out/models.h5" "$out/fits.h5" --all >"$out/compare.txt" || true
  local m
  for f in gltf glb mitsuba pbrt blender threejs; do
    mkdir -p "$out/export-$f"
    for m in plastic noisy-burley; do
      "$b" export "$out/models.h5" --material "$m" --format "$f" \
        -o "$out/export-$f/$m.out" >/dev/null 2>&1 || echo "export $f $m: exit $?" \
        >>"$out/export-status.txt"
    done
  done
  "$b" report "$out/models.h5" "$out/fits.h5" "$out/factors" "$out/bench.csv" \
    --no-renders -q -o "$out/report.html" || echo "report: exit $?" >>"$out/report-status.txt"
  # The pages' provenance line names the executable and the time; the rest must match.
  for h in report.html bench.html; do
    [[ -f $h ]] && sed -i 's|<p id="provenance">[^<]*<code>[^<]*</code>.</p>|<p id="provenance"></p>|' "$h"
  done
  cd - >/dev/null
}

echo "before: $before -> $work/before"
run_all "$before" "$work/before"
echo "after:  $after -> $work/after"
run_all "$after" "$work/after"

status=0
n=0
while IFS= read -r -d '' f; do
  rel=${f#"$work/before/"}
  n=$((n + 1))
  if [[ ! -e "$work/after/$rel" ]]; then
    echo "missing after: $rel"; status=1
  elif ! cmp -s "$f" "$work/after/$rel"; then
    echo "differs: $rel"; status=1
  fi
done < <(find "$work/before" -type f -print0 | sort -z)
while IFS= read -r -d '' f; do
  rel=${f#"$work/after/"}
  [[ -e "$work/before/$rel" ]] || { echo "new after: $rel"; status=1; }
done < <(find "$work/after" -type f -print0 | sort -z)
if [[ $status -eq 0 ]]; then
  echo "identical: $n files"
fi
exit $status
