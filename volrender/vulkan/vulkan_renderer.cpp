#include "volrender/vulkan/vulkan_renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <tbb/parallel_for.h>

#include "core/errors.h"
#include "render/ray_setup.h"
#include "render/render_checks.h"
#include "render/span.h"
#include "render/view_octants.h"
#include "shaders/device_contract.h"
#include "shaders/embedded_shaders.h"
#include "shaders/stereo_reprojection.h"
#include "volrender/vulkan/ray_pieces.h"
#include "volrender/vulkan/stereo_reprojector.h"

namespace vr {
namespace {

// The field's image formats, one binding each (a storage image is read in the format it declares).
constexpr vk::Format kFieldFormats[3] = {vk::Format::eR8Uint, vk::Format::eR16Uint, vk::Format::eR8G8B8A8Uint};
constexpr uint32_t kFieldBindings[3] = {device::kBindingField8, device::kBindingField16, device::kBindingFieldRGBA8};

// The uploaded decode table is the shader's array of kExtentTableEntries uvec4.
static_assert(kExtentTableEntries == device::kExtentTableEntries && sizeof(ExtentTableEntry) == 16);
// The unused words image stands in for the stored gradients too.
static_assert(kGradientFormat == kWordFormat);

// The casters' module ids, and the values of the extent code's specialization constant.
int deviceCaster(Caster caster) {
    switch (caster) {
        case Caster::Primitive: return device::kPrimitive;
        case Caster::PC: return device::kPC;
        case Caster::ACD: return device::kACD;
        case Caster::EACD: return device::kEACD;
        case Caster::Blocks: return device::kBlocks;
        case Caster::Hier: return device::kHier;
    }
    throw std::logic_error("deviceCaster: a caster the device does not know");
}

int deviceBlend(Blend blend) {
    switch (blend) {
        case Blend::Composite: return device::kBlendComposite;
        case Blend::MIP: return device::kBlendMIP;
        case Blend::MinIP: return device::kBlendMinIP;
        case Blend::Average: return device::kBlendAverage;
        case Blend::Iso: return device::kBlendIso;
    }
    throw std::logic_error("deviceBlend: a blend the device does not know");
}

int deviceScalarType(ScalarType type) {
    switch (type) {
        case ScalarType::UInt8: return device::kScalarUInt8;
        case ScalarType::Int16: return device::kScalarInt16;
        case ScalarType::UInt16: return device::kScalarUInt16;
        case ScalarType::Float32: return device::kScalarFloat32;
    }
    throw std::logic_error("deviceScalarType: a scalar type the device does not know");
}

int deviceExtentCode(ExtentCode code) {
    switch (code) {
        case ExtentCode::Exact: return device::kExact;
        case ExtentCode::Log16: return device::kLog16;
        case ExtentCode::Joint8: return device::kJoint8;
    }
    throw std::logic_error("deviceExtentCode: an extent code the device does not know");
}

// The value of the labels' specialization constant for an uploaded volume.
int deviceLabels(const GpuVolume& volume) {
    if (!volume.labelled()) return device::kNoLabels;
    return volume.labelType() == ScalarType::UInt16 ? device::kLabelsUInt16 : device::kLabelsUInt8;
}

device::vec4 toDevice(const Vec3d& v) { return {float(v.x), float(v.y), float(v.z), 0}; }
device::ivec4 toDevice(const Vec3i& v) { return {v.x, v.y, v.z, 0}; }

// x + y: the double rounded to float, and what that rounding left (an infinity stays one, with y = 0).
device::vec2 floatPair(double x) {
    const float hi = float(x);
    return {hi, std::isinf(hi) ? 0.0f : float(x - double(hi))};
}

// The casters count a ray's samples in a 32-bit integer (shaders/ray_setup.glsl).
void requireDeviceLattice(const GridGeometry& grid, double stepVoxels) {
    constexpr double kDeviceSamples = 0x1p31;
    const double samples = std::ceil(length(grid.extent()) / (stepVoxels * grid.smallestSpacing()));
    if (samples <= kDeviceSamples) return;
    char text[240];
    std::snprintf(text, sizeof text,
                  "--step %g: too small for this volume on a Vulkan device: a ray across it takes up to %.3g "
                  "samples, more than the %.0f the casters count (render with --cpu)",
                  stepVoxels, samples, kDeviceSamples);
    throw InputError(text);
}

device::CasterParams makeParams(const GpuVolume& volume, const Camera& camera, const RenderSettings& s) {
    const GridGeometry& grid = volume.grid();
    const std::array<int, kOctants>& slots = volume.octantSlot();
    device::CasterParams p{};
    p.eye = toDevice(camera.eye);
    p.forward = toDevice(camera.forward);
    p.right = toDevice(camera.right);
    p.up = toDevice(camera.up);
    p.gridOrigin = toDevice(grid.origin);
    p.spacing = toDevice(grid.spacing);
    p.halfHeight = float(camera.halfHeight);
    p.dt = float(s.stepVoxels * grid.smallestSpacing());
    p.dims = toDevice(grid.dims);
    p.imageSize = {camera.width, camera.height};
    p.maxIterations = uint32_t(std::clamp<long long>(s.maxIterationsPerRay, 1, device::kCutShort - 1));
    p.loopProbe = device::kLoopProbeTrips;
    static_assert(kOctants == 8, "octantSlot holds two ivec4 of slots");
    p.octantSlot[0] = {slots[0], slots[1], slots[2], slots[3]};
    p.octantSlot[1] = {slots[4], slots[5], slots[6], slots[7]};
    if (s.lightDirection) {
        const Vec3d l = normalize(*s.lightDirection);
        p.light = {float(l.x), float(l.y), float(l.z), 1};
    }
    const ShadingModel m;
    p.material = {float(m.ambient), float(m.diffuse), float(m.specular), float(m.shininess)};
    p.background = {float(s.background.x), float(s.background.y), float(s.background.z), 0};
    p.ertDepth = floatPair(terminationDepth(s.ert));
    const TablePlacement& table = volume.tablePlacement();
    p.tableLo = float(table.lo);
    p.tableInverseStep = float(1 / table.step);  // exactly 1 for an integer volume's step of 1
    p.tableLastEntry = float(table.entries - 1);
    p.flatGradient = float(table.flatGradient);
    p.isoValue = float(s.isoValue);
    p.opacityLength = float(table.referenceStep);
    const FlatTableEnds& flat = s.opaqueValues ? table.opaqueFlat : table.flat;
    p.flatAbove = float(flat.above);
    p.flatBelow = float(flat.below);
    static_assert(device::kBlockLevels == 4, "blockLevelZ holds an ivec4");
    const std::array<int, device::kBlockLevels>& levelZ = volume.blockLevelZ();
    p.blockLevelZ = {levelZ[0], levelZ[1], levelZ[2], levelZ[3]};
    const RayClip clip = RayClip::of(grid, s);
    p.cropLo = toDevice(clip.lo);
    p.cropHi = toDevice(clip.hi);
    for (std::size_t i = 0; i < clip.planes.size(); ++i) {
        const ClipPlane& plane = clip.planes[i];
        p.clipPlanes[i] = {float(plane.normal.x), float(plane.normal.y), float(plane.normal.z), float(plane.offset)};
    }
    p.clipPlaneCount = int(clip.planes.size());
    p.jitter = s.jitter ? 1 : 0;
    p.labelLastEntry = volume.labelLastEntry();
    p.opaqueValues = s.opaqueValues ? 1 : 0;
    p.frustumShift = float(camera.shift);
    p.gradientExponentBase = volume.gradientExponentBase();
    p.hierBlockShift = volume.hierBlockShift();
    return p;
}

}  // namespace

VulkanRenderer::VulkanRenderer(const VulkanContext& ctx, int tileSize, const ImageLimits& limits,
                               OutputMemory output)
    : ctx_(ctx),
      tileSize_(tileSize != kAutoTile ? tileSize : ctx.info().type == "cpu" ? 512 : 1024),
      limits_(limits),
      stagedOutput_(output == OutputMemory::Auto ? ctx.info().type == "discrete" : output == OutputMemory::Device),
      interleavedRows_(ctx.info().type == "cpu") {
    if (tileSize < 0)
        throw std::invalid_argument("tile size " + std::to_string(tileSize) + ": expected pixels > 0, or 0 for the "
                                    "device's choice");
    const vk::raii::Device& device = ctx.device();
    requireCasterImageSupport(ctx.info().name, ctx.physicalDevice().getFeatures(),
                              [&](vk::Format f) { return ctx.physicalDevice().getFormatProperties(f); });
    pool_ = vk::raii::CommandPool(device, vk::CommandPoolCreateInfo({}, ctx.queueFamily()));

    using T = vk::DescriptorType;
    const auto compute = vk::ShaderStageFlagBits::eCompute;
    std::vector<vk::DescriptorSetLayoutBinding> bindings{
        {device::kBindingParams, T::eStorageBuffer, 1, compute},
        {device::kBindingOutColours, T::eStorageBuffer, 1, compute},
        {device::kBindingOutCounts, T::eStorageBuffer, 1, compute},
        {device::kBindingRayStates, T::eStorageBuffer, 1, compute},
        {device::kBindingExtentTable, T::eUniformBuffer, 1, compute},
        {device::kBindingTransferTable, T::eStorageTexelBuffer, 1, compute},
        {device::kBindingLabelTable, T::eStorageTexelBuffer, 1, compute},
        {device::kBindingPixelList, T::eStorageBuffer, 1, compute},
        {device::kBindingStereoBands, T::eStorageBuffer, 1, compute}};
    bindings.emplace_back(device::kBindingScalarWords, T::eStorageImage, 1, compute);
    bindings.emplace_back(device::kBindingScalarsFloat, T::eStorageImage, 1, compute);
    for (uint32_t binding : kFieldBindings) bindings.emplace_back(binding, T::eStorageImage, 1, compute);
    bindings.emplace_back(device::kBindingBlockExtrema, T::eStorageImage, 1, compute);
    bindings.emplace_back(device::kBindingGradients, T::eStorageImage, 1, compute);
    bindings.emplace_back(device::kBindingLabelWords, T::eStorageImage, 1, compute);
    setLayout_ = vk::raii::DescriptorSetLayout(device, vk::DescriptorSetLayoutCreateInfo({}, bindings));
    vk::PushConstantRange push(compute, 0, sizeof(device::TilePush));
    vk::DescriptorSetLayout layout = *setLayout_;
    pipelineLayout_ = vk::raii::PipelineLayout(device, vk::PipelineLayoutCreateInfo({}, layout, push));
    timer_ = std::make_unique<DeviceTimer>(ctx);
    const uint8_t zeros[8] = {};
    unusedWords_ =
        std::make_unique<VolumeImage>(ctx, pool_, Vec3i{1, 1, 1}, kWordFormat, zeros, formatBytes(kWordFormat));
    const vk::Format floats = scalarFormat(ScalarType::Float32);
    unusedFloats_ = std::make_unique<VolumeImage>(ctx, pool_, Vec3i{1, 1, 1}, floats, zeros, formatBytes(floats));
    for (int i = 0; i < 3; ++i)
        unusedFields_[i] = std::make_unique<VolumeImage>(ctx, pool_, Vec3i{1, 1, 1}, kFieldFormats[i], zeros,
                                                         formatBytes(kFieldFormats[i]));
    unusedBlockExtrema_ = std::make_unique<VolumeImage>(ctx, pool_, Vec3i{1, 1, 1}, kBlockExtremaFormat, zeros,
                                                        formatBytes(kBlockExtremaFormat));
    unusedLabelTable_ = std::make_unique<TexelTable>(ctx, pool_, std::vector<float>(4, 0.f));
}

VulkanRenderer::Variant VulkanRenderer::variantOf(const RenderSettings& settings, bool perspective, ScalarType type,
                                                  int labels, bool bricked, bool pixelList, ExtentCode eacdCode,
                                                  bool marginLeaps, bool stereoBands, int pieces) {
    // The hier caster's blocks are in log16, whatever code the volume's EACD has.
    if (settings.caster == Caster::Hier) eacdCode = ExtentCode::Log16;
    return {settings.caster, settings.blend, settings.trilinear,  settings.shading,
            eacdCode,        bricked,        perspective,         type,
            labels,          pixelList,      settings.gradients == Gradients::Stored,
            stereoBands,     marginLeaps,    pieces};
}

const vk::raii::Pipeline& VulkanRenderer::pipeline(Variant v) {
    // Only the EACD and hier casters read the code: the others share one pipeline whatever the volume's code. Only
    // composite and the iso-surface shade, and only a shaded variant reads gradients.
    v.shading = v.shading && (v.blend == Blend::Composite || v.blend == Blend::Iso);
    if (v.caster != Caster::EACD && v.caster != Caster::Hier) v.eacdCode = ExtentCode::Exact;
    v.storedGradients = v.storedGradients && v.shading;
    v.stereoBands = v.stereoBands && v.blend == Blend::Composite;
    std::lock_guard lock(pipelinesMutex_);
    auto it = pipelines_.find(v);
    if (it != pipelines_.end()) return it->second;
    // The module of the variant's caster and blend, plain where the variant needs none of the full one's features,
    // made once.
    const bool plain = v.labels == device::kNoLabels && !v.storedGradients && !v.stereoBands &&
                       v.blend == Blend::Composite;
    const std::tuple module{v.caster, v.blend, plain};
    auto shader = shaders_.find(module);
    if (shader == shaders_.end()) {
        const std::vector<uint32_t>* spirv = casterModule(deviceCaster(v.caster), deviceBlend(v.blend), plain);
        if (!spirv)
            throw std::logic_error("no caster module for --caster " + std::string(casterName(v.caster)) +
                                   " with --blend " + std::string(blendName(v.blend)) +
                                   " (a bug: checkBlend refuses the pair)");
        shader = shaders_.emplace(module, vk::raii::ShaderModule(ctx_.device(), vk::ShaderModuleCreateInfo({}, *spirv)))
                     .first;
    }
    // (constant id, value); booleans are 32-bit VkBool32 in specialization data.
    const std::array<std::pair<int, uint32_t>, 13> constants{{
        {device::kSpecIdTrilinear, v.trilinear ? 1u : 0u},
        {device::kSpecIdShading, v.shading ? 1u : 0u},
        {device::kSpecIdExtentCode, uint32_t(deviceExtentCode(v.eacdCode))},
        {device::kSpecIdBricked, v.bricked ? 1u : 0u},
        {device::kSpecIdPerspective, v.perspective ? 1u : 0u},
        {device::kSpecIdScalarType, uint32_t(deviceScalarType(v.scalarType))},
        {device::kSpecIdLabels, uint32_t(v.labels)},
        {device::kSpecIdPixelList, v.pixelList ? 1u : 0u},
        {device::kSpecIdStoredGradients, v.storedGradients ? 1u : 0u},
        {device::kSpecIdStereoBands, v.stereoBands ? 1u : 0u},
        {device::kSpecIdMarginLeaps, v.marginLeaps ? 1u : 0u},
        {device::kSpecIdPieces, uint32_t(v.pieces)},
        {device::kSpecIdPiecewise, v.pieces > 1 ? 1u : 0u}}};
    std::array<uint32_t, constants.size()> values;
    std::array<vk::SpecializationMapEntry, constants.size()> entries;
    for (std::size_t i = 0; i < constants.size(); ++i) {
        values[i] = constants[i].second;
        entries[i] = vk::SpecializationMapEntry(uint32_t(constants[i].first), uint32_t(i * sizeof(uint32_t)),
                                                sizeof(uint32_t));
    }
    vk::SpecializationInfo spec(entries, vk::ArrayProxyNoTemporaries<const uint32_t>(values));
    vk::PipelineShaderStageCreateInfo stage({}, vk::ShaderStageFlagBits::eCompute, *shader->second, "main", &spec);
    vk::raii::Pipeline p(ctx_.device(), nullptr, vk::ComputePipelineCreateInfo({}, stage, *pipelineLayout_));
    return pipelines_.emplace(v, std::move(p)).first->second;
}

void VulkanRenderer::preparePipeline(const RenderSettings& settings, Projection projection, ScalarType type) {
    // Steps users render with leap by the margin (leapsByTheMargin).
    pipeline(variantOf(settings, projection == Projection::Perspective, type, device::kNoLabels, false, false,
                       kDefaultExtentCode, true));
}

void VulkanRenderer::prepareStereoPipelines(const RenderSettings& settings, ScalarType type) {
    // A pair's cameras are perspective (stereoPair).
    const bool composite = settings.blend == Blend::Composite;
    pipeline(variantOf(settings, true, type, device::kNoLabels, false, false, kDefaultExtentCode, true, composite));
    // The pieces of a list of a sixteenth of the frame: the CTs' pairs re-cast about 5 % of the right eye.
    const int pieces = piecesFor(false, settings, recastPiecesAsked(1, 16));
    pipeline(variantOf(settings, true, type, device::kNoLabels, false, true, kDefaultExtentCode, true, false, pieces));
    reprojector().preparePipeline(composite);
}

std::size_t VulkanRenderer::pipelineCount() {
    std::lock_guard lock(pipelinesMutex_);
    return pipelines_.size() + std::size_t(reprojector().pipelineCount());
}

StereoReprojector& VulkanRenderer::reprojector() {
    std::call_once(reprojectorMade_, [this] { reprojector_ = std::make_unique<StereoReprojector>(ctx_); });
    return *reprojector_;
}

GpuVolume VulkanRenderer::upload(const PreparedVolume& prepared, const GpuVolumeContents& contents) {
    return deviceErrors([&] { return GpuVolume(ctx_, pool_, prepared, contents, limits_); });
}

VulkanRenderer::~VulkanRenderer() = default;

namespace {

int checkedPieces(int pieces, int lowest, const std::string& what) {
    if (pieces < lowest || pieces > device::kMostPieces)
        throw std::invalid_argument(what + ": " + std::to_string(pieces) + " is outside " + std::to_string(lowest) +
                                    " to " + std::to_string(device::kMostPieces));
    return pieces;
}

}  // namespace

void VulkanRenderer::setRecastPieces(int pieces) {
    recastPieces_ = checkedPieces(pieces, kAutoPieces, "re-cast pieces (0: the device's choice)");
}

void VulkanRenderer::setRayPieces(int pieces) { rayPieces_ = checkedPieces(pieces, 1, "ray pieces"); }

int VulkanRenderer::recastPiecesAsked(std::size_t listPixels, std::size_t framePixels) const {
    return recastPieces_ != kAutoPieces ? recastPieces_
                                        : raysPieces(ctx_.info().type == "discrete", listPixels, framePixels);
}

int VulkanRenderer::piecesFor(bool bricked, const RenderSettings& settings, int pieces) const {
    if (pieces <= 1 || settings.blend != Blend::Composite || bricked) return 1;
    const vk::PhysicalDeviceLimits limits = ctx_.physicalDevice().getProperties().limits;
    const int groupPixels = device::kWorkgroupSize * device::kWorkgroupSize;
    return std::max(1, std::min({pieces, int(limits.maxComputeWorkGroupInvocations) / groupPixels,
                                 int(limits.maxComputeWorkGroupSize[2])}));
}

RenderResult VulkanRenderer::render(const GpuVolume& volume, const Camera& camera, const RenderSettings& settings) {
    checkRender(volume, camera, settings);
    return deviceErrors([&] { return renderOnDevice(volume, camera, settings); });
}

void VulkanRenderer::checkRender(const GpuVolume& volume, const Camera& camera, const RenderSettings& settings) {
    checkRenderSettings(volume.grid(), volume.segmentation(), settings);
    checkLabelledBlend(volume.labelled(), settings);
    requireDeviceLattice(volume.grid(), settings.stepVoxels);
    volume.requireHolds(settings, viewOctants(camera));
    // The iso-surface is refined between two samples, which may lie in different bricks: one brick's images do not
    // hold the scalars of the other's.
    if (settings.blend == Blend::Iso && volume.bricks().bricks().size() > 1)
        throw InputError("--blend iso on a volume split into " + std::to_string(volume.bricks().bricks().size()) +
                         " bricks for this Vulkan device: the iso-surface is rendered from one brick only (render "
                         "with --cpu)");
    uploads_.clear();  // what this render reads of the volume
    for (const UploadedResource& u : volume.uploads())
        if (u.name == "scalars" || u.name == "table" || u.name == "label map" || u.name == "label table" ||
            (settings.readsStoredGradients() && u.name == "gradients") ||
            (settings.caster != Caster::Primitive && u.name == casterName(settings.caster)))
            uploads_.push_back(u);
}

RenderResult VulkanRenderer::render(const PreparedVolume& prepared, const Camera& camera,
                                    const RenderSettings& settings) {
    checkRenderInputs(prepared, settings);
    const auto start = std::chrono::steady_clock::now();
    const GpuVolume volume =
        upload(prepared, {{settings.caster}, viewOctants(camera), settings.readsStoredGradients()});
    RenderResult result = render(volume, camera, settings);
    result.wallMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

VulkanRenderer::PixelOutput::PixelOutput(const VulkanContext& ctx, std::size_t pixels, bool staged)
    : host(ctx, pixels * sizeof(device::uvec4),
           vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst) {
    if (staged)
        onDevice.emplace(ctx, pixels * sizeof(device::uvec4),
                         vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc);
}

VulkanRenderer::FrameBuffers::FrameBuffers(const VulkanContext& ctx, std::size_t pixels, bool staged)
    : pixels(pixels),
      params(ctx, sizeof(device::CasterParams), vk::BufferUsageFlagBits::eStorageBuffer),
      extentTable(ctx, sizeof(ExtentTable), vk::BufferUsageFlagBits::eUniformBuffer),  // decodes coded EACD
      // bound, never read, without a list (and as the bands without them)
      noList(ctx, 2 * sizeof(uint32_t), vk::BufferUsageFlagBits::eStorageBuffer),
      rayState(ctx, pixels * sizeof(device::RayState), vk::BufferUsageFlagBits::eStorageBuffer),
      colours(ctx, pixels, staged),
      counts(ctx, pixels, staged) {}

VulkanRenderer::FrameBuffers& VulkanRenderer::frameBuffers(std::size_t pixels) {
    if (!frame_ || frame_->pixels < pixels) {
        frame_.reset();  // the old ones freed before the larger are allocated
        frame_.emplace(ctx_, pixels, stagedOutput_);
    }
    return *frame_;
}

RenderResult VulkanRenderer::renderOnDevice(const GpuVolume& volume, const Camera& camera,
                                            const RenderSettings& settings, const PixelList* list,
                                            const StereoLeft* left) {
    const auto start = std::chrono::steady_clock::now();
    const vk::raii::Device& device = ctx_.device();
    // Rays in pieces (ray_pieces.h): a list's as it asks, a frame's as setRayPieces asks; never a stereo left eye's,
    // which records its bands along the whole ray.
    const bool bricked = volume.bricks().bricks().size() > 1;
    const int pieces = left ? 1 : piecesFor(bricked, settings, list ? list->pieces : rayPieces_);
    const Variant variant =
        variantOf(settings, camera.projection == Projection::Perspective, volume.scalarType(), deviceLabels(volume),
                  bricked, list != nullptr, volume.eacdCode(),
                  leapsByTheMargin(volume.grid(), camera, settings.stepVoxels * volume.grid().smallestSpacing()),
                  left && left->bands, pieces);
    const ExtentCode extentCode = variant.eacdCode;
    const vk::raii::Pipeline& pipe = pipeline(variant);

    const std::size_t tilePixels = std::size_t(tileSize_) * tileSize_;
    FrameBuffers& frame = frameBuffers(list ? tilePixels
                                            : std::size_t(std::min(tileSize_, camera.width)) *
                                                  std::size_t(std::min(tileSize_, camera.height)));
    const HostBuffer &params = frame.params, &extentTable = frame.extentTable;
    device::CasterParams p = makeParams(volume, camera, settings);
    if (left) p.stereoBands = left->bandGeometry, p.stereoBandCount = left->bandCount;
    // A stereo left eye's pixels carry their depth intervals in their counts.
    const bool counts = settings.rayCounts || (left && left->pixels);
    p.rayCounts = counts ? 1 : 0;
    std::memcpy(params.data(), &p, sizeof(p));
    std::memcpy(extentTable.data(), extentDecodeTable(extentCode).data(), sizeof(ExtentTable));

    // One descriptor set per brick: its images, the rest shared.
    const std::vector<Brick>& bricks = volume.bricks().bricks();
    const uint32_t brickCount = uint32_t(bricks.size());
    std::array<vk::DescriptorPoolSize, 4> sizes{
        vk::DescriptorPoolSize(vk::DescriptorType::eUniformBuffer, 1 * brickCount),
        vk::DescriptorPoolSize(vk::DescriptorType::eStorageImage, 11 * brickCount),
        vk::DescriptorPoolSize(vk::DescriptorType::eStorageBuffer, 6 * brickCount),
        vk::DescriptorPoolSize(vk::DescriptorType::eStorageTexelBuffer, 2 * brickCount)};
    vk::raii::DescriptorPool descriptorPool(
        device,
        vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, brickCount, sizes));
    const std::vector<vk::DescriptorSetLayout> layouts(brickCount, *setLayout_);
    vk::raii::DescriptorSets sets(device, vk::DescriptorSetAllocateInfo(*descriptorPool, layouts));
    auto imageInfo = [&](const VolumeImage& image) {
        return vk::DescriptorImageInfo(nullptr, *image.view(), kVolumeLayout);
    };
    const vk::DescriptorBufferInfo buffers[6] = {
        {*params.buffer(), 0, VK_WHOLE_SIZE},
        {*frame.colours.written(), 0, VK_WHOLE_SIZE},
        {*frame.rayState.buffer(), 0, VK_WHOLE_SIZE},
        {*(list ? list->buffer : frame.noList).buffer(), 0, VK_WHOLE_SIZE},
        {left && left->bands ? *left->bands->buffer() : *frame.noList.buffer(), 0, VK_WHOLE_SIZE},
        {*frame.counts.written(), 0, VK_WHOLE_SIZE}};
    const vk::DescriptorBufferInfo extentEntries(*extentTable.buffer(), 0, VK_WHOLE_SIZE);
    const vk::BufferView transferEntries = *volume.table().view();
    const vk::BufferView labelEntries = *(volume.labelTable() ? volume.labelTable() : unusedLabelTable_.get())->view();
    const vk::DescriptorImageInfo blockRanges =
        imageInfo(volume.blockExtrema() ? *volume.blockExtrema() : *unusedBlockExtrema_);
    for (uint32_t b = 0; b < brickCount; ++b) {
        const vk::DescriptorSet set = *sets[b];
        const VolumeImage* field = volume.field(settings.caster, int(b));
        vk::DescriptorImageInfo fields[3];
        const VolumeImage* gradientImage = volume.gradients(int(b));
        const vk::DescriptorImageInfo gradients = imageInfo(gradientImage ? *gradientImage : *unusedWords_);
        const VolumeImage* labelImage = volume.labels(int(b));
        const vk::DescriptorImageInfo labels = imageInfo(labelImage ? *labelImage : *unusedWords_);
        const bool floats = volume.scalarType() == ScalarType::Float32;
        const vk::DescriptorImageInfo scalarWords = imageInfo(floats ? *unusedWords_ : volume.scalars(int(b)));
        const vk::DescriptorImageInfo scalarFloats = imageInfo(floats ? volume.scalars(int(b)) : *unusedFloats_);
        for (int i = 0; i < 3; ++i)
            fields[i] = imageInfo(field && field->format() == kFieldFormats[i] ? *field : *unusedFields_[i]);
        using T = vk::DescriptorType;
        std::vector<vk::WriteDescriptorSet> writes{
            {set, device::kBindingParams, 0, 1, T::eStorageBuffer, nullptr, &buffers[0]},
            {set, device::kBindingOutColours, 0, 1, T::eStorageBuffer, nullptr, &buffers[1]},
            {set, device::kBindingOutCounts, 0, 1, T::eStorageBuffer, nullptr, &buffers[5]},
            {set, device::kBindingRayStates, 0, 1, T::eStorageBuffer, nullptr, &buffers[2]},
            {set, device::kBindingExtentTable, 0, 1, T::eUniformBuffer, nullptr, &extentEntries},
            {set, device::kBindingTransferTable, 0, 1, T::eStorageTexelBuffer, nullptr, nullptr, &transferEntries},
            {set, device::kBindingLabelTable, 0, 1, T::eStorageTexelBuffer, nullptr, nullptr, &labelEntries},
            {set, device::kBindingPixelList, 0, 1, T::eStorageBuffer, nullptr, &buffers[3]},
            {set, device::kBindingStereoBands, 0, 1, T::eStorageBuffer, nullptr, &buffers[4]}};
        writes.emplace_back(set, device::kBindingScalarWords, 0, 1, T::eStorageImage, &scalarWords);
        writes.emplace_back(set, device::kBindingScalarsFloat, 0, 1, T::eStorageImage, &scalarFloats);
        for (int i = 0; i < 3; ++i) writes.emplace_back(set, kFieldBindings[i], 0, 1, T::eStorageImage, &fields[i]);
        writes.emplace_back(set, device::kBindingBlockExtrema, 0, 1, T::eStorageImage, &blockRanges);
        writes.emplace_back(set, device::kBindingGradients, 0, 1, T::eStorageImage, &gradients);
        writes.emplace_back(set, device::kBindingLabelWords, 0, 1, T::eStorageImage, &labels);
        device.updateDescriptorSets(writes, {});
    }

    // One pass per sign pattern of the view's rays on the split axes, each over the bricks in its front-to-back
    // order; a ray runs in its own pass only.
    const unsigned splitAxes = volume.bricks().splitAxes(), octants = viewOctants(camera);
    std::vector<std::pair<unsigned, std::vector<int>>> passes;  // (signs, bricks front to back)
    for (int oct = 0; oct < kOctants; ++oct) {
        const unsigned signs = unsigned(oct) & splitAxes;
        if ((octants >> oct & 1) &&
            std::none_of(passes.begin(), passes.end(), [&](const auto& pass) { return pass.first == signs; }))
            passes.emplace_back(signs, volume.bricks().frontToBack(signs));
    }

    RenderResult result = RenderResult::blank(camera.width, camera.height, counts);

    // The tiles of the image, or the list's chunks of a tile's pixels each (its first entry in tileOrigin.x).
    std::vector<device::TilePush> tiles;
    const auto addTile = [&tiles](device::ivec2 origin, device::ivec2 size) {
        device::TilePush t{};  // the brick's fields are set per dispatch
        t.tileOrigin = origin;
        t.tileSize = size;
        tiles.push_back(t);
    };
    if (list) {
        const int count = int(list->pixels.size());
        // One workgroup wide: each workgroup row takes a chunk, so that on llvmpipe the interleaved rows spread
        // every thread's run of workgroups over the whole list (a sorted list puts its long rays together).
        for (int first = 0; first < count; first += int(tilePixels)) {
            const int rows = (std::min(int(tilePixels), count - first) + device::kWorkgroupSize - 1) /
                             device::kWorkgroupSize;
            addTile({first, 0}, {device::kWorkgroupSize, rows});
        }
    } else {
        for (int y0 = 0; y0 < camera.height; y0 += tileSize_)
            for (int x0 = 0; x0 < camera.width; x0 += tileSize_)
                addTile({x0, y0}, {std::min(tileSize_, camera.width - x0), std::min(tileSize_, camera.height - y0)});
    }
    for (device::TilePush tile : tiles) {
        const int groupRows = (tile.tileSize.y + device::kWorkgroupSize - 1) / device::kWorkgroupSize;
        tile.groupRowStride = rowStride(groupRows);
        submitAndWait(ctx_, pool_, [&](const vk::raii::CommandBuffer& cmd) {
            using S = vk::PipelineStageFlagBits;
            using A = vk::AccessFlagBits;
            timer_->start(cmd);
            cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipe);
            tile.firstDispatch = 1;
            for (std::size_t pass = 0; pass < passes.size(); ++pass) {
                const auto& [signs, order] = passes[pass];
                for (std::size_t i = 0; i < order.size(); ++i) {
                    const Brick& b = bricks[order[i]];
                    tile.brickLo = toDevice(b.lo), tile.brickHi = toDevice(b.hi);
                    tile.imageLo = toDevice(b.imageLo), tile.imageDims = toDevice(b.imageDims);
                    tile.lastDispatch = pass + 1 == passes.size() && i + 1 == order.size();
                    tile.passAxes = int(splitAxes), tile.passSigns = int(signs);
                    cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipelineLayout_, 0,
                                           *sets[order[i]], {});
                    cmd.pushConstants<device::TilePush>(*pipelineLayout_, vk::ShaderStageFlagBits::eCompute, 0,
                                                        tile);
                    constexpr int group = device::kWorkgroupSize;
                    cmd.dispatch((tile.tileSize.x + group - 1) / group, (tile.tileSize.y + group - 1) / group, 1);
                    // The next brick reads the ray states this one wrote.
                    vk::MemoryBarrier carried(A::eShaderWrite, A::eShaderRead | A::eShaderWrite);
                    cmd.pipelineBarrier(S::eComputeShader, S::eComputeShader, {}, carried, {}, {});
                    tile.firstDispatch = 0;
                }
            }
            if (stagedOutput_) {  // the tile's pixels to host memory by the transfer engine
                vk::MemoryBarrier toCopy(A::eShaderWrite, A::eTransferRead);
                cmd.pipelineBarrier(S::eComputeShader, S::eTransfer, {}, toCopy, {}, {});
                const vk::BufferCopy tilePixels(
                    0, 0, vk::DeviceSize(tile.tileSize.x) * vk::DeviceSize(tile.tileSize.y) * sizeof(device::uvec4));
                cmd.copyBuffer(*frame.colours.onDevice->buffer(), *frame.colours.host.buffer(), tilePixels);
                if (counts) cmd.copyBuffer(*frame.counts.onDevice->buffer(), *frame.counts.host.buffer(), tilePixels);
            }
            timer_->stop(cmd);
            vk::MemoryBarrier toHost(A::eShaderWrite | A::eTransferWrite, A::eHostRead);
            cmd.pipelineBarrier(S::eComputeShader | S::eTransfer, S::eHost, {}, toHost, {}, {});
        });
        result.deviceMilliseconds += timer_->milliseconds();
        const auto* colours = static_cast<const device::uvec4*>(frame.colours.host.data());
        const auto* rayCounts = static_cast<const device::uvec4*>(frame.counts.host.data());
        // Rows in parallel: a 512 x 512 frame's 8 MB took one core longer than the H100 took to render it.
        tbb::parallel_for(0, tile.tileSize.y, [&](int ly) {
            for (int lx = 0; lx < tile.tileSize.x; ++lx) {
                const std::size_t local = std::size_t(ly) * tile.tileSize.x + lx;
                int px = tile.tileOrigin.x + lx, py = tile.tileOrigin.y + ly;
                if (list) {
                    const std::size_t entry = std::size_t(tile.tileOrigin.x) + local;
                    if (entry >= list->pixels.size()) break;
                    px = int(list->pixels[entry] & 0xffffu), py = int(list->pixels[entry] >> 16);
                }
                const std::size_t index = std::size_t(py) * camera.width + px;
                const device::uvec4& colour = colours[local];
                const uint32_t failure = device::failureFlagsOf(colour.w);
                if (failure & device::kCutShort)
                    throw std::runtime_error("Vulkan " + std::string(casterName(settings.caster)) + " caster: " +
                                             ctx_.info().name + " ended the shader's loops before the ray at pixel (" +
                                             std::to_string(px) + ", " + std::to_string(py) +
                                             ") was done (llvmpipe allows 65535 loop iterations per shader "
                                             "invocation); render with the CPU reference or a hardware device");
                if (failure & device::kFailed)
                    throw std::runtime_error("Vulkan " + std::string(casterName(settings.caster)) +
                                             " caster: the ray at pixel (" + std::to_string(px) + ", " +
                                             std::to_string(py) +
                                             ") hit the iteration cap, needed an octant not uploaded or was left in "
                                             "no brick pass (a bug)");
                std::memcpy(result.image.pixel(px, py), &colour, 4 * sizeof(float));
                if (!counts) continue;
                const device::uvec4& c = rayCounts[local];
                if (left && left->pixels) static_cast<device::OutPixel*>(left->pixels)[index] = {colour, c};
                result.iterations[index] = c.y;  // with the shader's flags
                result.samples[index] = c.x;
            }
        });
    }
    result.wallMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace vr
