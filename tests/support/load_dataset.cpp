#include "support/load_dataset.h"

#include <stdexcept>

namespace vr::test {

RawOptions manifestRawOptions(const std::string& file) {
    for (const DatasetEntry& e : manifest()) {
        if (e.file != file) continue;
        RawOptions raw;
        raw.spacing = e.spacing;
        return raw;
    }
    throw std::invalid_argument(file + ": not in MANIFEST.tsv");
}

Volume loadDataset(const DatasetEntry& entry) {
    RawOptions raw;
    raw.spacing = entry.spacing;
    return loadVolume(datasetsDir() / entry.file, raw);
}

Volume loadDataset(const std::string& prefix) { return loadDataset(rawDataset(prefix)); }

TransferFunction datasetTransferFunction(const std::string& name) { return loadTransferFunction(datasetsDir() / name); }

}  // namespace vr::test
