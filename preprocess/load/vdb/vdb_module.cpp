// volload_vdb.so's one entry (format_module.h).
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/format_module.h"

extern "C" vr::FormatLoader vrFormatLoader(vr::ModuleFormat format) {
    return format == vr::ModuleFormat::Vdb ? vr::ignoringRawOptions<vr::loadVdb> : nullptr;
}
