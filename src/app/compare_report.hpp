#pragma once
// Writing the integrator study: results.csv, orders.csv, the plots and report.md.
#include <filesystem>
#include <string>

#include "study/study.hpp"

namespace pba::app {

/// The first moving particle's rows, as a table of E(end)/E(0): integrators down, dt across.
std::string energyTable(const study::StudyConfig& config, const study::StudyResult& result,
                        CollisionResponse collision, bool markdown);

/// The table's title: the response it is for, or that every response gave it when nothing collided.
std::string energyTableHeading(const study::StudyConfig& config, const study::StudyResult& result,
                               CollisionResponse collision);

void writeResultsCsv(const std::filesystem::path& path, const study::StudyResult& result);
void writeOrdersCsv(const std::filesystem::path& path, const study::StudyResult& result);
/// Draws height.png, energy.png and convergence.png with gnuplot; returns false (and writes
/// nothing) if gnuplot is missing.
bool writePlots(const std::filesystem::path& dir, const study::StudyConfig& config, const study::StudyResult& result);
void writeReport(const std::filesystem::path& path, const study::StudyConfig& config, const study::StudyResult& result,
                 bool withPlots);

} // namespace pba::app
