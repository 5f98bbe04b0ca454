// What every peer renders: one volume, its transfer function tabulated per scalar value, and our orbit of views.
#pragma once
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "core/volume.h"
#include "preprocess/classify/transfer_function.h"
#include "preprocess/load/load_volume.h"
#include "render/camera.h"
#include "render/render_settings.h"
#include "render/span.h"

namespace vr {

struct PeerSceneOptions {
    std::filesystem::path volume, transferFunction;
    RawOptions raw;
    int views = 8, width = 512, height = 512;
    double elevationDeg = 0;  // of every view of the orbit
    double stepVoxels = 0.5;  // our --step: voxels of the smallest spacing
    double ert = 0.99;        // our early ray termination
    int threads = 2;
    // false: every peer samples nearest and unshaded (emission-absorption only), the algorithm comparison.
    // true (--user-settings): what users render with: trilinear (linear) interpolation, shaded with our Phong
    // material (render/span.h ShadingModel) and one white headlight; the peers that cannot are skipped.
    bool userSettings = false;
    // composite, or MIP (--blend mip): VTK's MAXIMUM_INTENSITY blend, our CPU reference's mip; the peers without a
    // MIP are skipped.
    Blend blend = Blend::Composite;
};

// The render settings every peer is set up for, in words: the caption of vr_peers' table.
std::string settingsDescription(const PeerSceneOptions& options);

struct PeerScene {
    PeerSceneOptions options;
    Volume volume;
    TransferFunction tf;
    // The TF at every integer value from the volume's minimum to its maximum for integer volumes (exact there, as
    // our classification samples it), else at 4096 values over the range: every peer gets its tables from here.
    SampledTransferFunction table;
    std::vector<Camera> views;  // azimuth 360 i / N, the elevation asked, orthographic: Camera::fit as ours use it

    double referenceStep() const { return volume.grid.smallestSpacing(); }  // the TF's opacity is per this length
    double sampleDistance() const { return options.stepVoxels * referenceStep(); }
    std::size_t tableIndex(float value) const;  // nearest table entry of a scalar value
};

PeerScene loadPeerScene(const PeerSceneOptions& options);

// PeerScene::table of a volume and transfer function: the TF at every integer value from the volume's minimum to
// its maximum for integer volumes, else at 4096 values over the range.
SampledTransferFunction peerTable(const Volume& volume, const TransferFunction& tf);

// The grid resampled (nearest) onto cubic voxels of its smallest spacing, for the peers whose opacity or ray
// stepping assumes cubic voxels (VolPack, vdb_render): the same lattice for isotropic grids. Voxel v of it is
// centred at grid.origin + (v + 1/2) * size.
struct CubicLattice {
    Vec3i dims;
    double size = 1;
    std::array<std::vector<int>, 3> source;  // per axis: the grid voxel each cubic voxel takes its value from

    explicit CubicLattice(const GridGeometry& grid);
    std::size_t sourceIndex(const GridGeometry& grid, int x, int y, int z) const {
        return linearIndex(grid.dims, source[0][x], source[1][y], source[2][z]);
    }
};

}  // namespace vr
