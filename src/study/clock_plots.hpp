#pragma once
// The clocks study's figure as a gnuplot script and the data files it reads: how far the runs at
// 30 and 144 Hz lie from the run at 60 Hz, per clock, steady and through the hitch.
#include <filesystem>
#include <string>

#include "clock_study.hpp"

namespace pba::study {

inline constexpr const char* kClockPlotFile = "clocks.png";

/// Writes the data files into `dir` and returns the script that draws kClockPlotFile from them.
std::string clockPlotScript(const std::filesystem::path& dir, const ClockConfig& config, const ClockResult& result);

} // namespace pba::study
