#pragma once
// Writing the rotation study (`pba compare` on a scene with rigid bodies): results.csv, the
// plots and report.md.
#include <filesystem>
#include <string>

#include "study/rotation_study.hpp"

namespace pba::app {

/// A table of one measure of the runs: integrators down, dt across (text or Markdown).
enum class RotationMeasure { EnergyDrift, MomentumDrift, PeriodError };
std::string rotationTable(const study::RotationConfig& config, const study::RotationResult& result,
                          RotationMeasure measure, bool markdown);

void writeRotationCsv(const std::filesystem::path& path, const study::RotationResult& result);
/// Draws drift.png, flip.png (a body with three different moments) and (with an exact period)
/// period.png; false (and nothing written) without gnuplot.
bool writeRotationPlots(const std::filesystem::path& dir, const study::RotationConfig& config,
                        const study::RotationResult& result);
void writeRotationReport(const std::filesystem::path& path, const study::RotationConfig& config,
                         const study::RotationResult& result, bool withPlots);

} // namespace pba::app
