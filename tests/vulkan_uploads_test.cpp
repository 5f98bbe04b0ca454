// What a Vulkan render puts on the device: only what it reads, one upload for many renders, and a volume
// split into bricks that each fit the device's image limits rendering the same image, with the same leaps, as the
// unsplit one.
#include <gtest/gtest.h>

#include <bit>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/classify/transfer_function.h"
#include "render/block_extrema.h"
#include "render/cpu_renderer.h"
#include "render/view_octants.h"
#include "support/prepare.h"
#include "support/vulkan.h"

namespace vr {
namespace {

using test::bytesByName;
using test::expectNoValidationErrors;
using test::kCasters;
using test::renderSettings;

// 20-pixel tiles on 32x24 images: full and partial tiles.
VulkanRenderer& whole() { return test::vulkanRenderer(20); }

// At least three bricks along every axis (the test volumes' scalars, a byte or two a voxel, would fit the smallest
// image limits that a brick with its margin of two voxels meets), and images of at most 40 texels along an axis:
// ACD / EACD, whose octant slabs stack along z, split along z again. One tile per image: the dispatches are many.
constexpr ImageLimits kSmallImages{.maxDimension = 40, .minBricks = {3, 3, 3}};
VulkanRenderer& bricked() {
    static VulkanRenderer r(test::vulkanContext(), 32, kSmallImages);
    return r;
}

const TransferFunction& phantomTf() {
    static const TransferFunction tf = parseTransferFunction(R"({
        "Points": [0, 0, 0.5, 0, 40, 0.1, 0.5, 0, 100, 0.05, 0.5, 0, 200, 0.3, 0.5, 0, 255, 0.9, 0.5, 0],
        "RGBPoints": [0, 0.9, 0.5, 0.4, 128, 0.3, 0.8, 0.2, 255, 1, 1, 0.9]
    })", "phantom TF");
    return tf;
}

PreparedVolume prepare(const Volume& volume, double to, double ta, bool trilinear) {
    return test::prepareVolume(volume, phantomTf(), {to, ta, true, trilinear});
}

ViewParams view(double az, double el, Projection projection = Projection::Orthographic, double fov = 30) {
    return test::orbitView(az, el, 32, 24, projection, fov);
}

std::size_t texels(const Vec3i& d) { return std::size_t(d.x) * d.y * d.z; }

using Bytes = std::map<std::string, std::size_t>;

// What every render reads: the scalars in their own type and the transfer table, 16 bytes an entry; and more.
Bytes always(const PreparedVolume& p, const Bytes& more = {}) {
    Bytes b{{"scalars", p.grid().voxels() * scalarBytes(p.scalars.sourceType)},
            {"table", p.classification.table.size() * 16}};
    b.insert(more.begin(), more.end());
    return b;
}

TEST(VulkanUploads, ARenderUploadsOnlyWhatItReads) {
    const Volume v = shellsPhantom({20, 18, 16});
    const PreparedVolume p = prepare(v, 0.02, 10, false);
    const std::size_t voxels = v.grid.voxels();
    const Camera ortho = Camera::fit(v.grid, view(30, 20));
    const Camera persp = Camera::fit(v.grid, view(0, 0, Projection::Perspective));
    ASSERT_EQ(v.sourceType, ScalarType::Int16);
    ASSERT_GT(p.classification.table.size(), 1u);

    whole().render(p, ortho, renderSettings(Caster::Primitive, false));
    EXPECT_EQ(bytesByName(whole().lastUploads()),
              (Bytes{{"scalars", voxels * 2}, {"table", p.classification.table.size() * 16}}));
    whole().render(p, ortho, renderSettings(Caster::Primitive, true));  // shading reads the same scalars
    EXPECT_EQ(bytesByName(whole().lastUploads()), always(p));
    whole().render(p, ortho, renderSettings(Caster::PC, false));
    EXPECT_EQ(bytesByName(whole().lastUploads()), always(p, {{"pc", voxels}}));
    // Orthographic: exactly the one octant of the view direction.
    whole().render(p, ortho, renderSettings(Caster::ACD, false));
    EXPECT_EQ(bytesByName(whole().lastUploads()), always(p, {{"acd", voxels}}));
    whole().render(p, ortho, renderSettings(Caster::EACD, true));
    EXPECT_EQ(bytesByName(whole().lastUploads()), always(p, {{"eacd", voxels * 4}}));

    // Perspective: the octants its rays have, which viewOctants finds exactly here (down -z from the centre line:
    // the rays spread over x and y, never toward +z).
    unsigned seen = 0;
    for (int y = 0; y < persp.height; ++y)
        for (int x = 0; x < persp.width; ++x) {
            const Vec3d d = persp.ray(x + 0.5, y + 0.5).direction;
            seen |= 1u << octantOf(d.x, d.y, d.z);
        }
    EXPECT_EQ(viewOctants(persp), seen);
    EXPECT_EQ(seen, 0b11110000u);
    for (Caster c : {Caster::ACD, Caster::EACD}) {
        whole().render(p, persp, renderSettings(c, false));
        const std::size_t texel = c == Caster::ACD ? 1 : 4;
        EXPECT_EQ(bytesByName(whole().lastUploads()), always(p, {{std::string(casterName(c)), 4 * voxels * texel}}));
    }
    for (const UploadedResource& u : whole().lastUploads()) EXPECT_EQ(u.brick, 0) << u.name;  // one brick
    expectNoValidationErrors();
}

// The device memory of an orthographic, shaded EACD render of an int16 volume with the default EACD code (log16):
// the scalars' 2 bytes a voxel and one octant of log16's 2. Shading uploads nothing (the casters take the
// gradient from the scalars); the table is per entry of the transfer function, not per voxel.
TEST(VulkanUploads, ShadedEacdOfAnInt16VolumeTakesFourBytesAVoxel) {
    const Volume v = shellsPhantom({20, 18, 16});
    ASSERT_EQ(v.sourceType, ScalarType::Int16);
    PreparedVolume p = prepare(v, 0.02, 10, false);
    quantiseEACD(p.fields, kDefaultExtentCode);
    ASSERT_EQ(kDefaultExtentCode, ExtentCode::Log16);
    const std::size_t voxels = v.grid.voxels(), tableBytes = p.classification.table.size() * 16;
    RenderSettings s = renderSettings(Caster::EACD, true);
    const Camera ortho = Camera::fit(v.grid, view(30, 20));
    whole().render(p, ortho, s);
    EXPECT_EQ(bytesByName(whole().lastUploads()),
              (Bytes{{"scalars", voxels * 2}, {"eacd", voxels * 2}, {"table", tableBytes}}));
    std::size_t perVoxel = 0;
    for (const UploadedResource& u : whole().lastUploads())
        if (u.name != "table") perVoxel += u.bytes;
    EXPECT_LE(perVoxel, 4 * voxels);
    // An upload kept for many renders holds the same.
    const GpuVolume volume = whole().upload(p, {{Caster::EACD}, viewOctants(ortho)});
    EXPECT_EQ(volume.uploadedBytes(), 4 * voxels + tableBytes);
    expectNoValidationErrors();
}

// Fields built for the octants of some views only (volrender's one-command path) serve those views, and render what
// the full fields render; a view in another octant is refused, naming the octants.
TEST(VulkanUploads, FieldsOfSomeOctantsServeTheirViewsOnly) {
    const Volume v = shellsPhantom({20, 18, 16});
    const PreparedVolume full = prepare(v, 0.02, 10, false);
    const Camera ortho = Camera::fit(v.grid, view(30, 20)), opposite = Camera::fit(v.grid, view(210, -20));
    const unsigned held = viewOctants(ortho);
    ASSERT_EQ(held & viewOctants(opposite), 0u);
    PreparedVolume some = full;
    for (int o = 0; o < kOctants; ++o)
        if (!(held >> o & 1u)) {
            some.fields.acd[o] = {};
            some.fields.eacd[o] = {};
        }
    for (Caster c : {Caster::ACD, Caster::EACD}) {
        const RenderSettings s = renderSettings(c, true);
        EXPECT_EQ(maxAbsDifference(whole().render(some, ortho, s).image, whole().render(full, ortho, s).image), 0.0f)
            << casterName(c);
        EXPECT_THROW(whole().render(some, opposite, s), InputError) << casterName(c);
    }
    expectNoValidationErrors();
}

// A transfer table is one texel buffer, a texel an entry: one beyond the device's maxTexelBufferElements is refused
// before anything is uploaded, naming the table's entries and the limit.
TEST(VulkanUploads, TableBeyondTheTexelBufferLimitIsRefused) {
    const Volume v = shellsPhantom({12, 10, 8});
    const PreparedVolume p = prepare(v, 0.02, 10, false);
    const std::size_t entries = p.classification.table.size();
    ASSERT_GT(entries, 2u);
    const Camera cam = Camera::fit(v.grid, view(30, 20));
    VulkanRenderer fits(test::vulkanContext(), 20, ImageLimits{.maxTableEntries = entries});
    EXPECT_NO_THROW(fits.render(p, cam, renderSettings(Caster::Primitive)));
    VulkanRenderer small(test::vulkanContext(), 20, ImageLimits{.maxTableEntries = entries - 1});
    for (Caster c : kCasters) {
        try {
            small.render(p, cam, renderSettings(c));
            ADD_FAILURE() << "uploaded a table beyond the texel buffer limit";
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("transfer table of " + std::to_string(entries) + " entries"), std::string::npos)
                << what;
            EXPECT_NE(what.find("maxTexelBufferElements " + std::to_string(entries - 1)), std::string::npos)
                << what;
            EXPECT_NE(what.find("at most " + std::to_string(entries - 1) + " entries"), std::string::npos) << what;
        }
    }
    expectNoValidationErrors();
}

// The scalars are read in their own type: values that are none of it (a corrupt volume) are refused, not converted.
TEST(VulkanUploads, ScalarsOutsideTheirTypeAreRefused) {
    const Volume v = enginePhantom({12, 10, 8});
    ASSERT_EQ(v.sourceType, ScalarType::UInt8);
    const PreparedVolume p = prepare(v, 0.02, 10, false);
    const Camera cam = Camera::fit(v.grid, view(30, 20));
    for (float bad : {256.0f, -1.0f, 0.5f, std::numeric_limits<float>::quiet_NaN()}) {
        PreparedVolume corrupt = p;
        corrupt.scalars.values[corrupt.scalars.values.size() / 2] = bad;
        EXPECT_THROW(whole().render(corrupt, cam, renderSettings(Caster::Primitive)), InputError) << bad;
    }
    EXPECT_NO_THROW(whole().render(p, cam, renderSettings(Caster::Primitive)));
    expectNoValidationErrors();
}

// Every storage-image format the casters read is checked when a renderer is made, and a device without one (or
// without shaderStorageImageExtendedFormats) is refused with the name of what it lacks.
TEST(VulkanUploads, DevicesWithoutTheCastersImageFormatsAreRefusedByName) {
    const VulkanContext& ctx = test::vulkanContext();
    const vk::PhysicalDeviceFeatures features = ctx.physicalDevice().getFeatures();
    auto real = [&](vk::Format f) { return ctx.physicalDevice().getFormatProperties(f); };
    EXPECT_NO_THROW(requireCasterImageSupport("this device", features, real));
    ASSERT_EQ(casterImageFormats().size(), 5u);

    vk::PhysicalDeviceFeatures without = features;
    without.shaderStorageImageExtendedFormats = VK_FALSE;
    try {
        requireCasterImageSupport("a device", without, real);
        ADD_FAILURE() << "accepted a device without shaderStorageImageExtendedFormats";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("shaderStorageImageExtendedFormats"), std::string::npos) << e.what();
    }
    for (const CasterImageFormat& missing : casterImageFormats()) {
        auto lacking = [&](vk::Format f) {
            vk::FormatProperties props = real(f);
            if (f == missing.format) props.optimalTilingFeatures &= ~vk::FormatFeatureFlagBits::eStorageImage;
            return props;
        };
        try {
            requireCasterImageSupport("a device", features, lacking);
            ADD_FAILURE() << "accepted a device without " << missing.name;
        } catch (const std::runtime_error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(std::string(missing.name) + " as a storage image"), std::string::npos) << what;
            EXPECT_NE(what.find("VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT"), std::string::npos) << what;
        }
    }
    EXPECT_EQ(casterImageFormats()[0].format, scalarFormat(ScalarType::Int16));  // integer scalars, in words
}

// Regions made without normals let a leap carry one shade across a change of normal: a volume uploaded for many
// renders refuses shaded leaping as a one-off render does (checkRenderInputs), and renders the rest.
TEST(VulkanUploads, ShadedLeapingOverRegionsMadeWithoutNormalsIsRefused) {
    const Volume v = shellsPhantom({12, 10, 8});
    const PreparedVolume p = test::prepareVolume(v, phantomTf(), {0.02, 10, false, false});
    const Camera cam = Camera::fit(v.grid, view(30, 20));
    const GpuVolume volume = whole().upload(p, {{std::begin(kCasters), std::end(kCasters)}, viewOctants(cam)});
    for (Caster c : {Caster::PC, Caster::ACD, Caster::EACD}) {
        EXPECT_THROW(whole().render(volume, cam, renderSettings(c, true)), InputError) << casterName(c);
        EXPECT_THROW(whole().render(p, cam, renderSettings(c, true)), InputError) << casterName(c);
        EXPECT_NO_THROW(whole().render(volume, cam, renderSettings(c, false))) << casterName(c);
    }
    EXPECT_NO_THROW(whole().render(volume, cam, renderSettings(Caster::Primitive, true)));
    expectNoValidationErrors();
}

// lavapipe's uploads write texels in place, into linear images whose rows are padded (to 64 bytes, and to 64 rows
// a slice); a GPU's go through a staging buffer. Both give the same images and leaps, shaded and unshaded, with
// volume sides that are no multiple of the padding.
// A volume read for the device alone (readPrepared without float scalars) holds its integer scalars in their own
// type: uploaded as they are, whole and in bricks, they render what their floats render.
TEST(VulkanUploads, ScalarsInTheirOwnTypeRenderWhatTheirFloatsRender) {
    const PreparedVolume p = prepare(shellsPhantom({21, 18, 13}), 0.02, 10, true);
    const ScalarType type = p.scalars.sourceType;
    ASSERT_NE(type, ScalarType::Float32);
    PreparedVolume own = p;
    own.scalars.stored.resize(p.grid().voxels() * scalarBytes(type));
    ASSERT_EQ(narrowScalars(p.scalars.values.data(), p.grid().voxels(), type, own.scalars.stored.data()),
              p.grid().voxels());
    own.scalars.values.clear();
    const Camera cam = Camera::fit(p.grid(), view(30, 20, Projection::Perspective));
    for (VulkanRenderer* renderer : {&whole(), &bricked()})
        for (Caster c : kCasters) {
            SCOPED_TRACE(casterName(c));
            const RenderSettings s = renderSettings(c, true);
            const RenderResult floats = renderer->render(p, cam, s);
            const RenderResult stored = renderer->render(own, cam, s);
            EXPECT_EQ(maxAbsDifference(stored.image, floats.image), 0.0);
            EXPECT_EQ(stored.iterations, floats.iterations);
        }
    // What reads the scalars on the host refuses a volume without their floats, rather than reading nothing.
    EXPECT_THROW(renderCpu(own, cam, renderSettings(Caster::Primitive, true)), std::logic_error);
    EXPECT_THROW(blockExtrema(own.scalars), std::logic_error);
    expectNoValidationErrors();
}

TEST(VulkanUploads, StagedUploadsRenderWhatInPlaceUploadsRender) {
    static VulkanRenderer staged(test::vulkanContext(), 20, ImageLimits{0, 0, true});
    const PreparedVolume p = prepare(shellsPhantom({21, 18, 13}), 0.02, 10, false);
    for (const Camera& cam : {Camera::fit(p.grid(), view(30, 20)),
                              Camera::fit(p.grid(), view(200, -25, Projection::Perspective))})
        for (Caster c : kCasters)
            for (bool shading : {false, true}) {
                SCOPED_TRACE(std::string(casterName(c)) + (shading ? " shaded" : ""));
                const RenderResult inPlace = whole().render(p, cam, renderSettings(c, shading));
                const RenderResult copied = staged.render(p, cam, renderSettings(c, shading));
                EXPECT_EQ(maxAbsDifference(copied.image, inPlace.image), 0.0);
                EXPECT_EQ(copied.iterations, inPlace.iterations);
                EXPECT_EQ(bytesByName(staged.lastUploads()), bytesByName(whole().lastUploads()));
            }
    expectNoValidationErrors();
}

// The casters' pixels written to device memory and copied to the host (a discrete GPU's path, forced here) are
// the pixels written to host memory, for every caster, on full and partial tiles, for both eyes of a stereo pair
// (the right eye reprojected in device memory, its re-cast pixels as a list), and a later, larger image grows the
// frame's buffers.
TEST(VulkanUploads, OutputCopiedFromDeviceMemoryEqualsOutputWrittenToTheHost) {
    VulkanRenderer host(test::vulkanContext(), 20, {}, VulkanRenderer::OutputMemory::Host);
    VulkanRenderer device(test::vulkanContext(), 20, {}, VulkanRenderer::OutputMemory::Device);
    const PreparedVolume p = prepare(shellsPhantom({21, 18, 13}), 0.02, 10, false);
    for (const ViewParams& v : {test::orbitView(30, 20, 16, 12), view(200, -25, Projection::Perspective)}) {
        const Camera cam = Camera::fit(p.grid(), v);
        for (Caster c : kCasters) {
            SCOPED_TRACE(std::string(casterName(c)) + " " + std::to_string(cam.width));
            const RenderResult written = host.render(p, cam, renderSettings(c, true));
            const RenderResult copied = device.render(p, cam, renderSettings(c, true));
            EXPECT_EQ(maxAbsDifference(copied.image, written.image), 0.0);
            EXPECT_EQ(copied.iterations, written.iterations);
        }
    }
    const StereoPair pair = stereoPair(Camera::fit(p.grid(), view(30, 20, Projection::Perspective)), p.grid(), 2,
                                       std::nullopt);
    const GpuVolume onHost = host.upload(p, {{Caster::EACD}, kAllOctants});
    const GpuVolume onDevice = device.upload(p, {{Caster::EACD}, kAllOctants});
    // Composite reprojects the left eye's bands, MIP its pixels.
    for (const auto& [caster, blend] :
         {std::pair{Caster::EACD, Blend::Composite}, std::pair{Caster::Primitive, Blend::MIP}}) {
        SCOPED_TRACE(casterName(caster));
        RenderSettings s = renderSettings(caster, true);
        s.blend = blend;
        const StereoRender written = host.renderStereo(onHost, pair, s, true);
        const StereoRender copied = device.renderStereo(onDevice, pair, s, true);
        EXPECT_GT(copied.recastFraction, 0);
        EXPECT_LT(copied.recastFraction, 1);
        EXPECT_EQ(copied.recast, written.recast);
        EXPECT_EQ(maxAbsDifference(copied.right.image, written.right.image), 0.0);
    }
    expectNoValidationErrors();
}

// Without ray counts the casters' colours alone come back, in host memory and through device memory alike: the
// same image as a counted render, no counts, and a ray that fails still fails the render (its colour says so).
TEST(VulkanUploads, ColoursWithoutRayCountsAreTheCountedRendersAndFailuresStillReport) {
    VulkanRenderer host(test::vulkanContext(), 20, {}, VulkanRenderer::OutputMemory::Host);
    VulkanRenderer device(test::vulkanContext(), 20, {}, VulkanRenderer::OutputMemory::Device);
    const PreparedVolume p = prepare(shellsPhantom({21, 18, 13}), 0.02, 10, false);
    const Camera cam = Camera::fit(p.grid(), test::orbitView(30, 20, 16, 12));
    for (VulkanRenderer* r : {&host, &device})
        for (Caster c : kCasters) {
            SCOPED_TRACE(std::string(casterName(c)) + (r == &host ? " host" : " device"));
            RenderSettings s = renderSettings(c, true);
            const RenderResult counted = r->render(p, cam, s);
            s.rayCounts = false;
            const RenderResult colours = r->render(p, cam, s);
            EXPECT_EQ(maxAbsDifference(colours.image, counted.image), 0.0);
            EXPECT_TRUE(colours.iterations.empty() && colours.samples.empty());
            EXPECT_FALSE(counted.iterations.empty());
            s.maxIterationsPerRay = 2;
            EXPECT_THROW(r->render(p, cam, s), std::runtime_error);
        }
    expectNoValidationErrors();
}

// One upload for an orbit and every caster: each render reads (and reports) its own part, and renders what a
// render that uploads for itself renders.
TEST(VulkanUploads, OneUploadServesAnOrbitOfEveryCaster) {
    const Volume v = enginePhantom({24, 20, 18});
    const PreparedVolume p = prepare(v, 0.02, 10, false);
    const std::size_t voxels = v.grid.voxels();
    std::vector<Camera> cameras;
    unsigned octants = 0;
    for (int i = 0; i < 4; ++i) {
        cameras.push_back(Camera::fit(v.grid, view(90.0 * i + 10, 20)));
        octants |= viewOctants(cameras.back());
    }
    ASSERT_EQ(std::popcount(octants), 4);
    const GpuVolume volume = whole().upload(p, {{std::begin(kCasters), std::end(kCasters)}, octants});
    ASSERT_EQ(v.sourceType, ScalarType::UInt8);
    // The hier field: 2 bytes per block of 4^3 voxels and octant.
    const std::size_t blocks = voxelCount(p.fields.hier.blocks);
    EXPECT_EQ(blocks, 6u * 5 * 5);
    const Bytes all = always(p, {{"pc", voxels}, {"acd", voxels * 4}, {"eacd", voxels * 16}, {"hier", blocks * 8}});
    EXPECT_EQ(bytesByName(volume.uploads()), all);
    EXPECT_EQ(volume.uploadedBytes(), voxels * (1 + 1 + 4 + 16) + blocks * 8 + p.classification.table.size() * 16);

    for (const Camera& cam : cameras)
        for (Caster c : kCasters)
            for (bool shading : {true, false}) {
                SCOPED_TRACE(std::string(casterName(c)) + (shading ? " shaded" : " unshaded"));
                const RenderResult shared = whole().render(volume, cam, renderSettings(c, shading));
                Bytes read = always(p);
                if (c != Caster::Primitive) read[std::string(casterName(c))] = all.at(std::string(casterName(c)));
                EXPECT_EQ(bytesByName(whole().lastUploads()), read);
                const RenderResult own = whole().render(p, cam, renderSettings(c, shading));
                EXPECT_EQ(maxAbsDifference(shared.image, own.image), 0.0);
                EXPECT_EQ(shared.iterations, own.iterations);
            }

    // What the upload lacks is the caller's error, named.
    const Camera persp = Camera::fit(v.grid, view(0, 0, Projection::Perspective));
    EXPECT_THROW(whole().render(volume, persp, renderSettings(Caster::ACD, false)), std::invalid_argument);  // octants
    const GpuVolume plain = whole().upload(p, {{Caster::Primitive}, 0});
    EXPECT_THROW(whole().render(plain, cameras[0], renderSettings(Caster::PC, false)), std::invalid_argument);
    EXPECT_NO_THROW(whole().render(plain, cameras[0], renderSettings(Caster::Primitive, false)));
    EXPECT_NO_THROW(whole().render(plain, cameras[0], renderSettings(Caster::Primitive, true)));  // nothing more
    expectNoValidationErrors();
}

// Bricks: their cores tile the volume, their images hold the core and two neighbour voxels each side (a shaded
// trilinear sample reads the central differences of its cell's corners), and the uploads give each brick's bytes;
// the table is uploaded once.
void expectBrickFigures(const GpuVolume& volume, const PreparedVolume& p, int slots) {
    const Vec3i dims = p.grid().dims;
    std::size_t cores = 0;
    for (const Brick& b : volume.bricks().bricks()) {
        cores += texels(b.hi - b.lo + Vec3i{1, 1, 1});
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(b.imageLo[a], std::max(0, b.lo[a] - 2));
            EXPECT_EQ(b.imageLo[a] + b.imageDims[a] - 1, std::min(dims[a] - 1, b.hi[a] + 2));
        }
    }
    EXPECT_EQ(cores, p.grid().voxels());
    EXPECT_FALSE(volume.uploads().empty());
    const auto& bricks = volume.bricks().bricks();
    int tables = 0;
    for (const UploadedResource& u : volume.uploads()) {
        ASSERT_LT(std::size_t(u.brick), bricks.size());
        if (u.name == "table") {
            ++tables;
            EXPECT_EQ(u.bytes, p.classification.table.size() * 16);
            continue;
        }
        if (u.name == "hier") {  // 2 bytes a block that the brick's images touch, per octant
            const BrickBlocks blocks = brickBlocks(bricks[u.brick].imageLo, bricks[u.brick].imageDims,
                                                   p.fields.hier.blockShift);
            EXPECT_EQ(u.bytes, 2 * slots * texels(blocks.count)) << "hier brick " << u.brick;
            continue;
        }
        const Vec3i imageDims = bricks[u.brick].imageDims;
        if (u.name == "scalars") {  // 32-bit words of the row's scalars, the last one padded
            const int perWord = scalarsPerTexel(p.scalars.sourceType);
            EXPECT_EQ(u.bytes, 4 * texels({(imageDims.x + perWord - 1) / perWord, imageDims.y, imageDims.z}))
                << "scalars brick " << u.brick;
            continue;
        }
        const std::size_t n = texels(imageDims);
        const std::map<std::string, std::size_t> perTexel{{"pc", 1},
                                                          {"acd", slots},
                                                          {"eacd", 4 * slots}};
        EXPECT_EQ(u.bytes, n * perTexel.at(u.name)) << u.name << " brick " << u.brick;
    }
    EXPECT_EQ(tables, 1);
}

// Split and unsplit renders of every caster, nearest and trilinear, orthographic and perspective (outside and
// inside the volume): the same image, the same fetches and samples per ray.
void expectSplitEqualsUnsplit(const std::string& name, const PreparedVolume& p) {
    const GridGeometry& grid = p.grid();
    std::vector<std::pair<std::string, Camera>> cameras{
        {"ortho az 30 el 20", Camera::fit(grid, view(30, 20))},
        {"ortho along -z", Camera::fit(grid, view(0, 0))},
        {"ortho az -135 el -35", Camera::fit(grid, view(-135, -35))},
        {"persp az -60 el 10", Camera::fit(grid, view(-60, 10, Projection::Perspective))},
        {"persp az 20 el 30 fov 90", Camera::fit(grid, view(20, 30, Projection::Perspective, 90))}};
    // From the centre: rays of seven octants, split on every axis, so seven passes.
    cameras.emplace_back("persp inside", test::perspectiveCamera(grid.centre(), normalize(Vec3d{1, 1, 1}),
                                                                 normalize(Vec3d{1, -1, 0}), 32, 24, 120));
    for (const auto& [camName, cam] : cameras)
        for (Caster c : kCasters)
            for (bool trilinear : {false, true}) {
                SCOPED_TRACE(name + " " + camName + " " + std::string(casterName(c)) +
                             (trilinear ? " trilinear" : " nearest"));
                const RenderSettings s = renderSettings(c, true, trilinear);
                const RenderResult unsplit = whole().render(p, cam, s);
                ASSERT_EQ(whole().lastUploads().size(), c == Caster::Primitive ? 2u : 3u);  // one brick, the table
                const RenderResult split = bricked().render(p, cam, s);
                EXPECT_LT(maxAbsDifference(split.image, unsplit.image), 1e-4);
                EXPECT_EQ(split.iterations, unsplit.iterations);
                EXPECT_EQ(split.samples, unsplit.samples);
            }
    const unsigned inside = viewOctants(cameras.back().second);
    EXPECT_EQ(std::popcount(inside), 7);  // all but the one behind the eye
    const GpuVolume volume = bricked().upload(p, {{std::begin(kCasters), std::end(kCasters)}, inside});
    const Vec3i counts = volume.bricks().counts();
    EXPECT_GT(counts.x, 1);
    EXPECT_GT(counts.y, 1);
    EXPECT_GT(counts.z, 1);
    expectBrickFigures(volume, p, 7);
}

TEST(VulkanUploadsInBricks, SplitRendersEqualUnsplitOnPhantoms) {
    expectSplitEqualsUnsplit("shells", prepare(shellsPhantom({16, 14, 12}), 0.02, 10, true));
    expectSplitEqualsUnsplit("engine", prepare(enginePhantom({18, 14, 12}), 0, 0, true));
    expectSplitEqualsUnsplit("noise", prepare(noisePhantom({12, 10, 14}, 3), 0.05, 20, true));
    expectNoValidationErrors();
}

// The synthetic volumes of the stiff and extreme cases (render_cases.h): a long thin stack seen along it, and
// white noise with opaque and transparent voxels under odd spacings.
TEST(VulkanUploadsInBricks, SplitRendersEqualUnsplitOnSyntheticVolumes) {
    const PreparedVolume slabs = test::syntheticPrepared({{2, 3, 60}, {1, 1, 1}, {0, 0, 0}}, 1.0, [](const Vec3i& v) {
        return test::VoxelClass{v.z % 2 ? 0.02 : 1e-4, {1, 0.2, 0}};
    });
    const PreparedVolume noise =
        test::syntheticPrepared({{13, 7, 11}, {1, 2.5, 0.7}, {-3, 0, 2}}, 0.7, [](const Vec3i& v) {
            const unsigned h = unsigned(v.x * 73856093 ^ v.y * 19349663 ^ v.z * 83492791) % 100;
            return test::VoxelClass{h < 10 ? 0.0 : h > 90 ? 1.0 : h / 100.0, {h / 100.0, 0.5, 1 - h / 100.0}};
        });
    for (const PreparedVolume* p : {&slabs, &noise}) {
        const GridGeometry& g = p->grid();
        const std::vector<Camera> cameras{
            test::orthoCamera({1, 1.5, 70}, {0, 0, -1}, {1, 0, 0}, 5, 5, 2.5),  // along the stack, voxel edges
            Camera::fit(g, view(45, 35.264389682754654)),
            Camera::fit(g, view(150, -20, Projection::Perspective, 70)),
            test::perspectiveCamera(g.centre(), normalize(Vec3d{-1, 0.3, 1}), normalize(Vec3d{1, 0, 1}), 17, 13, 140)};
        for (const Camera& cam : cameras)
            for (Caster c : kCasters)
                for (double step : {0.25, 1.7}) {
                    RenderSettings s = renderSettings(c, false);
                    s.stepVoxels = step;
                    s.ert = step > 1 ? 1.0 : 0.99;
                    const RenderResult unsplit = whole().render(*p, cam, s);
                    const RenderResult split = bricked().render(*p, cam, s);
                    SCOPED_TRACE(std::string(casterName(c)) + " step " + std::to_string(step));
                    EXPECT_LT(maxAbsDifference(split.image, unsplit.image), 1e-4);
                    EXPECT_EQ(split.iterations, unsplit.iterations);
                    EXPECT_EQ(split.samples, unsplit.samples);
                }
    }
    expectNoValidationErrors();
}

// A limit on one image dimension alone: unsplit where one octant fits, split along z only where the stacked
// octant slabs of a perspective view exceed it (as a 512^3 volume's four slabs exceed 2048 texels).
TEST(VulkanUploadsInBricks, StackedOctantSlabsSplitAlongZ) {
    const Volume v = shellsPhantom({16, 16, 16});
    const PreparedVolume p = prepare(v, 0.02, 10, false);
    VulkanRenderer slabLimited(test::vulkanContext(), 20, ImageLimits{32, 0});
    const Camera ortho = Camera::fit(v.grid, view(30, 20));
    const Camera persp = Camera::fit(v.grid, view(0, 0, Projection::Perspective));
    const GpuVolume one = slabLimited.upload(p, {{Caster::ACD}, viewOctants(ortho)});
    EXPECT_EQ(one.bricks().counts(), (Vec3i{1, 1, 1}));
    const GpuVolume four = slabLimited.upload(p, {{Caster::ACD}, viewOctants(persp)});
    EXPECT_EQ(four.bricks().counts().x, 1);
    EXPECT_EQ(four.bricks().counts().y, 1);
    EXPECT_GE(four.bricks().counts().z, 3);
    EXPECT_LE(four.bricks().largestImage().z * 4, 32);
    expectBrickFigures(four, p, 4);
    for (Caster c : {Caster::ACD, Caster::EACD}) {
        const RenderResult split = slabLimited.render(p, persp, renderSettings(c, true));
        const RenderResult unsplit = whole().render(p, persp, renderSettings(c, true));
        EXPECT_LT(maxAbsDifference(split.image, unsplit.image), 1e-4) << casterName(c);
        EXPECT_EQ(split.iterations, unsplit.iterations) << casterName(c);
    }
    expectNoValidationErrors();
}

// Only what cannot be split is refused: an image limit below one voxel and its neighbours (5^3 int16 scalars).
TEST(VulkanUploadsInBricks, UnsplittableVolumeIsRefusedClearly) {
    const Volume v = shellsPhantom({8, 8, 8});
    const PreparedVolume p = prepare(v, 0, 0, false);
    VulkanRenderer tiny(test::vulkanContext(), 20, ImageLimits{0, 2 * 5 * 5 * 5 - 1});
    try {
        tiny.render(p, Camera::fit(v.grid, view(0, 0)), renderSettings(Caster::Primitive, false));
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot be split"), std::string::npos) << e.what();
    }
    expectNoValidationErrors();
}

// Front-to-back orders: along every axis a ray of the given signs crosses bricks in increasing order.
TEST(VulkanUploadsInBricks, FrontToBackOrderFollowsEveryAxisSign) {
    const BrickGrid grid({10, 9, 8}, {3, 2, 4});
    ASSERT_EQ(grid.bricks().size(), 24u);
    EXPECT_EQ(grid.splitAxes(), 7u);
    for (unsigned signs = 0; signs < 8; ++signs) {
        const std::vector<int> order = grid.frontToBack(signs);
        std::vector<int> rank(order.size());
        for (std::size_t i = 0; i < order.size(); ++i) rank[order[i]] = int(i);
        const auto& b = grid.bricks();
        for (std::size_t i = 0; i < b.size(); ++i)
            for (std::size_t j = 0; j < b.size(); ++j) {
                bool before = i != j;  // i lies before j on every axis for these signs (or level with it)
                for (int a = 0; a < 3; ++a) {
                    const bool down = signs >> a & 1;
                    before = before && (down ? b[i].lo[a] >= b[j].lo[a] : b[i].lo[a] <= b[j].lo[a]);
                }
                if (before) {
                    EXPECT_LT(rank[i], rank[j]) << "signs " << signs << " bricks " << i << ", " << j;
                }
            }
    }
}

}  // namespace
}  // namespace vr
