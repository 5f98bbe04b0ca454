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

TransferFunction linearTransferFunction(double x0, double x1) {
    TransferFunction tf;
    tf.opacity = {{x0, 0.0}, {x1, 1.0}};
    tf.colour = {{x0, 1, 0, 0}, {x1, 0, 0, 1}};
    return tf;
}

}  // namespace vr::test
