// One row of sweep.csv: one dataset, one (T_o, T_a) setting and one caster, with its costs and error figures.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sweep/metrics/image_error.h"

namespace vr {

struct SweepRow {
    std::string dataset;
    double opacityThreshold = 0, angleThreshold = 0;  // T_o, T_a
    std::string caster;
    int views = 0, width = 0, height = 0;
    std::string render;  // the render settings the dataset's rows share (SweepOptions::renderSettings)
    // Preprocessing wall seconds at this setting (the same for every caster of the setting; 0: not built).
    double segmentSeconds = 0, pcSeconds = 0, acdSeconds = 0, eacdSeconds = 0;
    long long regions = 0;
    double deviceMsMedian = 0, deviceMsP95 = 0, wallMsMedian = 0;
    double ratioToPrimitive = 0;  // device median / the primitive caster's at this setting, same run
    double iterationsMean = 0, iterationsP95 = 0, iterationsMax = 0;  // per ray, over all views' pixels
    long long fieldBytes = 0;      // this caster's distance field (all octants)
    long long uploadedBytes = 0;   // everything uploaded for one render
    ErrorSummary error;            // against the reference over all views

    std::string key() const;
};

// The key of a row as the CSV writes it: "dataset,T_o,T_a,caster".
std::string rowKey(const std::string& dataset, double opacityThreshold, double angleThreshold,
                   const std::string& caster);

// The column names, in order.
const std::vector<std::string>& sweepColumns();
std::string csvHeader();
std::string toCsvLine(const SweepRow& row);
// Throws InputError naming `source` and the line for a malformed row.
SweepRow parseCsvLine(const std::string& line, const std::string& source, int lineNumber);

// Every row of a sweep.csv (none when the file does not exist); throws InputError for a foreign header.
std::vector<SweepRow> readSweepCsv(const std::filesystem::path& path);
// Appends rows, writing the header first when the file is new; flushed so an interrupted sweep keeps them.
void appendSweepCsv(const std::filesystem::path& path, const std::vector<SweepRow>& rows);

// A threshold as written in keys and labels (shortest exact-enough form, e.g. 0.005).
std::string thresholdText(double t);

// What the CSVs of the sweep share: a number as written (%.6g, "inf"), read back (InputError naming `where`), and
// the error figures' columns (mean then worst of RMSE, PSNR, max abs, SSIM, % off > 1/255, % CIEDE2000 > 2.3).
std::string csvNumber(double v);
double parseCsvNumber(const std::string& text, const std::string& where);
const std::vector<std::string>& errorColumns();
std::vector<double> errorFigures(const ErrorSummary& e);
ErrorSummary parseErrorFigures(const std::function<double()>& next);
// The cells of every line of a CSV after its header (none when the file does not exist), each with the line's
// description for errors ("FILE line N"); throws InputError naming the file for a foreign header, `kind` the CSV's
// name (sweep.csv), and for a line without `columns` cells.
struct CsvLine {
    std::vector<std::string> cells;
    std::string where;
};
std::vector<CsvLine> readCsvLines(const std::filesystem::path& path, const std::string& header, const char* kind,
                                  std::size_t columns);
// Appends lines, writing the header first when the file is new; flushed so an interrupted sweep keeps them.
void appendCsvLines(const std::filesystem::path& path, const std::string& header,
                    const std::vector<std::string>& lines);

}  // namespace vr
