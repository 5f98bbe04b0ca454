// Counting what compressed data really hold. VTK's readers allocate the image a header claims and then decompress
// into it, so a 100-byte file could claim gigabytes; sizes the file states about its compressed data (gzip's
// ISIZE, which is mod 2^32, or MetaImage's CompressedDataSize) are as untrustworthy as the header itself.
#include "preprocess/load/compressed_data.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <new>
#include <vector>

namespace vr {

std::uintmax_t decompressedBytes(BoundedReader& file, std::uintmax_t offset, std::uintmax_t needed,
                                 Compression compression, std::uintmax_t compressedBytes) {
    file.seek(std::min<std::uintmax_t>(offset, file.size()), "its compressed data");
    std::vector<unsigned char> input(1 << 16), output(1 << 18);
    std::uintmax_t consumed = 0;
    // Keeps the unread input at the front of the buffer and tops it up from the file; false when nothing is left.
    z_stream z{};
    const auto refill = [&] {
        std::memmove(input.data(), z.next_in, z.avail_in);
        const std::uintmax_t room = std::min<std::uintmax_t>(input.size() - z.avail_in, compressedBytes - consumed);
        const std::size_t got = file.readUpTo(input.data() + z.avail_in, std::size_t(room));
        consumed += got;
        z.next_in = input.data();
        z.avail_in += uInt(got);
        return z.avail_in > 0;
    };
    z.next_in = input.data();
    if (!refill()) return 0;
    // gzread reads data without the gzip magic as they are, and so do the readers that use it.
    if (compression == Compression::GzipOrPlain && !(z.avail_in >= 2 && input[0] == 0x1f && input[1] == 0x8b))
        return std::min(needed, std::min(compressedBytes, file.size() - std::min<std::uintmax_t>(file.size(), offset)));

    if (inflateInit2(&z, 15 + 32) != Z_OK) throw std::bad_alloc();  // 15 + 32: zlib or gzip, told by the header
    struct End {
        z_stream* z;
        ~End() { inflateEnd(z); }
    } end{&z};
    std::uintmax_t produced = 0;
    while (produced < needed) {
        if (z.avail_in == 0 && !refill()) break;  // the data end here
        z.next_out = output.data();
        z.avail_out = uInt(output.size());
        const int status = inflate(&z, Z_NO_FLUSH);
        produced += output.size() - z.avail_out;
        if (status == Z_STREAM_END) {
            // gzread goes on into a following gzip member; anything else after the stream is ignored.
            if (z.avail_in < 2) refill();
            if (compression != Compression::GzipOrPlain || z.avail_in < 2 || z.next_in[0] != 0x1f ||
                z.next_in[1] != 0x8b)
                break;
            inflateReset(&z);
        } else if (status == Z_DATA_ERROR || status == Z_NEED_DICT) {
            throw file.fail(std::string("corrupt compressed data: ") + (z.msg ? z.msg : "bad stream") + " after " +
                            std::to_string(produced) + " decompressed bytes");
        } else if (status == Z_MEM_ERROR) {
            throw std::bad_alloc();
        }
        // Z_BUF_ERROR: no progress without more input, which the next round reads (or finds the data ended).
    }
    return std::min(produced, needed);
}

std::string gzreadBytes(const BoundedReader& file, std::size_t count) {
    gzFile gz = gzopen(file.path().c_str(), "rb");
    if (!gz) throw file.fail("cannot open its gzip data");
    std::string bytes(count, '\0');
    const int got = gzread(gz, bytes.data(), unsigned(count));
    gzclose(gz);
    if (got < 0) throw file.fail("corrupt gzip data at its start");
    bytes.resize(std::size_t(got));
    return bytes;
}

}  // namespace vr
