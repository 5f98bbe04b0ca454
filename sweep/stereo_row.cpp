#include "sweep/stereo_row.h"


namespace vr {
namespace fs = std::filesystem;

namespace {

std::string stereoHeader() {
    std::string h = "dataset,caster,views,width,height,render,separation_per_focus,one_eye_ms,pair_ms,full_pair_ms,"
                    "reproject_ms,recast_pct";
    for (const std::string& c : errorColumns()) h += "," + c;
    return h;
}

}  // namespace

StereoRow StereoRow::of(const std::string& dataset, Caster caster, int width, int height, int views,
                        const std::string& render, const StereoMeasurement& m) {
    return {dataset, std::string(casterName(caster)), views, width, height, render, kSeparationPerFocus, m.oneEyeMs,
            m.pairMs, m.fullPairMs, m.reprojectMs, 100 * m.recastFraction, m.error};
}

SweepRow StereoRow::plotted() const {
    SweepRow r;
    r.dataset = dataset;
    r.caster = "stereo pair (" + caster + ", time / one eye's)";
    r.ratioToPrimitive = oneEyeMs > 0 ? pairMs / oneEyeMs : 0;
    r.error = error;
    return r;
}

std::vector<StereoRow> readStereoCsv(const fs::path& path) {
    std::vector<StereoRow> rows;
    for (const CsvLine& line : readCsvLines(path, stereoHeader(), "stereo.csv", 12 + errorColumns().size())) {
        std::size_t i = 2;
        auto next = [&] { return parseCsvNumber(line.cells[i++], line.where); };
        StereoRow r;
        r.dataset = line.cells[0];
        r.caster = line.cells[1];
        r.views = int(next());
        r.width = int(next());
        r.height = int(next());
        r.render = line.cells[i++];
        r.separationPerFocus = next();
        r.oneEyeMs = next();
        r.pairMs = next();
        r.fullPairMs = next();
        r.reprojectMs = next();
        r.recastPercent = next();
        r.error = parseErrorFigures(next);
        rows.push_back(r);
    }
    return rows;
}

void appendStereoCsv(const fs::path& path, const StereoRow& r) {
    std::string line = r.dataset + ',' + r.caster + ',' + std::to_string(r.views) + ',' + std::to_string(r.width) +
                       ',' + std::to_string(r.height) + ',' + r.render;
    for (double v : {r.separationPerFocus, r.oneEyeMs, r.pairMs, r.fullPairMs, r.reprojectMs, r.recastPercent})
        line += ',' + csvNumber(v);
    for (double v : errorFigures(r.error)) line += ',' + csvNumber(v);
    appendCsvLines(path, stereoHeader(), {line});
}

}  // namespace vr
