#!/usr/bin/env bash
# The whole process, from the source volume file to the first image, against VTK's (docs/BENCH.md "What users
# feel"): wall seconds and peak resident memory of each process, as `/usr/bin/time -f '%e %M'` gives them, of
#   (a) volrender VOLUME --tf TF: our one command (load, classify, segment, the caster's field, upload, render);
#   (b) vtk_whole_process VOLUME --tf TF: VTK's fixed-point CPU ray caster in one process, as a VTK user's script
#       does it (bench/peers/vtk_whole_process.cpp: load, TF, mapper, render, PNG), under xvfb-run;
#   (c) volprep VOLUME --tf TF -o PREPARED, then volrender PREPARED: prepare once (default fields), render many.
# Same settings for all: trilinear (VTK: linear), shaded (our Phong material, one white headlight), orthographic
# (Camera::fit), azimuth 0, elevation ELEVATION, SIZE, sample distance 0.5 x the smallest spacing.
#   scripts/whole_process.sh DATASET [SIZE]
# DATASET: a file in the shared datasets folder or the start of its name (boston_teapot, cranium_ct, ...), resolved
# from MANIFEST.tsv as scripts/peers.sh does (file, transfer function, spacing). SIZE default 512x512.
# CLINICAL=XxYxZ: instead of DATASET itself, a CT of that size made from it (bench/make_clinical_volume: resampled
# trilinearly over the same extent, Gaussian noise of 20 in its units added), e.g. CLINICAL=512x512x1024 cranium_ct.
# BUILD_DIR (default build); THREADS (default 2): VTK's threads; RUNS (default 3): runs of each, taking turns;
# ELEVATION (default 20); OUTDIR (default out/whole_process/NAME): the images, the prepared file, each run's log.
# Prints the settings and a Markdown table: per tool the median wall seconds and median peak resident MB over the
# runs, the source volume's bytes, and each figure's ratio to volrender's one command.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
datasets=${VR_DATASETS_DIR:-$root/../shared/datasets}
build=${BUILD_DIR:-build}
threads=${THREADS:-2}
runs=${RUNS:-3}
elevation=${ELEVATION:-20}

dataset=${1:?usage: scripts/whole_process.sh DATASET [SIZE]}
size=${2:-512x512}
if ! [[ $threads =~ ^[1-9][0-9]*$ && $runs =~ ^[1-9][0-9]*$ ]]; then
  echo "whole_process.sh: THREADS and RUNS must be positive integers" >&2
  exit 1
fi

source scripts/manifest_row.sh
manifest_row whole_process.sh "$dataset"
name=${file%%.raw.gz}
out=${OUTDIR:-out/whole_process/$name}

bash scripts/install-deps.sh libvolpack1-dev xvfb xauth libgl1-mesa-dri libglx-mesa0 time
[[ -f $build/CMakeCache.txt ]] || cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build "$build" --target volrender volprep vtk_whole_process make_clinical_volume -j 2 >&2

if [[ -n ${CLINICAL:-} ]]; then
  name=clinical_ct_$CLINICAL
  out=${OUTDIR:-out/whole_process/$name}
fi
mkdir -p "$out"
rm -f "$out"/*.time
volume=$datasets/$file
if [[ -n ${CLINICAL:-} ]]; then
  echo "+ make_clinical_volume --from $file --dims $CLINICAL" >&2
  read -r volume spacing < <("$build/bench/make_clinical_volume" --from "$file" --dims "$CLINICAL" -o "$out")
  file=$(basename "$volume")
  row=$(awk -F'\t' -v d="${CLINICAL//x/ }" -v t="$(cut -f3 <<<"$row")" 'BEGIN { OFS = FS } { $2 = d; $3 = t; print }' \
    <<<"$row")
fi
# The voxels' bytes in the file's type (dims x type size); the file's own bytes (gzip, or raw) beside them.
voxel_bytes=$(awk -F'\t' '{ split($2, d, " "); b = ($3 ~ /^uint8/) ? 1 : ($3 ~ /^float/) ? 4 : 2;
  printf "%d", d[1] * d[2] * d[3] * b }' <<<"$row")
file_bytes=$(stat -c %s "$volume")
cat "$volume" "$datasets/$tf" >/dev/null  # in the page cache before the first run, so that no tool pays the disk

view=(--spacing "$spacing" --size "$size" --elevation "$elevation")
ours=("$build/volrender/volrender" "$volume" --tf "$datasets/$tf" "${view[@]}" -o "$out/volrender.png")
vtk=("$build/bench/peers/vtk_whole_process" "$volume" --tf "$datasets/$tf" "${view[@]}" --threads "$threads"
  -o "$out/vtk.png")
prep=("$build/preprocess/volprep" "$volume" --tf "$datasets/$tf" --spacing "$spacing" -o "$out/prepared.volprep")
render=("$build/volrender/volrender" "$out/prepared.volprep" --size "$size" --elevation "$elevation"
  -o "$out/volrender_prepared.png")

# TAG COMMAND...: runs COMMAND under /usr/bin/time (VTK's inside xvfb-run: the X server's start is not VTK's, a
# user has a display; VTK still needs one), appending "seconds kilobytes" to $out/TAG.time and the command's output
# to $out/TAG.log.
timed() {
  local tag=$1
  shift
  local cmd=(/usr/bin/time -f '%e %M' -o "$out/$tag.run" "$@")
  if [[ $tag == vtk ]]; then cmd=(xvfb-run -a -s "-screen 0 1280x1024x24" "${cmd[@]}"); fi
  if ! "${cmd[@]}" >"$out/$tag.log" 2>&1; then
    echo "whole_process.sh: $tag failed (its output: $out/$tag.log):" >&2
    tail -5 "$out/$tag.log" >&2
    exit 1
  fi
  tail -1 "$out/$tag.run" >>"$out/$tag.time"
}
echo "+ ${ours[*]}" >&2
echo "+ xvfb-run -a ${vtk[*]}" >&2
echo "+ ${prep[*]} && ${render[*]}" >&2
for ((i = 1; i <= runs; i++)); do  # the tools take turns, so that a busy machine slows them alike
  timed volrender "${ours[@]}"
  timed vtk "${vtk[@]}"
  timed volprep "${prep[@]}"
  timed volrender_prepared "${render[@]}"
  echo "  run $i of $runs done" >&2
done
paste -d' ' "$out/volprep.time" "$out/volrender_prepared.time" |
  awk '{ print $1 + $3, ($2 > $4 ? $2 : $4) }' >"$out/prepare_once.time"

# Median of a column of a .time file (the mean of the two middle values for an even count, docs/BENCH.md).
median() {
  sort -g <(cut -d' ' -f"$2" "$out/$1.time") |
    awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
base_s=$(median volrender 1)
base_kb=$(median volrender 2)
caster=$(grep -oE '[a-z]+ caster' "$out/volrender.log" | head -1 || true)
device=$("$build/volrender/volrender" --list-devices 2>/dev/null | head -1 | sed 's/^[0-9]*: //' || true)
vtk_version=$(grep -oE 'VTK [0-9.]+' "$out/vtk.log" | head -1 || true)
cores=$(nproc)

echo
echo "Whole process, $name ($(tr , x <<<"${spacing}") spacing): source file to a ${size} PNG, trilinear, shaded" \
  "(Phong, one white headlight), orthographic, azimuth 0, elevation $elevation, sample distance 0.5 x the smallest" \
  "spacing. Median of $runs runs each, taking turns, on $cores cores; \`/usr/bin/time -f '%e %M'\`: wall seconds" \
  "and peak resident memory of the process (VTK's timed inside xvfb-run: the X server is not counted)."
echo "Threads: volrender at its defaults: TBB and the Vulkan device (${device:-unknown}) on all $cores cores" \
  "(${caster:-the caster auto chose}); vtk_whole_process ($vtk_version) $threads thread(s)" \
  "(vtkFixedPointVolumeRayCastMapper::SetNumberOfThreads, vtkMultiThreader's global maximum)."
echo "Source volume: $file, $voxel_bytes bytes of voxels ($file_bytes in the file); our loader holds them as" \
  "float for both tools (VTK's wrapped without a copy)."
echo
echo "| tool | median wall s | median peak resident MB | source volume bytes | wall / volrender | peak / volrender |"
echo "|---|---:|---:|---:|---:|---:|"
row() {  # TAG LABEL
  local s kb
  s=$(median "$1" 1)
  kb=$(median "$1" 2)
  awk -v l="$2" -v s="$s" -v kb="$kb" -v b="$voxel_bytes" -v bs="$base_s" -v bk="$base_kb" \
    'BEGIN { printf "| %s | %.2f | %.0f | %d | %.2f | %.2f |\n", l, s, kb * 1024 / 1e6, b, s / bs, kb / bk }'
}
row volrender "(a) volrender VOLUME --tf (one command)"
row vtk "(b) vtk_whole_process (VTK fixed-point, $threads threads)"
row volprep "(c) volprep VOLUME --tf (prepare once)"
row volrender_prepared "(c) volrender PREPARED (each render after)"
row prepare_once "(c) volprep + volrender PREPARED (peak: the larger)"
echo
awk -v v="$(median vtk 1)" -v vk="$(median vtk 2)" -v s="$base_s" -v k="$base_kb" 'BEGIN {
  printf "VTK / volrender (one command): wall %.2f, peak resident memory %.2f.\n", v / s, vk / k }'
echo "Images: $out/volrender.png, $out/vtk.png, $out/volrender_prepared.png; each run's output: $out/*.log"
