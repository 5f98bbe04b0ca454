// One row of stereo.csv: one dataset's orbit of stereo pairs (sweep/stereo_measure.h), the right eye reprojected
// from the left against both eyes cast in full.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "sweep/stereo_measure.h"
#include "sweep/sweep_row.h"

namespace vr {

struct StereoRow {
    std::string dataset, caster;
    int views = 0, width = 0, height = 0;
    std::string render;  // the render settings of the dataset's sweep (SweepRow::render)
    double separationPerFocus = 0;
    double oneEyeMs = 0, pairMs = 0, fullPairMs = 0, reprojectMs = 0;  // medians over the views
    double recastPercent = 0;                                          // of the right eye, mean over the views
    ErrorSummary error;  // the reused right eye against its full render

    static StereoRow of(const std::string& dataset, Caster caster, int width, int height, int views,
                        const std::string& render, const StereoMeasurement& m);
    // The row as the error plot takes it: its time as the pair's over one eye's.
    SweepRow plotted() const;
};

std::vector<StereoRow> readStereoCsv(const std::filesystem::path& path);  // none when the file does not exist
void appendStereoCsv(const std::filesystem::path& path, const StereoRow& row);

}  // namespace vr
