#pragma once
// Writing the clocks study (`pba compare --clocks`): clocks.csv, clocks.png and report.md.
#include <filesystem>
#include <string>

#include "study/clock_study.hpp"

namespace pba::app {

/// The drift table: a row per clock and frames (steady, hitch), the 30 and 144 Hz runs' largest
/// distance from the 60 Hz run, and the steps the 60 Hz run took (text or Markdown).
std::string clockTable(const study::ClockConfig& config, const study::ClockResult& result, bool markdown);
/// The findings in sentences, computed from the result.
std::string clockFindings(const study::ClockConfig& config, const study::ClockResult& result);

void writeClockCsv(const std::filesystem::path& path, const study::ClockResult& result);
/// Draws clocks.png; false (and nothing written) without gnuplot.
bool writeClockPlot(const std::filesystem::path& dir, const study::ClockConfig& config, const study::ClockResult& result);
void writeClockReport(const std::filesystem::path& path, const study::ClockConfig& config,
                      const study::ClockResult& result, bool withPlot);

} // namespace pba::app
