#pragma once
// The integrator study's figures as a gnuplot script and the data files it reads. Each
// integrator's line is drawn in its colour from render/palette.hpp, the colours the viewer
// draws its bodies in. Running gnuplot is the program's business, not the study's.
#include <array>
#include <filesystem>
#include <string>

#include "study.hpp"

namespace pba::study {

/// The pictures the script draws, in its working folder.
inline constexpr std::array<const char*, 3> kPlotFiles{"height.png", "energy.png", "convergence.png"};
/// Drawn too for a scene with springs (when the result has a stability study).
inline constexpr const char* kStabilityPlotFile = "stability.png";

/// Writes the data files into `dir` and returns the script that draws kPlotFiles from them
/// (run it with `dir` as the working folder).
std::string plotScript(const std::filesystem::path& dir, const StudyConfig& config, const StudyResult& result);

} // namespace pba::study
