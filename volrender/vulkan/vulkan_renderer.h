// The Vulkan compute casters: same inputs and outputs as renderCpu, one dispatch per image tile and brick.
#pragma once
#include <map>
#include <stdexcept>
#include <memory>
#include <mutex>
#include <optional>
#include <tuple>
#include <vector>

#include "core/prepared_volume.h"
#include "render/camera.h"
#include "render/render_result.h"
#include "render/stereo_camera.h"
#include "shaders/device_contract.h"
#include "volrender/vulkan/device_timer.h"
#include "volrender/vulkan/gpu_volume.h"
#include "volrender/vulkan/vulkan_context.h"
#include "volrender/vulkan/workgroup_rows.h"

namespace vr {

class StereoReprojector;

// A stereo pair's two images and what the right eye's reuse of the left's did.
struct StereoRender {
    RenderResult left, right;       // each eye's deviceMilliseconds: its own (the right's: reprojection + re-casts)
    std::vector<uint8_t> recast;    // per right pixel: 1 where it was ray-cast (every pixel without reuse)
    std::vector<float> recastFrom;  // per right pixel ray-cast with reuse: the depth along the view direction its ray
                                    // was cast from, behind the reprojection of what lies before (0: the whole ray)
    double recastFraction = 1;      // of the right eye's pixels
    double recastInPartFraction = 0;   // of the right eye's pixels: re-cast from a depth on (recastFrom > 0)
    double reprojectMilliseconds = 0;  // device time of the reprojection alone (part of the right eye's)
    int recastPieces = 1;              // the pieces each re-cast ray was cast in
};

class VulkanRenderer {
public:
    // Tiles of tileSize x tileSize pixels are separate submits, so no dispatch runs long enough to trip a
    // GPU watchdog; kAutoTile: 1024 on a GPU (smaller tiles leave most of a large GPU idle), or 512 on a CPU
    // device (no watchdog; each submit costs llvmpipe a thread-pool round). `limits` lowers the device's image and
    // storage-buffer limits (tests force bricks and refusals with it). Throws std::invalid_argument for a negative
    // tile size, std::runtime_error for a device that cannot read the casters' storage-image formats
    // (requireCasterImageSupport).
    static constexpr int kAutoTile = 0;
    // Where the casters write a tile's pixels: host memory read in place, or device memory copied to it by the
    // transfer engine. Auto: device memory on a discrete GPU, whose shaders write host memory at PCIe rates
    // (about 8 GB/s on an H100: 1.1 ms for a 512 x 512 frame whatever its iterations), host memory elsewhere.
    enum class OutputMemory { Auto, Host, Device };
    explicit VulkanRenderer(const VulkanContext& ctx, int tileSize = kAutoTile, const ImageLimits& limits = {},
                            OutputMemory output = OutputMemory::Auto);
    int tileSize() const { return tileSize_; }

    // Uploads a prepared volume once for many renders (see GpuVolume); a volume too large for one image is split
    // into bricks. Throws InputError when the prepared volume lacks what `contents` asks for.
    GpuVolume upload(const PreparedVolume& prepared, const GpuVolumeContents& contents);

    // Renders an uploaded volume, reads back. Throws InputError for unusable settings, std::invalid_argument when
    // the volume lacks what the settings or the view need, std::runtime_error for device failures (out of memory,
    // device lost) and for a ray that hit the iteration cap.
    RenderResult render(const GpuVolume& volume, const Camera& camera, const RenderSettings& settings);

    // Uploads just what this caster and view need, then renders (one-off renders; an orbit uploads once).
    RenderResult render(const PreparedVolume& prepared, const Camera& camera, const RenderSettings& settings);

    // Renders both eyes of a pair (docs/ALGORITHMS.md section 12). With reuse the left eye is
    // cast in full, keeping each pixel's depth interval on the device; the right eye is its reprojection, and only
    // the pixels the reprojection cannot vouch for are cast again, from a compacted list. Without reuse both eyes
    // are cast in full. Throws as render() does.
    StereoRender renderStereo(const GpuVolume& volume, const StereoPair& pair, const RenderSettings& settings,
                              bool reuse);
    // How a pair's composite re-casts of a one-brick volume are cast: kAutoPieces (ray_pieces.h raysPieces: whole
    // rays, or pieces on a discrete GPU), or each ray in this many pieces, 1 to device::kMostPieces (else
    // std::invalid_argument). Other re-casts cast whole rays.
    static constexpr int kAutoPieces = 0;
    void setRecastPieces(int pieces);
    // Whole frames' composite rays of a one-brick volume in this many pieces each, 1 (whole rays, the default) to
    // device::kMostPieces (else std::invalid_argument): for measuring where a GPU's frame waits on its longest rays
    // (render_bench --ray-pieces).
    void setRayPieces(int pieces);

    // Makes, ahead of any render, the pipeline that a render of a one-brick volume of scalars of `type`, without a
    // label map, with `settings` in `projection` (and an EACD in the default code) takes: volrender makes it while the
    // volume is still being prepared (a CPU device takes longer to make a pipeline than to render a small CT). Safe
    // beside a render on another thread: a render that needs a pipeline being made waits for it.
    void preparePipeline(const RenderSettings& settings, Projection projection, ScalarType type);
    // The same for a stereo pair with reuse (renderStereo) of such a volume: the left eye's pipeline (composite's
    // records its bands), the re-casts' and the reprojection's, which the first pair would otherwise make once the
    // volume is ready (on lavapipe they took 30-60 ms off one pair's whole process).
    void prepareStereoPipelines(const RenderSettings& settings, ScalarType type);
    // How many pipelines it has made so far, the casters' and the reprojection's, each once.
    std::size_t pipelineCount();

    ~VulkanRenderer();

    // The resources the last render read (of the volume uploaded for it or given to it), per brick: the scalars,
    // the transfer table, the caster's field.
    const std::vector<UploadedResource>& lastUploads() const { return uploads_; }

private:
    // The checks of render(); notes what the render reads in lastUploads().
    void checkRender(const GpuVolume& volume, const Camera& camera, const RenderSettings& settings);
    // What the casters cast: every pixel, tile by tile, or (list) the rays of a list on the device (device::ListRay
    // each), whose packed pixels copied to the host (`pixels`) say where each result goes; the pixels not in it stay
    // blank.
    // A list's rays may be cast in pieces (piecesFor).
    struct PixelList {
        const HostBuffer& buffer;
        std::vector<uint32_t> pixels;
        int pieces = 1;
    };
    // A stereo pair's left eye, for the reprojection: every pixel's OutPixel kept, row by row (a whole image of
    // them), and for composite its bands' segments (a uvec4 each, shaders/stereo_reprojection.h bandTexel).
    struct StereoLeft {
        void* pixels;  // null where the reprojection reads the bands alone (composite)
        const DeviceBuffer* bands;  // composite only
        device::vec4 bandGeometry;  // CasterParams::stereoBands
        int bandCount;
    };
    RenderResult renderOnDevice(const GpuVolume& volume, const Camera& camera, const RenderSettings& settings,
                                const PixelList* list = nullptr, const StereoLeft* left = nullptr);
    // What picks a pipeline: one value per specialization constant of shaders/caster.comp.
    struct Variant {
        Caster caster;
        Blend blend;
        bool trilinear, shading;
        ExtentCode eacdCode;  // read by EACD only: the others' variants hold Exact
        bool bricked;         // the volume is split into bricks, whose dispatches carry each ray's state on
        bool perspective;
        ScalarType scalarType;
        int labels;           // the device's label type (device::kNoLabels without a label map)
        bool pixelList;
        bool storedGradients;  // read by shaded variants only: the others' hold false
        bool stereoBands;      // composite only: the others' hold false
        bool marginLeaps;      // leapsByTheMargin (render/ray_setup.h)
        int pieces;            // composite of a one-brick volume only; the others' variants hold 1
        auto operator<=>(const Variant&) const = default;
    };
    static Variant variantOf(const RenderSettings& settings, bool perspective, ScalarType type, int labels,
                             bool bricked, bool pixelList, ExtentCode eacdCode, bool marginLeaps,
                             bool stereoBands = false, int pieces = 1);
    // The pieces a render with `settings` casts each ray in when asked for `pieces`: composite rays of a one-brick
    // volume only (others 1), no more than the device's workgroups hold (a piece an invocation).
    int piecesFor(bool bricked, const RenderSettings& settings, int pieces) const;
    // The pieces a pair's re-casts ask for, `listPixels` of a frame of `framePixels` (setRecastPieces).
    int recastPiecesAsked(std::size_t listPixels, std::size_t framePixels) const;
    StereoReprojector& reprojector();  // made once, by the first that needs it
    const vk::raii::Pipeline& pipeline(Variant variant);
    // What one tile's dispatches read and write beside the volume, for tiles of up to `pixels` pixels. Kept from
    // render to render, and grown when a render needs more: a GPU driver pins host memory as it is allocated, which
    // took longer than the frame on an H100. One render at a time uses them.
    // One of the casters' per-pixel outputs (a uvec4 a pixel of the tile): host memory, or, when staged, device
    // memory whose tile the transfer engine copies into host memory.
    struct PixelOutput {
        PixelOutput(const VulkanContext& ctx, std::size_t pixels, bool staged);
        HostBuffer host;
        std::optional<DeviceBuffer> onDevice;
        const vk::raii::Buffer& written() const { return onDevice ? onDevice->buffer() : host.buffer(); }
    };
    struct FrameBuffers {
        FrameBuffers(const VulkanContext& ctx, std::size_t pixels, bool staged);
        std::size_t pixels;
        HostBuffer params, extentTable, noList;
        DeviceBuffer rayState;
        PixelOutput colours, counts;  // OutPixel's two halves; the counts read back only when asked
    };
    FrameBuffers& frameBuffers(std::size_t pixels);
    // What a stereo pair with reuse reads and writes beside the frame's buffers: the left eye's pixels, the
    // reprojected right eye's colours, the re-cast list and composite's band segments (uvec4 each). Kept and grown
    // as the frame's are: made afresh, their tens of MB were faulted in by every pair.
    struct PairBuffers {
        PairBuffers(const VulkanContext& ctx, std::size_t pixels, std::size_t segments, std::size_t leftPixels);
        std::size_t pixels, segments, leftPixels;
        HostBuffer left, right, recast;  // left: leftPixels, at least 1 (bound, unread, for composite)
        std::optional<DeviceBuffer> bands;  // when segments > 0
    };
    PairBuffers& pairBuffers(std::size_t pixels, std::size_t segments, std::size_t leftPixels);
    // Turns Vulkan's out-of-memory and device-lost errors into messages that say what to try.
    template <typename Work>
    auto deviceErrors(Work&& work) -> decltype(work());

    const VulkanContext& ctx_;
    int tileSize_;
    ImageLimits limits_;
    bool stagedOutput_;  // OutputMemory::Device
    bool interleavedRows_;  // a CPU device: its threads take contiguous runs of workgroups (workgroup_rows.h)
    // The stride of a dispatch's `rows` workgroup rows over its image rows: interleaved on a CPU device, else 1.
    int rowStride(int rows) const { return interleavedRows_ ? interleavedRowStride(rows) : 1; }
    vk::raii::CommandPool pool_{nullptr};
    vk::raii::DescriptorSetLayout setLayout_{nullptr};
    vk::raii::PipelineLayout pipelineLayout_{nullptr};
    std::map<std::tuple<Caster, Blend, bool>, vk::raii::ShaderModule> shaders_;  // (caster, blend, plain), made as
                                                                                 // pipelines need them
    std::unique_ptr<DeviceTimer> timer_;
    std::map<Variant, vk::raii::Pipeline> pipelines_;
    std::mutex pipelinesMutex_;  // held while a pipeline is looked up or made
    std::optional<FrameBuffers> frame_;
    std::optional<PairBuffers> pair_;
    // Bound where a variant reads nothing (the scalar binding of the other kind, the field for primitive, the field
    // bindings of the other formats, the block extrema for every caster but blocks, the labels of a volume without
    // them, the gradients where none are stored): never read. Words serve every R32_UINT binding.
    std::unique_ptr<VolumeImage> unusedWords_, unusedFloats_, unusedFields_[3], unusedBlockExtrema_;
    std::unique_ptr<TexelTable> unusedLabelTable_;  // bound without a label map
    std::vector<UploadedResource> uploads_;
    std::unique_ptr<StereoReprojector> reprojector_;
    std::once_flag reprojectorMade_;
    int recastPieces_ = kAutoPieces;
    int rayPieces_ = 1;
};

template <typename Work>
auto VulkanRenderer::deviceErrors(Work&& work) -> decltype(work()) {
    try {
        return work();
    } catch (const vk::OutOfDeviceMemoryError&) {
        throw std::runtime_error("the Vulkan device " + ctx_.info().name +
                                 " ran out of memory (try a smaller volume, --caster primitive or an orthographic "
                                 "view)");
    } catch (const vk::OutOfHostMemoryError&) {
        throw std::runtime_error("the Vulkan driver ran out of host memory");
    } catch (const vk::DeviceLostError&) {
        throw std::runtime_error("the Vulkan device " + ctx_.info().name +
                                 " was lost (a driver crash or a watchdog reset; try a smaller --size)");
    }
}

}  // namespace vr
