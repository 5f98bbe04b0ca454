#include "bench/peers/volpack_peer.h"

#include <volpack.h>

#include <chrono>
#include <cstdint>
#include <memory>

#include "core/errors.h"

namespace vr {
namespace {

struct ContextDeleter {
    void operator()(vpContext* c) const { vpDestroyContext(c); }
};
using Context = std::unique_ptr<vpContext, ContextDeleter>;

void check(vpContext* vpc, vpResult r, const char* what) {
    if (r != VP_OK)
        throw std::runtime_error(std::string("VolPack ") + what + ": " + vpGetErrorString(vpGetError(vpc)));
}

// VolPack's object space puts voxel sample v at (v - len/2) / maxlen (the largest dimension spans the unit
// cube); our cubic lattice puts voxel v's centre at origin + (v + 1/2) u. This maps the first to the second.
void objectToWorld(const GridGeometry& g, const CubicLattice& cubes, vpMatrix4 m) {
    const int maxLen = std::max({cubes.dims.x, cubes.dims.y, cubes.dims.z});
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[r][c] = r == c ? 1.0 : 0.0;
    for (int a = 0; a < 3; ++a) {
        m[a][a] = cubes.size * maxLen;
        m[a][3] = g.origin[a] + cubes.size * (0.5 * cubes.dims[a] + 0.5);
    }
}

// World -> eye: x right, y up and z along our forward. VolPack's manual has the viewer look down -z, but its
// shear-warp composites from +z in eye space (checked against our reference on cranium_ct, whose two ends differ),
// so depth runs along the view direction here.
void worldToEye(const Camera& cam, vpMatrix4 m) {
    const Vec3d rows[3] = {cam.right, cam.up, cam.forward};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m[r][c] = rows[r][c];
        m[r][3] = -dot(rows[r], cam.eye);
    }
    m[3][0] = m[3][1] = m[3][2] = 0;
    m[3][3] = 1;
}

}  // namespace

PeerRun runVolPackPeer(const PeerScene& scene, const std::filesystem::path& outDir) {
    if (scene.views.front().projection != Projection::Orthographic)
        throw InputError("vr_peers: VolPack renders parallel projections only");
    const GridGeometry& g = scene.volume.grid;
    const auto setup = std::chrono::steady_clock::now();
    Context context(vpCreateContext());
    vpContext* vpc = context.get();

    // One 16-bit field: the TF table index of the voxel's value; it drives both the opacity (classifier table)
    // and the colour (a one-material lookup "shader" that returns the TF colour: no lighting). On the cubic lattice,
    // because VolPack corrects opacity for the distance between slices in voxels: with cubes of our reference step
    // that is exact for every view.
    const CubicLattice cubes(g);
    const std::size_t n = scene.table.opacity.size();
    if (n > 65536) throw InputError("vr_peers: VolPack's field holds at most 65536 table entries");
    std::vector<std::uint16_t> voxels;
    voxels.reserve(voxelCount(cubes.dims));
    for (int z = 0; z < cubes.dims.z; ++z)
        for (int y = 0; y < cubes.dims.y; ++y)
            for (int x = 0; x < cubes.dims.x; ++x)
                voxels.push_back(std::uint16_t(scene.tableIndex(scene.volume.values[cubes.sourceIndex(g, x, y, z)])));
    std::vector<float> opacity(n), colour(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        opacity[i] = float(scene.table.opacity[i]);
        for (int c = 0; c < 3; ++c) colour[3 * i + c] = 255 * scene.table.colour[i][c];  // VolPack shades in 0..255
    }
    const int sx = 2, sy = sx * cubes.dims.x, sz = sy * cubes.dims.y;
    check(vpc, vpSetVolumeSize(vpc, cubes.dims.x, cubes.dims.y, cubes.dims.z), "volume size");
    check(vpc, vpSetVoxelSize(vpc, 2, 1, 1, 1), "voxel size");
    check(vpc, vpSetVoxelField(vpc, 0, 2, 0, int(n - 1)), "voxel field");
    check(vpc, vpSetRawVoxels(vpc, voxels.data(), int(voxels.size() * 2), sx, sy, sz), "voxels");
    check(vpc, vpSetClassifierTable(vpc, 0, 0, opacity.data(), int(opacity.size() * sizeof(float))), "classifier");
    check(vpc, vpSetLookupShader(vpc, 3, 1, 0, colour.data(), int(colour.size() * sizeof(float)), 0, nullptr, 0),
          "shader");
    // Every voxel with any opacity enters the run-length encoding, as every such voxel counts in ours.
    check(vpc, vpSetd(vpc, VP_MIN_VOXEL_OPACITY, 0.0), "min voxel opacity");
    check(vpc, vpSetd(vpc, VP_MAX_RAY_OPACITY, scene.options.ert), "max ray opacity");
    check(vpc, vpClassifyVolume(vpc), "classify");  // the three run-length encoded copies, one per axis

    const int w = scene.options.width, h = scene.options.height;
    std::vector<unsigned char> rgba(std::size_t(w) * h * 4);
    check(vpc, vpSetImage(vpc, rgba.data(), w, h, w * 4, VP_RGBA), "image");
    vpMatrix4 model;
    objectToWorld(g, cubes, model);
    check(vpc, vpCurrentMatrix(vpc, VP_MODEL), "model matrix");
    check(vpc, vpSetMatrix(vpc, model), "model matrix");
    const double radius = 0.5 * length(g.extent());
    const double setupMs = millisecondsSince(setup);

    PeerRun run = runViews("volpack", scene, outDir, [&](std::size_t i, Image& out) {
        const Camera& cam = scene.views[i];
        vpMatrix4 view;
        worldToEye(cam, view);
        check(vpc, vpCurrentMatrix(vpc, VP_VIEW), "view matrix");
        check(vpc, vpSetMatrix(vpc, view), "view matrix");
        check(vpc, vpCurrentMatrix(vpc, VP_PROJECT), "projection");
        check(vpc, vpIdentityMatrix(vpc), "projection");
        const double hw = cam.halfHeight * w / h;
        check(vpc, vpWindow(vpc, VP_PARALLEL, -hw, hw, -cam.halfHeight, cam.halfHeight, 0, 4 * radius), "window");
        const auto start = std::chrono::steady_clock::now();
        check(vpc, vpRenderClassifiedVolume(vpc), "render");
        const double ms = millisecondsSince(start);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c)
                    out.pixel(x, y)[c] = rgba[(std::size_t(h - 1 - y) * w + x) * 4 + c] / 255.f;
        return ms;
    });
    run.setupMs = setupMs;
    run.notes = "shear-warp: one bilinear sample per slice of the principal axis (no sample distance; VolPack "
                "corrects opacity for the slice spacing along the ray), pre-classified opacity/colour per voxel, "
                "anisotropic volumes resampled to cubic voxels of the smallest spacing, "
                "8-bit image, single-threaded; setup = vpClassifyVolume (run-length encoding)";
    return run;
}

}  // namespace vr
