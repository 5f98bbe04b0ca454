#!/usr/bin/env bash
# The main job: render a real head MRI shipped by Debian (Colin27 T1, mricron-data) in one command, then prepare it
# once with volprep and render the prepared file, as a study rendered again and again would.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh mricron-data
bash scripts/build.sh
mkdir -p out
input=/usr/share/mricron/templates/ch2.nii.gz
# The defaults: --caster auto, trilinear sampling (post-classified), Phong shading. The volume's axes are the
# patient's (RAS: y anterior, z superior): the camera is raised 90 degrees from its default place on +z to +y, the
# front, with +z up, so the head is seen upright, and the orbit turns about the vertical as a turntable.
build/volrender/volrender "$input" --tf datasets/tf/mri_head.tf.json --size 512x512 --up 0,0,1 --elevation 90 \
  -o out/ch2.png --stats out/ch2.stats.json --heatmap out/ch2.heat.png
build/preprocess/volprep "$input" --tf datasets/tf/mri_head.tf.json --to 0.01 --ta 3 -o out/ch2.volprep
build/volrender/volrender out/ch2.volprep --size 512x512 --up 0,0,1 --elevation 90 --views 8 -o out/ch2_orbit.png
echo "Wrote out/ch2.png (with out/ch2.heat.png and out/ch2.stats.json), out/ch2.volprep and out/ch2_orbit_000..007.png"
