#include "io/prepared_chunks.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

namespace vr::prepared_detail {

ChunkLayout layoutOf(const std::string& name, ExtentCode eacdCode, ScalarType scalarType, ScalarType labelType) {
    if (name == "scalars") return {std::string(scalarTypeName(scalarType)), 1, scalarBytes(scalarType)};
    if (name == "table") return {"float32", kTableComponents, 4};
    if (name == "labelMap") return {std::string(scalarTypeName(labelType)), 1, scalarBytes(labelType)};
    if (name == "labelTable") return {"float32", kTableComponents, 4};
    if (name == "labels") return {"uint32", 1, 4};
    if (name == "pc") return {"uint8", 1, 1};
    for (int o = 0; o < kOctants; ++o) {
        if (name == "acd" + std::to_string(o)) return {"uint8", 1, 1};
        if (name == "eacd" + std::to_string(o))
            return eacdCode == ExtentCode::Exact ? ChunkLayout{"uint8", 3, 1}
                   : eacdCode == ExtentCode::Log16 ? ChunkLayout{"uint16", 1, 2}
                                                   : ChunkLayout{"uint8", 1, 1};
    }
    return {"", 0, 0};
}

bool isTableChunk(const std::string& name) { return name == "table" || name == "labelTable"; }

uint64_t sliceBytesOf(const std::string& name, const ChunkLayout& l, const Vec3i& dims) {
    return isTableChunk(name) ? 0 : uint64_t(dims.x) * uint64_t(dims.y) * uint64_t(l.components) * l.elementBytes;
}

std::size_t encodeScalars(const std::vector<float>& values, ScalarType t, std::vector<char>& bytes) {
    bytes.resize(values.size() * scalarBytes(t));
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, values.size()), values.size(),
        [&](const tbb::blocked_range<std::size_t>& r, std::size_t first) {
            unsigned char* to = reinterpret_cast<unsigned char*>(bytes.data()) + r.begin() * scalarBytes(t);
            const std::size_t bad = narrowScalars(values.data() + r.begin(), r.size(), t, to);
            return std::min(first, bad < r.size() ? r.begin() + bad : values.size());
        },
        [](std::size_t a, std::size_t b) { return std::min(a, b); });
}

namespace {

template <typename T>
void decodeAs(const std::vector<char>& bytes, std::vector<float>& values) {
    const T* from = reinterpret_cast<const T*>(bytes.data());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, values.size()), [&](const tbb::blocked_range<std::size_t>& b) {
        for (std::size_t i = b.begin(); i < b.end(); ++i) values[i] = float(from[i]);
    });
}

}  // namespace

void decodeScalars(const std::vector<char>& bytes, ScalarType t, std::vector<float>& values) {
    switch (t) {
        case ScalarType::UInt8: decodeAs<uint8_t>(bytes, values); break;
        case ScalarType::Int16: decodeAs<int16_t>(bytes, values); break;
        case ScalarType::UInt16: decodeAs<uint16_t>(bytes, values); break;
        case ScalarType::Float32: break;  // read straight into the values
    }
}

void splitTable(const std::vector<float>& in, TransferTable& t) {
    const std::size_t entries = in.size() / kTableComponents;
    t.sigma.resize(entries);
    t.colour.resize(entries);
    for (std::size_t i = 0; i < entries; ++i) {
        const float* e = &in[i * kTableComponents];
        t.colour[i] = {e[0], e[1], e[2]};
        t.sigma[i] = e[3];
    }
}

}  // namespace vr::prepared_detail
