// ParaView preset JSON through parseTransferFunction. A function it accepts is also sampled over its points' range,
// and every sample must be an opacity and a colour in [0,1]: what classification relies on; written back as
// ParaView JSON (as the window/level ramp is kept), it must read back to the same function.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.h"
#include "fuzz/support.h"
#include "preprocess/classify/transfer_function.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    vr::TransferFunction tf;
    try {
        tf = vr::parseTransferFunction(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    } catch (const vr::InputError&) {
        return 0;
    }
    double lo = tf.opacity.front().x, hi = tf.opacity.back().x;
    for (const auto& p : tf.colour) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
    const vr::SampledTransferFunction s = vr::sampleTransferFunction(tf, lo, hi, 33);
    for (std::size_t i = 0; i < s.opacity.size(); ++i) {
        if (!(s.opacity[i] >= 0 && s.opacity[i] <= 1)) vr::fuzz::finding("sampled opacity outside [0,1]");
        for (float c : s.colour[i])
            if (!(c >= 0 && c <= 1)) vr::fuzz::finding("sampled colour outside [0,1]");
    }
    try {
        vr::TransferFunction back = vr::parseTransferFunction(vr::paraViewJson(tf), "written.json");
        back.json = tf.json;
        if (!(back == tf)) vr::fuzz::finding("paraViewJson reads back to another function");
    } catch (const vr::InputError&) {
        vr::fuzz::finding("paraViewJson wrote a preset that does not read back");
    }
    return 0;
}
