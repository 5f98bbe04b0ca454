#include "sweep/image_strip.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>

#include "core/errors.h"

namespace vr {
namespace fs = std::filesystem;

namespace {
constexpr int kGap = 8, kLabelHeight = 40, kMinPitch = 150, kFontSize = 13;

OIIO::ImageBuf readTile(const fs::path& path) {
    OIIO::ImageBuf tile(path.string());
    if (!tile.read(0, 0, true, OIIO::TypeDesc::UINT8))
        throw fileError(path.string(), "cannot read the image for the strip: " + tile.geterror());
    return tile;
}
}  // namespace

void writeImageStrip(const std::vector<StripColumn>& columns, const fs::path& output) {
    if (columns.empty()) throw InputError(output.string() + ": no columns for the image strip");
    const OIIO::ImageBuf first = readTile(columns.front().image);
    const int w = first.spec().width, h = first.spec().height;
    const int cols = int(columns.size());
    const int pitch = std::max(w, kMinPitch) + kGap;  // room for the labels beside small images
    OIIO::ImageSpec spec(kGap + cols * pitch, kLabelHeight + 2 * h + 3 * kGap, 3, OIIO::TypeDesc::UINT8);
    OIIO::ImageBuf strip(spec);
    const float grey[3] = {0.15f, 0.15f, 0.15f};
    OIIO::ImageBufAlgo::fill(strip, grey);
    for (int c = 0; c < cols; ++c) {
        const int x = kGap + c * pitch;
        const OIIO::ImageBuf image = readTile(columns[c].image);
        OIIO::ImageBufAlgo::paste(strip, x, kLabelHeight + kGap, 0, 0, image);
        if (!columns[c].errorMap.empty())
            OIIO::ImageBufAlgo::paste(strip, x, kLabelHeight + 2 * kGap + h, 0, 0, readTile(columns[c].errorMap));
        else
            OIIO::ImageBufAlgo::fill(strip, std::vector<float>{0, 0, 0},
                                     OIIO::ROI(x, x + w, kLabelHeight + 2 * kGap + h, kLabelHeight + 2 * kGap + 2 * h));
        // Labels need a TrueType font OIIO can find; without one the report names the columns.
        const float white[3] = {1, 1, 1};
        if (!OIIO::ImageBufAlgo::render_text(strip, x, kLabelHeight / 2 - 4, columns[c].label, kFontSize,
                                             "DejaVuSans", white) ||
            !OIIO::ImageBufAlgo::render_text(strip, x, kLabelHeight - 4, columns[c].subLabel, kFontSize,
                                             "DejaVuSans", white))
            strip.geterror();  // reading the error clears it
    }
    if (!strip.write(output.string())) throw fileError(output.string(), "cannot write: " + strip.geterror());
}

}  // namespace vr
