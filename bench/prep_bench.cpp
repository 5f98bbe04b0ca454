// Preprocessing benchmark: per dataset, the median over several runs of each stage's wall and CPU time (load,
// classify, segment, each distance field, write, and reading the prepared file back), the bytes of every field,
// and what the segmentation produced. Prints Markdown tables.
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <map>

#include "core/errors.h"
#include "core/prepared_file.h"
#include "preprocess/pipeline/prepare.h"
#include "support/datasets.h"

namespace {
namespace fs = std::filesystem;

const std::vector<std::string> kStages = {"load", "classify", "segment", "pc", "acd", "eacd", "write", "read"};
const std::vector<std::string> kChunks = {"sigma", "colour", "normal", "labels", "pc", "acd", "eacd"};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

struct DatasetResult {
    std::string name;
    std::map<std::string, std::vector<double>> wall, cpu;  // per stage, one entry per run
    nlohmann::json statistics;                           // from the last run (the same every run)
    std::uintmax_t fileBytes = 0;
};

vr::test::DatasetEntry findDataset(const std::string& file) {
    for (const auto& e : vr::test::manifest())
        if (e.file == file) return e;
    throw vr::InputError(file + ": not in " + (vr::test::datasetsDir() / "MANIFEST.tsv").string());
}

DatasetResult benchDataset(const std::string& file, const vr::PrepareOptions& base, int runs, const fs::path& scratch) {
    vr::test::DatasetEntry e = findDataset(file);
    vr::PrepareOptions options = base;
    options.raw.spacing = e.spacing;
    options.classify.transferFunction = vr::loadTransferFunction(vr::test::datasetsDir() / e.tf);
    fs::path out = scratch / (file + ".vprep");
    DatasetResult result{file, {}, {}, {}, 0};
    for (int run = 0; run < runs; ++run) {
        vr::PrepareResult r = vr::prepareFile(vr::test::datasetsDir() / file, out, options);
        r.prepared = {};  // free it before reading the file back
        vr::StageClock clock;
        vr::PreparedVolume back = vr::readPrepared(out, options.fields, options.classify.normals);
        r.stages.push_back(clock.stop("read"));
        for (const vr::StageTime& t : r.stages) {
            result.wall[t.stage].push_back(t.seconds);
            result.cpu[t.stage].push_back(t.cpuSeconds);
        }
        result.statistics = back.meta.statistics;
        result.fileBytes = r.fileBytes;
        std::fprintf(stderr, "%s: run %d of %d done\n", file.c_str(), run + 1, runs);
    }
    fs::remove(out);
    return result;
}

void printTimes(const char* title, const std::vector<DatasetResult>& results,
                std::map<std::string, std::vector<double>> DatasetResult::*times) {
    std::printf("%s\n\n| dataset | voxels |", title);
    for (const auto& s : kStages) std::printf(" %s |", s.c_str());
    std::printf(" total (no read) |\n|---|---:|");
    for (std::size_t i = 0; i <= kStages.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (const auto& r : results) {
        std::printf("| %s | %zu |", r.name.c_str(), r.statistics["voxels"].get<std::size_t>());
        double total = 0;
        for (const auto& s : kStages) {
            if (!(r.*times).count(s)) {
                std::printf(" - |");
                continue;
            }
            double m = median((r.*times).at(s));
            if (s != "read") total += m;
            std::printf(" %.3f |", m);
        }
        std::printf(" %.3f |\n", total);
    }
    std::printf("\n");
}

void printTables(const std::vector<DatasetResult>& results, const vr::PrepareOptions& o, int runs) {
    std::printf("Preprocessing, T_o = %g, T_a = %g deg, normals %s, %s sampling, %d threads; median of %d runs.\n"
                "pc is timed on its own (with its own 8 ACD passes); eacd on top of acd; read is readPrepared of every "
                "chunk written.\n\n",
                o.segmentation.opacityThreshold, o.segmentation.angleThresholdDeg, o.classify.normals ? "on" : "off",
                o.segmentation.trilinear ? "trilinear" : "nearest", tbb::info::default_concurrency(), runs);
    printTimes("Wall seconds per stage:", results, &DatasetResult::wall);
    printTimes("CPU seconds per stage (all threads; steadier than wall time on a shared machine):", results,
               &DatasetResult::cpu);

    std::printf("MiB per chunk:\n\n| dataset |");
    for (const auto& c : kChunks) std::printf(" %s |", c.c_str());
    std::printf(" file |\n|---|");
    for (std::size_t i = 0; i <= kChunks.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (const auto& r : results) {
        std::printf("| %s |", r.name.c_str());
        for (const auto& c : kChunks) std::printf(" %.1f |", mib(r.statistics["bytes"][c].get<double>()));
        std::printf(" %.1f |\n", mib(double(r.fileBytes)));
    }

    std::printf("\nRegions and mean leaps in voxels (ACD edge: the same in every octant; EACD extents x,y,z of octant 0):\n\n"
                "| dataset | regions | mean region size | PC radius | ACD edge | EACD extents |\n"
                "|---|---:|---:|---:|---:|---|\n");
    for (const auto& r : results) {
        const nlohmann::json& s = r.statistics;
        const nlohmann::json& l = s["leaps"];
        auto number = [&](const char* key, auto get) {
            if (!l.contains(key)) return std::string("-");
            char text[32];
            std::snprintf(text, sizeof(text), "%.2f", get(l[key]));
            return std::string(text);
        };
        std::string extents = "-";
        if (l.contains("eacdMeanExtent")) {
            const nlohmann::json& e = l["eacdMeanExtent"][0];
            char text[64];
            std::snprintf(text, sizeof(text), "%.2f, %.2f, %.2f", e[0].get<double>(), e[1].get<double>(), e[2].get<double>());
            extents = text;
        }
        std::printf("| %s | %u | %.1f | %s | %s | %s |\n", r.name.c_str(), s["regions"].get<uint32_t>(),
                    s["meanRegionSize"].get<double>(),
                    number("pcMeanRadius", [](const nlohmann::json& j) { return j.get<double>(); }).c_str(),
                    number("acdMeanEdge", [](const nlohmann::json& j) { return j[0].get<double>(); }).c_str(),
                    extents.c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Times every preprocessing stage on real datasets (spacing and transfer function from MANIFEST.tsv)."};
    std::vector<std::string> datasets{"boston_teapot_256x256x178_uint8.raw.gz", "cranium_ct_256x256x108_int16.raw.gz"};
    vr::PrepareOptions options;
    options.segmentation.opacityThreshold = 0.01;
    options.segmentation.angleThresholdDeg = 3;
    bool noNormals = false;
    int runs = 3;
    std::string scratch = (fs::temp_directory_path() / "prep_bench").string();
    app.add_option("datasets", datasets, "file names in MANIFEST.tsv")->capture_default_str();
    app.add_option("--to", options.segmentation.opacityThreshold, "T_o")->capture_default_str();
    app.add_option("--ta", options.segmentation.angleThresholdDeg, "T_a, degrees")->capture_default_str();
    app.add_flag("--trilinear", options.segmentation.trilinear, "regions for trilinear sampling");
    app.add_flag("--no-normals", noNormals, "no gradients (T_a ignored)");
    app.add_option("--runs", runs, "runs per dataset (the median is printed)")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--scratch", scratch, "folder for the prepared files")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    options.classify.normals = options.segmentation.useNormals = !noNormals;

    try {
        fs::create_directories(scratch);
        std::vector<DatasetResult> results;
        for (const std::string& d : datasets) results.push_back(benchDataset(d, options, runs, scratch));
        printTables(results, options, runs);
    } catch (const vr::InputError& e) {
        std::fprintf(stderr, "prep_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
