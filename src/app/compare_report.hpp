#pragma once
// Writing the integrator study: results.csv, orders.csv, the plots and report.md.
#include <filesystem>
#include <functional>
#include <vector>
#include <string>

#include "study/study.hpp"
#include "study/work_precision.hpp"

namespace pba::app {

/// A table of the studies' shape, integrators down and dt across, text or Markdown, each cell
/// cell(integrator, dt).
std::string integratorTable(const std::vector<Integrator>& integrators, const std::vector<double>& dts, bool markdown,
                            const std::function<std::string(Integrator, double)>& cell);

/// The followed rows (the first moving particle's, or the system's), as a table of E(end)/E(0):
/// integrators down, dt across.
std::string energyTable(const study::StudyConfig& config, const study::StudyResult& result,
                        CollisionResponse collision, bool markdown);

/// For a study that follows a system: the centre of mass's largest distance from the reference
/// run, integrators down and dt across.
std::string centreErrorTable(const study::StudyConfig& config, const study::StudyResult& result,
                             CollisionResponse collision, bool markdown);

/// The table's title: the response it is for, or that every response gave it when nothing collided.
std::string energyTableHeading(const study::StudyConfig& config, const study::StudyResult& result,
                               CollisionResponse collision);

void writeResultsCsv(const std::filesystem::path& path, const study::StudyResult& result);
void writeOrdersCsv(const std::filesystem::path& path, const study::StudyResult& result);
/// One row per integrator of the stability study; theory_dt_limit is `none` for forward Euler.
/// Call only for a result with a stability study (a scene with springs).
void writeStabilityCsv(const std::filesystem::path& path, const study::StudyResult& result);
/// The report's stability section (Markdown, from its heading), or "" without a stability study.
std::string stabilitySection(const study::StudyConfig& config, const study::StudyResult& result, bool withPlots);
/// Draws height.png, energy.png, convergence.png and (with springs) stability.png with gnuplot; returns false (and writes
/// nothing) if gnuplot is missing.
bool writePlots(const std::filesystem::path& dir, const study::StudyConfig& config, const study::StudyResult& result);
/// `workPrecision`: the report's work-precision section (Markdown, from its heading), or "".
void writeReport(const std::filesystem::path& path, const study::StudyConfig& config, const study::StudyResult& result,
                 bool withPlots, const std::string& workPrecision = "");
/// work_precision.csv (scene,integrator,dt,error,cpu_s; runs that blew up left out), and with
/// gnuplot work_precision.png; returns the report's section on them.
std::string writeWorkPrecision(const std::filesystem::path& dir, const std::vector<study::WorkPrecisionPoint>& points,
                               bool plots);

} // namespace pba::app
