#include "sweep/sweep_row.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/errors.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

// Numbers in the CSV: %.6g, with "inf" for an infinite PSNR.
std::string num(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char s[32];
    std::snprintf(s, sizeof s, "%.6g", v);
    return s;
}

double parseNumber(const std::string& text, const std::string& where) {
    if (text == "inf") return std::numeric_limits<double>::infinity();
    if (text == "-inf") return -std::numeric_limits<double>::infinity();
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || text.empty()) throw InputError(where + ": '" + text + "' is not a number");
    return v;
}

// The error figures in column order: mean then worst of each.
std::vector<double> errorFigures(const ErrorSummary& e) {
    return {std::sqrt(e.mean.mse), std::sqrt(e.worst.mse), e.mean.psnr, e.worst.psnr, e.mean.maxAbs,
            e.worst.maxAbs, e.mean.ssim, e.worst.ssim, e.mean.percentOff8Bit, e.worst.percentOff8Bit,
            e.mean.percentPerceptual, e.worst.percentPerceptual};
}

}  // namespace

std::string thresholdText(double t) {
    char s[32];
    std::snprintf(s, sizeof s, "%g", t);
    return s;
}

std::string rowKey(const std::string& dataset, double to, double ta, const std::string& caster) {
    return dataset + "," + thresholdText(to) + "," + thresholdText(ta) + "," + caster;
}

std::string SweepRow::key() const { return rowKey(dataset, opacityThreshold, angleThreshold, caster); }

const std::vector<std::string>& sweepColumns() {
    static const std::vector<std::string> columns{
        "dataset", "T_o", "T_a", "caster", "views", "width", "height", "segment_s", "pc_s", "acd_s", "eacd_s",
        "regions", "device_ms_median", "device_ms_p95", "wall_ms_median", "ratio_to_primitive", "iter_mean",
        "iter_p95", "iter_max", "field_bytes", "uploaded_bytes", "rmse_mean", "rmse_worst", "psnr_mean",
        "psnr_worst", "maxabs_mean", "maxabs_worst", "ssim_mean", "ssim_worst", "off8bit_pct_mean",
        "off8bit_pct_worst", "de2000_pct_mean", "de2000_pct_worst"};
    return columns;
}

std::string csvHeader() {
    std::string h;
    for (const std::string& c : sweepColumns()) h += (h.empty() ? "" : ",") + c;
    return h;
}

std::string toCsvLine(const SweepRow& r) {
    std::vector<std::string> cells{r.dataset, thresholdText(r.opacityThreshold), thresholdText(r.angleThreshold),
                                   r.caster, std::to_string(r.views), std::to_string(r.width),
                                   std::to_string(r.height)};
    for (double v : {r.segmentSeconds, r.pcSeconds, r.acdSeconds, r.eacdSeconds}) cells.push_back(num(v));
    cells.push_back(std::to_string(r.regions));
    for (double v : {r.deviceMsMedian, r.deviceMsP95, r.wallMsMedian, r.ratioToPrimitive, r.iterationsMean,
                     r.iterationsP95, r.iterationsMax})
        cells.push_back(num(v));
    cells.push_back(std::to_string(r.fieldBytes));
    cells.push_back(std::to_string(r.uploadedBytes));
    for (double v : errorFigures(r.error)) cells.push_back(num(v));
    std::string line;
    for (const std::string& c : cells) line += (line.empty() ? "" : ",") + c;
    return line;
}

SweepRow parseCsvLine(const std::string& line, const std::string& source, int lineNumber) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    const std::string where = source + " line " + std::to_string(lineNumber);
    if (cells.size() != sweepColumns().size())
        throw InputError(where + ": " + std::to_string(cells.size()) + " columns, expected " +
                         std::to_string(sweepColumns().size()));
    std::size_t i = 0;
    auto next = [&] { return parseNumber(cells[i++], where); };
    SweepRow r;
    r.dataset = cells[i++];
    r.opacityThreshold = next();
    r.angleThreshold = next();
    r.caster = cells[i++];
    r.views = int(next());
    r.width = int(next());
    r.height = int(next());
    r.segmentSeconds = next();
    r.pcSeconds = next();
    r.acdSeconds = next();
    r.eacdSeconds = next();
    r.regions = (long long)next();
    r.deviceMsMedian = next();
    r.deviceMsP95 = next();
    r.wallMsMedian = next();
    r.ratioToPrimitive = next();
    r.iterationsMean = next();
    r.iterationsP95 = next();
    r.iterationsMax = next();
    r.fieldBytes = (long long)next();
    r.uploadedBytes = (long long)next();
    ImageError& m = r.error.mean;
    ImageError& w = r.error.worst;
    const double rmseMean = next(), rmseWorst = next();
    m.mse = rmseMean * rmseMean;
    w.mse = rmseWorst * rmseWorst;
    for (double* v : {&m.psnr, &w.psnr, &m.maxAbs, &w.maxAbs, &m.ssim, &w.ssim, &m.percentOff8Bit,
                      &w.percentOff8Bit, &m.percentPerceptual, &w.percentPerceptual})
        *v = next();
    return r;
}

std::vector<SweepRow> readSweepCsv(const fs::path& path) {
    std::vector<SweepRow> rows;
    std::ifstream in(path);
    if (!in) return rows;
    std::string line;
    if (!std::getline(in, line)) return rows;
    if (line != csvHeader())
        throw fileError(path.string(), "not a sweep.csv of this version (its header differs); use another -o");
    for (int n = 2; std::getline(in, line); ++n)
        if (!line.empty()) rows.push_back(parseCsvLine(line, path.string(), n));
    return rows;
}

void appendSweepCsv(const fs::path& path, const std::vector<SweepRow>& rows) {
    const bool fresh = !fs::exists(path) || fs::file_size(path) == 0;
    std::ofstream out(path, std::ios::app);
    if (!out) throw fileError(path.string(), "cannot append to the CSV");
    if (fresh) out << csvHeader() << '\n';
    for (const SweepRow& r : rows) out << toCsvLine(r) << '\n';
    out.flush();
    if (!out) throw fileError(path.string(), "cannot write the CSV");
}

}  // namespace vr
