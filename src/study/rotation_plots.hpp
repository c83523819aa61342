#pragma once
// The rotation study's figures as a gnuplot script and the data files it reads, each
// integrator in its colour (render/palette.hpp), as the particles' study draws them.
#include <filesystem>
#include <string>

#include "rotation_study.hpp"

namespace pba::study {

/// drift.png (energy and |L| drift against dt); flip.png (the angular velocity about the
/// intermediate axis against time) for a body with three different moments; period.png too
/// where the exact flip period is known.
inline constexpr const char* kDriftPlotFile = "drift.png";
inline constexpr const char* kFlipPlotFile = "flip.png";
inline constexpr const char* kPeriodPlotFile = "period.png";

/// Writes the data files into `dir` and returns the script that draws the plots from them; the
/// studied body's name is not in it (a scene's text never becomes script text): run it with the
/// name as ARG1.
std::string rotationPlotScript(const std::filesystem::path& dir, const RotationConfig& config,
                               const RotationResult& result);

} // namespace pba::study
