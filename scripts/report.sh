#!/usr/bin/env bash
# The full threshold-sweep report (BENCH.md "Error against run time"): every raw dataset of the shared
# MANIFEST.tsv and one synthetic phantom through volsweep into one folder: sweep.csv, report.md, plots/ (gnuplot),
# strips/ and images/. Also runs scripts/peers.sh (when present) on the datasets in PEERS and joins its figures.
#   scripts/report.sh [OUTDIR]            (default out/sweep)
# Defaults sized for about 30 minutes on 2 cores with lavapipe (see the "This run" section of the report):
# 256x256 images, 4 views, a 3x3 threshold grid for volumes of a million voxels or more, 5x3 below that.
# Environment: BUILD_DIR (default build), VIEWS (4), SIZE (256x256), ONLY (space-separated dataset name prefixes,
# e.g. "cranium_ct vtk_headsq_ct phantom"), PEERS (dataset prefixes for scripts/peers.sh, default "vtk_headsq_ct";
# "" for none), RESUME=1 (keep OUTDIR and skip the settings already in its sweep.csv), BIG_TO, BIG_TA, SMALL_TO,
# SMALL_TA (the threshold grids, comma-separated).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
datasets=${VR_DATASETS_DIR:-$root/../shared/datasets}
build=${BUILD_DIR:-build}
out=${1:-out/sweep}
views=${VIEWS:-4}
size=${SIZE:-256x256}
only=${ONLY:-}
peers=${PEERS-vtk_headsq_ct}
big_to=${BIG_TO:-0,0.02,0.1} big_ta=${BIG_TA:-0,3,20}  # 3x3 for volumes of >= 1M voxels
small_to=${SMALL_TO:-0,0.01,0.02,0.05,0.1} small_ta=${SMALL_TA:-0,3,20}
phantom_dims=128x128x128

bash scripts/install-deps.sh gnuplot-nox
[[ -f $build/CMakeCache.txt ]] || cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build "$build" --target volsweep_cli volphantom -j 2
volsweep=$build/sweep/volsweep

resume=()
if [[ ${RESUME:-0} == 1 ]]; then resume=(--resume); else rm -rf "$out"; fi
mkdir -p "$out"
start=$SECONDS
timings=""

wanted() {  # wanted NAME: whether ONLY is empty or NAME starts with one of its prefixes
  [[ -z $only ]] && return 0
  local p
  for p in $only; do [[ $1 == "$p"* ]] && return 0; done
  return 1
}

sweep() {  # sweep NAME FILE TF SPACING
  local name=$1 file=$2 tf=$3 spacing=$4
  local dims voxels to=$big_to ta=$big_ta
  dims=$(grep -oE '_[0-9]+x[0-9]+x[0-9]+_' <<<"$file" | tr -d _ | tr x ' ')
  voxels=$(awk '{ print $1 * $2 * $3 }' <<<"$dims")
  if ((voxels < 1000000)); then to=$small_to ta=$small_ta; fi
  local t0=$SECONDS
  echo "+ volsweep $name (T_o $to, T_a $ta)" >&2
  "$volsweep" "$file" --tf "$tf" --spacing "$spacing" --name "$name" --to "$to" --ta "$ta" --views "$views" \
    --size "$size" -o "$out" "${resume[@]}" </dev/null >/dev/null
  timings+="| $name | $dims | $to | $ta | $((SECONDS - t0)) |"$'\n'
  echo "  $name: $((SECONDS - t0)) s" >&2
  local p
  for p in $peers; do
    [[ $name == "$p"* ]] && peers_of "$name" "$file" "$tf" "$spacing"
  done
  return 0
}

# The peers render without shading (scripts/peers.sh): compare them with an unshaded sweep at T_o = T_a = 0 of
# the same dataset, in its own report section NAME_unshaded.
peers_of() {  # peers_of NAME FILE TF SPACING
  local name=$1 file=$2 tf=$3 spacing=$4 t0=$SECONDS
  [[ -f scripts/peers.sh ]] || return 0
  if ! BUILD_DIR=$build bash scripts/peers.sh "$(basename "$file")" "$views" "$size" "$out/peers/$name" \
    </dev/null >&2; then
    echo "report.sh: scripts/peers.sh failed on $name: the report has no peers for it" >&2
    return 0
  fi
  "$volsweep" "$file" --tf "$tf" --spacing "$spacing" --name "${name}_unshaded" --no-shading --to 0 --ta 0 \
    --views "$views" --size "$size" -o "$out" --peers "$out/peers/$name" "${resume[@]}" </dev/null >/dev/null
  timings+="| ${name}_unshaded + peers | | 0 | 0 | $((SECONDS - t0)) |"$'\n'
}

# Every headerless raw dataset of the manifest, with its spacing (the first three numbers) and transfer function.
while IFS=$'\t' read -r file _dims _type spacing _source _desc _sha _notes tf; do
  [[ $file == *.raw.gz ]] || continue
  name=${file%.raw.gz}
  wanted "$name" || continue
  spacing=$(grep -oE '[0-9]+(\.[0-9]+)?' <<<"$spacing" | head -3 | paste -sd,)
  sweep "$name" "$datasets/$file" "$datasets/$tf" "$spacing"
done < <(tail -n +2 "$datasets/MANIFEST.tsv")

# One synthetic phantom: CT-like shells in Hounsfield units with the CT transfer function.
if wanted phantom; then
  mkdir -p "$out/phantom"
  "$build/datasets/volphantom" shells --dims "$phantom_dims" --type int16 -o "$out/phantom" </dev/null >/dev/null
  sweep "phantom_shells_${phantom_dims}_int16" "$out/phantom/shells_${phantom_dims}_int16.raw" \
    "$datasets/cranium_ct.tf.json" 1,1,1
fi

"$volsweep" --report-only -o "$out" >/dev/null
total=$((SECONDS - start))
# CPU seconds of everything this script ran (user + system): what the run costs whatever else shares the machine.
cpu=$(times | awk 'NR == 2 { s = 0; for (i = 1; i <= 2; ++i) { split($i, t, /[ms]/); s += t[1] * 60 + t[2] } printf "%.0f", s }')
device=$(vulkaninfo --summary 2>/dev/null | awk -F'= ' '/deviceName/ { print $2; exit }' || true)
cat >>"$out/report.md" <<MD
## This run (scripts/report.sh)

$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPU cores, Vulkan device: ${device:-unknown}. Images ${size}, ${views}
views (azimuth 360 i / ${views}, elevation 0), step 0.5 voxel, nearest sampling, Phong shading with a headlight.
Threshold grid: T_o {${big_to}} x T_a {${big_ta}} degrees for volumes of a million voxels or more,
T_o {${small_to}} x T_a {${small_ta}} below that (sized for about 30 minutes on this 2-core machine; the wall
time below grows with whatever else shares it). Peers (scripts/peers.sh, unshaded as they render) on: ${peers:-none}, compared in the NAME_unshaded
sections with our unshaded casters at T_o = T_a = 0.

| dataset | dims | T_o | T_a | seconds |
|---|---|---|---|---:|
${timings}
**Whole report: ${total} s wall, ${cpu} s CPU** (user + system of all its processes; the wall time depends on
what else runs on the machine).
MD
echo "$out/report.md (${total} s wall, ${cpu} s CPU)"
