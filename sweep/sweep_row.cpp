#include "sweep/sweep_row.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "core/errors.h"

namespace vr {
namespace fs = std::filesystem;

// Numbers in the CSV: %.6g, with "inf" for an infinite PSNR.
std::string csvNumber(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char s[32];
    std::snprintf(s, sizeof s, "%.6g", v);
    return s;
}

double parseCsvNumber(const std::string& text, const std::string& where) {
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

std::vector<double> errorFigures(const ErrorSummary& e) {
    return {std::sqrt(e.mean.mse), std::sqrt(e.worst.mse), e.mean.psnr, e.worst.psnr, e.mean.maxAbs,
            e.worst.maxAbs, e.mean.ssim, e.worst.ssim, e.mean.percentOff8Bit, e.worst.percentOff8Bit,
            e.mean.percentPerceptual, e.worst.percentPerceptual};
}

ErrorSummary parseErrorFigures(const std::function<double()>& next) {
    ErrorSummary e;
    ImageError& m = e.mean;
    ImageError& w = e.worst;
    const double rmseMean = next(), rmseWorst = next();
    m.mse = rmseMean * rmseMean;
    w.mse = rmseWorst * rmseWorst;
    for (double* v : {&m.psnr, &w.psnr, &m.maxAbs, &w.maxAbs, &m.ssim, &w.ssim, &m.percentOff8Bit,
                      &w.percentOff8Bit, &m.percentPerceptual, &w.percentPerceptual})
        *v = next();
    return e;
}

const std::vector<std::string>& errorColumns() {
    static const std::vector<std::string> columns{"rmse_mean", "rmse_worst", "psnr_mean", "psnr_worst",
                                                  "maxabs_mean", "maxabs_worst", "ssim_mean", "ssim_worst",
                                                  "off8bit_pct_mean", "off8bit_pct_worst", "de2000_pct_mean",
                                                  "de2000_pct_worst"};
    return columns;
}

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
    static const std::vector<std::string> columns = [] {
        std::vector<std::string> c{"dataset", "T_o", "T_a", "caster", "views", "width", "height", "render",
                                   "segment_s",
                                   "pc_s", "acd_s", "eacd_s", "regions", "device_ms_median", "device_ms_p95",
                                   "wall_ms_median", "ratio_to_primitive", "iter_mean", "iter_p95", "iter_max",
                                   "field_bytes", "uploaded_bytes"};
        c.insert(c.end(), errorColumns().begin(), errorColumns().end());
        return c;
    }();
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
                                   std::to_string(r.height), r.render};
    for (double v : {r.segmentSeconds, r.pcSeconds, r.acdSeconds, r.eacdSeconds}) cells.push_back(csvNumber(v));
    cells.push_back(std::to_string(r.regions));
    for (double v : {r.deviceMsMedian, r.deviceMsP95, r.wallMsMedian, r.ratioToPrimitive, r.iterationsMean,
                     r.iterationsP95, r.iterationsMax})
        cells.push_back(csvNumber(v));
    cells.push_back(std::to_string(r.fieldBytes));
    cells.push_back(std::to_string(r.uploadedBytes));
    for (double v : errorFigures(r.error)) cells.push_back(csvNumber(v));
    std::string line;
    for (const std::string& c : cells) line += (line.empty() ? "" : ",") + c;
    return line;
}

namespace {

std::vector<std::string> csvCells(const std::string& line, const std::string& where, std::size_t columns) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (cells.size() != columns)
        throw InputError(where + ": " + std::to_string(cells.size()) + " columns, expected " +
                         std::to_string(columns));
    return cells;
}

SweepRow rowOfCells(const std::vector<std::string>& cells, const std::string& where) {
    std::size_t i = 0;
    auto next = [&] { return parseCsvNumber(cells[i++], where); };
    SweepRow r;
    r.dataset = cells[i++];
    r.opacityThreshold = next();
    r.angleThreshold = next();
    r.caster = cells[i++];
    r.views = int(next());
    r.width = int(next());
    r.height = int(next());
    r.render = cells[i++];
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
    r.error = parseErrorFigures(next);
    return r;
}

}  // namespace

SweepRow parseCsvLine(const std::string& line, const std::string& source, int lineNumber) {
    const std::string where = source + " line " + std::to_string(lineNumber);
    return rowOfCells(csvCells(line, where, sweepColumns().size()), where);
}

std::vector<CsvLine> readCsvLines(const fs::path& path, const std::string& header, const char* kind,
                                  std::size_t columns) {
    std::vector<CsvLine> lines;
    std::ifstream in(path);
    if (!in) return lines;
    std::string line;
    if (!std::getline(in, line)) return lines;
    if (line != header)
        throw fileError(path.string(), std::string("not a ") + kind + " of this version (its header differs); use "
                                       "another -o");
    for (int n = 2; std::getline(in, line); ++n)
        if (!line.empty()) {
            const std::string where = path.string() + " line " + std::to_string(n);
            lines.push_back({csvCells(line, where, columns), where});
        }
    return lines;
}

std::vector<SweepRow> readSweepCsv(const fs::path& path) {
    std::vector<SweepRow> rows;
    for (const CsvLine& line : readCsvLines(path, csvHeader(), "sweep.csv", sweepColumns().size()))
        rows.push_back(rowOfCells(line.cells, line.where));
    return rows;
}

void appendCsvLines(const fs::path& path, const std::string& header, const std::vector<std::string>& lines) {
    const bool fresh = !fs::exists(path) || fs::file_size(path) == 0;
    std::ofstream out(path, std::ios::app);
    if (!out) throw fileError(path.string(), "cannot append to the CSV");
    if (fresh) out << header << '\n';
    for (const std::string& line : lines) out << line << '\n';
    out.flush();
    if (!out) throw fileError(path.string(), "cannot write the CSV");
}

void appendSweepCsv(const fs::path& path, const std::vector<SweepRow>& rows) {
    std::vector<std::string> lines;
    for (const SweepRow& r : rows) lines.push_back(toCsvLine(r));
    appendCsvLines(path, csvHeader(), lines);
}

}  // namespace vr
