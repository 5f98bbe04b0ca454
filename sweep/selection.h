// Which rows of a sweep the report singles out: the quality target and the best setting meeting it.
#pragma once
#include <string>
#include <vector>

#include "sweep/sweep_row.h"

namespace vr {

// The target: PSNR >= 40 dB and fewer than 1 % of the pixels off by more than 1/255, both in the WORST view.
constexpr double kTargetPsnr = 40;
constexpr double kTargetPercentOff = 1;
// The speed-up EACD aims for over the primitive caster at the quality target.
constexpr double kTargetSpeedUp = 8;

bool meetsQualityTarget(const SweepRow& row);

// The primitive caster's device median over this row's, at the same setting in the same run (0 when unknown).
double speedUp(const SweepRow& row);

// The row of `caster` (any caster but primitive when empty) with the largest speed-up that meets the quality
// target; null when none does.
const SweepRow* bestMeetingTarget(const std::vector<SweepRow>& rows, const std::string& caster = "");

// The datasets in the order of their first row, and one dataset's rows.
std::vector<std::string> datasetsOf(const std::vector<SweepRow>& rows);
std::vector<SweepRow> rowsOf(const std::vector<SweepRow>& rows, const std::string& dataset);

// The casters of some rows in the order of their first row.
std::vector<std::string> castersOf(const std::vector<SweepRow>& rows);

}  // namespace vr

namespace vr {

// PSNR as plotted: an exact image (inf) is drawn at this height.
constexpr double kPlotPsnrCap = 100;
double plottedPsnr(const SweepRow& row);

// The Pareto fronts over (render time relative to primitive, error) of some rows: error = mean PSNR (higher is
// better) or the mean percentage of pixels with CIEDE2000 > 2.3.
std::vector<bool> psnrFront(const std::vector<SweepRow>& rows);
std::vector<bool> perceptualFront(const std::vector<SweepRow>& rows);

}  // namespace vr
