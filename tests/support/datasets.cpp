#include "support/datasets.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vr::test {
namespace fs = std::filesystem;

fs::path datasetsDir() { return fs::path(VR_DATASETS_DIR); }

bool DatasetEntry::isRaw() const { return file.ends_with(".raw.gz"); }

static std::vector<std::string> splitTabs(const std::string& line) {
    std::vector<std::string> cols;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, '\t')) cols.push_back(c);
    return cols;
}

std::vector<DatasetEntry> manifest() {
    std::ifstream in(datasetsDir() / "MANIFEST.tsv");
    if (!in) throw std::runtime_error("cannot open " + (datasetsDir() / "MANIFEST.tsv").string());
    std::string line;
    std::getline(in, line);  // header
    std::vector<DatasetEntry> rows;
    while (std::getline(in, line)) {
        auto c = splitTabs(line);
        if (c.size() < 9) continue;
        DatasetEntry e;
        e.file = c[0];
        std::istringstream(c[1]) >> e.dims.x >> e.dims.y >> e.dims.z;
        std::string type = c[2].substr(0, c[2].find(' '));
        e.type = parseScalarType(type);
        e.spacing = {1, 1, 1};
        std::istringstream sp(c[3]);
        Vec3d s;
        if (sp >> s.x >> s.y >> s.z) e.spacing = s;
        e.tf = c[8];
        rows.push_back(e);
    }
    if (rows.empty()) throw std::runtime_error((datasetsDir() / "MANIFEST.tsv").string() + " lists no dataset");
    return rows;
}

std::vector<DatasetEntry> rawManifest() {
    std::vector<DatasetEntry> rows;
    for (auto& e : manifest())
        if (e.isRaw()) rows.push_back(e);
    if (rows.empty()) throw std::runtime_error((datasetsDir() / "MANIFEST.tsv").string() + " lists no .raw.gz dataset");
    return rows;
}

DatasetEntry rawDataset(const std::string& prefix) {
    for (const DatasetEntry& e : rawManifest())
        if (e.file.starts_with(prefix)) return e;
    throw std::runtime_error("no raw dataset named " + prefix + "... in " + (datasetsDir() / "MANIFEST.tsv").string());
}

DatasetEntry dataset(const std::string& file) {
    for (const DatasetEntry& e : manifest())
        if (e.file == file) return e;
    throw std::runtime_error(file + ": not in " + (datasetsDir() / "MANIFEST.tsv").string());
}

fs::path scratchDir(const std::string& name) {
    // One folder per process: CTest runs the cases of one executable as parallel processes, and a folder
    // shared between them would be wiped by one while another writes into it.
    fs::path p = fs::path(VR_BINARY_DIR) / "test-scratch" / (name + "." + std::to_string(::getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

}  // namespace vr::test
