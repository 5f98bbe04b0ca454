#!/usr/bin/env bash
# The full report (docs/BENCH.md "Error against run time" and "Peers"): every raw dataset of the shared MANIFEST.tsv
# and one synthetic phantom through volsweep over a 6x5 threshold grid, and the peers side by side with
# our casters on every CT dataset, into one folder: sweep.csv, report.md, plots/, strips/, images/, peers/.
#   scripts/report.sh [OUTDIR]            (default out/sweep)
# Sized for 30 minutes on this 2-core machine with lavapipe (the "This run" section of the report says why):
# 256x256 images, an 8-view orbit at elevation 0; volumes of BIG_VOXELS voxels or more are swept
# box-averaged by DOWNSAMPLE per axis; the peers at 512x512 (the same 8 views) on the full-size CT volumes.
# Environment: BUILD_DIR (default build), VIEWS (8), SIZE (256x256), TO and TA (the grid, comma-separated; default
# 0,0.005,0.01,0.02,0.05,0.1 x 0,1,3,10,20), BIG_VOXELS (4000000), DOWNSAMPLE (2), ONLY
# (space-separated dataset name prefixes, e.g. "cranium_ct vtk_headsq_ct phantom"), PEERS (dataset prefixes for
# the peers, default the CT volumes "boston_teapot cranium_ct vtk_headsq_ct"; "" for none), PEER_SIZE (512x512),
# PEER_VIEWS (8), PEER_LIST (the peers run, default vtk-fixed-point,vtk-gpu,volpack,vdb_render),
# UNSHADED_TO (T_o values of the unshaded full-size sweep beside the peers, default 0,0.01,0.02,0.05,0.1),
# RESUME=1 (keep OUTDIR and skip the settings already in its sweep.csv).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
datasets=${VR_DATASETS_DIR:-$root/../shared/datasets}
build=${BUILD_DIR:-build}
out=${1:-out/sweep}
views=${VIEWS:-8}
size=${SIZE:-256x256}
to=${TO:-0,0.005,0.01,0.02,0.05,0.1}
ta=${TA:-0,1,3,10,20}
big_voxels=${BIG_VOXELS:-4000000}
downsample=${DOWNSAMPLE:-2}
only=${ONLY:-}
peers=${PEERS-boston_teapot cranium_ct vtk_headsq_ct}
peer_size=${PEER_SIZE:-512x512}
peer_views=${PEER_VIEWS:-8}
peer_list=${PEER_LIST:-vtk-fixed-point,vtk-gpu,volpack,vdb_render}
unshaded_to=${UNSHADED_TO:-0,0.01,0.02,0.05,0.1}
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

# Sets cpu to the CPU seconds (user + system) of every finished child process so far: what a step costs whatever
# shares the machine. The builtin `times` must run in this shell (a subshell would report its own children).
cpu_now() {
  times >"$out/.times"
  cpu=$(awk 'NR == 2 { s = 0; for (i = 1; i <= 2; ++i) { split($i, t, /[ms]/); s += t[1] * 60 + t[2] }
                      printf "%.0f", s }' "$out/.times")
}

wanted() {  # wanted NAME: whether ONLY is empty or NAME starts with one of its prefixes
  [[ -z $only ]] && return 0
  local p
  for p in $only; do [[ $1 == "$p"* ]] && return 0; done
  return 1
}

sweep() {  # sweep NAME FILE TF SPACING DIMS ("X Y Z")
  local name=$1 file=$2 tf=$3 spacing=$4 dims=$5 factor=1 swept=$5
  local voxels t0=$SECONDS c0
  cpu_now
  c0=$cpu
  voxels=$(awk '{ print $1 * $2 * $3 }' <<<"$dims")
  if ((voxels >= big_voxels && downsample > 1)); then
    factor=$downsample
    swept=$(awk -v f="$factor" '{ printf "%d %d %d", ($1 + f - 1) / f, ($2 + f - 1) / f, ($3 + f - 1) / f }' <<<"$dims")
    name="${name}_at_$(tr ' ' x <<<"$swept")"
  fi
  echo "+ volsweep $name (T_o $to, T_a $ta, downsample $factor)" >&2
  "$volsweep" "$file" --tf "$tf" --spacing "$spacing" --name "$name" --to "$to" --ta "$ta" --views "$views" \
    --size "$size" --downsample "$factor" --nearest -o "$out" "${resume[@]}" </dev/null >/dev/null
  cpu_now
  timings+="| $name | $(tr ' ' x <<<"$dims") | $(tr ' ' x <<<"$swept") | $((SECONDS - t0)) | $((cpu - c0)) |"$'\n'
  echo "  $name: $((SECONDS - t0)) s" >&2
}

# The peers render without shading (scripts/peers.sh): they are compared with our unshaded casters on the
# full-size volume, at their image size and views, in the report section NAME_unshaded, which also sweeps T_o
# (unshaded regions are segmented without normals, so T_a does not apply).
peers_of() {  # peers_of NAME FILE TF SPACING
  local name=$1 file=$2 tf=$3 spacing=$4 t0=$SECONDS c0
  cpu_now
  c0=$cpu
  if ! USER_SETTINGS=0 BUILD_DIR=$build PEER_LIST=$peer_list bash scripts/peers.sh "$(basename "$file")" "$peer_views" \
    "$peer_size" "$out/peers/$name" </dev/null >&2; then
    echo "report.sh: scripts/peers.sh failed on $name: the report has no peers for it" >&2
    return 0
  fi
  "$volsweep" "$file" --tf "$tf" --spacing "$spacing" --name "${name}_unshaded" --no-shading --to "$unshaded_to" \
    --ta 0 --nearest \
    --views "$peer_views" --size "$peer_size" -o "$out" --peers "$out/peers/$name" "${resume[@]}" </dev/null >/dev/null
  cpu_now
  timings+="| ${name}_unshaded + peers (${peer_size}) | | | $((SECONDS - t0)) | $((cpu - c0)) |"$'\n'
}

# Every headerless raw dataset of the manifest, with its spacing (the first three numbers) and transfer function.
while IFS=$'\t' read -r file dims _type spacing _source _desc _sha _notes tf; do
  [[ $file == *.raw.gz ]] || continue
  name=${file%.raw.gz}
  wanted "$name" || continue
  spacing=$(grep -oE '[0-9]+(\.[0-9]+)?' <<<"$spacing" | head -3 | paste -sd,)
  sweep "$name" "$datasets/$file" "$datasets/$tf" "$spacing" "$dims"
  for p in $peers; do
    if [[ $name == "$p"* ]]; then peers_of "$name" "$datasets/$file" "$datasets/$tf" "$spacing"; fi
  done
done < <(tail -n +2 "$datasets/MANIFEST.tsv")

# One synthetic phantom: CT-like shells in Hounsfield units with the CT transfer function.
if wanted phantom; then
  mkdir -p "$out/phantom"
  "$build/datasets/volphantom" shells --dims "$phantom_dims" --type int16 -o "$out/phantom" </dev/null >/dev/null
  sweep "phantom_shells_${phantom_dims}_int16" "$out/phantom/shells_${phantom_dims}_int16.raw" \
    "$datasets/cranium_ct.tf.json" 1,1,1 "$(tr x ' ' <<<"$phantom_dims")"
fi

"$volsweep" --report-only -o "$out" >/dev/null
total=$((SECONDS - start))
cpu_now
rm -f "$out/.times"
device=$(vulkaninfo --summary 2>/dev/null | awk -F'= ' '/deviceName/ { print $2; exit }' || true)
cat >>"$out/report.md" <<MD
## This run (scripts/report.sh)

$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPU cores, Vulkan device: ${device:-unknown}.

**Sweeps:** images ${size}, ${views} views (azimuth 360 i / ${views}, elevation 0), step 0.5 voxel, nearest
sampling, Phong shading with a headlight, the grid T_o {${to}} x T_a {${ta}} degrees on every dataset. Volumes of
${big_voxels} voxels or more are swept box-averaged over ${downsample}^3 blocks (named NAME_at_DIMS below and in
their sections).

**Peers:** ${peer_list} (scripts/peers.sh, unshaded as they render) on: ${peers:-none}, at ${peer_size} with
${peer_views} views on the full-size volumes, compared in the NAME_unshaded sections with our unshaded casters at
T_o = T_a = 0, same size, views and sample distance. Those sections also sweep T_o {${unshaded_to}}: without
shading the regions are segmented without normals (T_a does not apply), as volprep --no-normals does.

**Why these sizes (the 30-minute budget on 2 cores with lavapipe).** Measured on this machine: the 30-setting
sweep of headsq (0.38 M voxels, 4 views of 256x256) cost 93 CPU-s while the primitive caster was rendered at every
setting and 45 CPU-s now that its renders are the reference's (it reads no regions or fields: its images and times
do not depend on the thresholds); PC is then three quarters of the render time, ACD and EACD a tenth each. On the
full-size teapot (11.7 M voxels) a setting costs about 7.5 CPU-s, two thirds of it segmentation and the fields,
which grow with the voxels; the volume is uploaded once per setting, not per render. At full size the twelve
volumes would cost about 50 CPU-s per setting, 25 minutes of the budget on an idle machine for the sweeps alone.
Box-averaging the five volumes of 7 M voxels or more by 2 per axis (8 times fewer voxels to segment and build
fields for) brings the sweeps to about 30 CPU-s per setting (15 minutes at most); the peers and our 512x512
renders on the three CT volumes add 1-2 minutes each. Larger images or more views scale the render part linearly.
The table below gives this run's seconds per dataset; "Where the time went" above splits them by stage and caster.

| dataset | dims | swept at | seconds | CPU seconds |
|---|---|---|---:|---:|
${timings}
**Whole report: ${total} s wall, ${cpu} s CPU** (user + system of all its processes; the wall time depends on
what else runs on the machine).
MD
echo "$out/report.md (${total} s wall, ${cpu} s CPU)"
