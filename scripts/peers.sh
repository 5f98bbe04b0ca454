#!/usr/bin/env bash
# The peer renderers side by side (docs/BENCH.md "Peers"): VTK's fixed-point CPU and OpenGL GPU ray casters (on Mesa
# llvmpipe), VolPack and OpenVDB's vdb_render, with our CPU reference, on the same views of one dataset.
#   scripts/peers.sh DATASET [VIEWS] [SIZE] [OUTDIR]
#   USER_SETTINGS=1 scripts/peers.sh DATASET [VIEWS] [SIZE] [OUTDIR]
# DATASET: a file in the shared datasets folder or the start of its name (boston_teapot, cranium_ct, ...): the
# MANIFEST gives its spacing and transfer function. "smoke": one 64x64 view of vtk_headmr (a few seconds).
# Defaults: 8 views, 512x512, out/peers/NAME. BUILD_DIR (default build) is the build folder; THREADS (default 2);
# ELEVATION (default 0) the views' elevation in degrees;
# PEER_LIST (comma-separated, default all: ours-cpu-primitive,vtk-fixed-point,vtk-gpu,volpack,vdb_render).
# Every peer renders nearest and unshaded, unless USER_SETTINGS=1 (vr_peers --user-settings): the settings users
# render with, trilinear and shaded (our Phong material, one headlight), for our reference and both VTK mappers;
# VolPack and vdb_render cannot and are skipped (a row says why). Its default OUTDIR is out/peers/NAME_user.
# Prints the settings and a Markdown table; OUTDIR/peers.json has the settings and, per peer and view, the
# milliseconds and the image (EXR, linear).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
datasets=${VR_DATASETS_DIR:-$root/../shared/datasets}
build=${BUILD_DIR:-build}

dataset=${1:?usage: scripts/peers.sh DATASET [VIEWS] [SIZE] [OUTDIR]}
views=${2:-8}
size=${3:-512x512}
if [[ $dataset == smoke ]]; then
  dataset=vtk_headmr_48x62x42_uint8.raw.gz views=${2:-1} size=${3:-64x64}
fi

source scripts/manifest_row.sh
manifest_row peers.sh "$dataset"
user_settings=${USER_SETTINGS:-0}
if [[ $user_settings != 0 && $user_settings != 1 ]]; then
  echo "peers.sh: USER_SETTINGS=$user_settings: expected 0 or 1" >&2
  exit 1
fi
suffix=""
if [[ $user_settings == 1 ]]; then suffix=_user; fi
out=${4:-out/peers/${file%%.raw.gz}$suffix}

bash scripts/install-deps.sh libvolpack1-dev libopenvdb-tools xvfb xauth libgl1-mesa-dri libglx-mesa0
[[ -f $build/CMakeCache.txt ]] || cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build "$build" --target vr_peers -j 2

mkdir -p "$out"
# VTK's OpenGL render windows need an X display, even off screen: a virtual one.
cmd=("$build/bench/peers/vr_peers" "$datasets/$file" --tf "$datasets/$tf" --spacing "$spacing"
  --views "$views" --size "$size" --elevation "${ELEVATION:-0}" --threads "${THREADS:-2}" -o "$out")
if [[ -n ${PEER_LIST:-} ]]; then cmd+=(--peers "$PEER_LIST"); fi
if [[ $user_settings == 1 ]]; then cmd+=(--user-settings); fi
echo "+ xvfb-run -a ${cmd[*]}" >&2
start=$(date +%s.%N)
xvfb-run -a -s "-screen 0 1280x1024x24" "${cmd[@]}"
echo "(all peers: $(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.1f", e - s }') s; $out/peers.json)"
