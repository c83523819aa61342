#pragma once
// Work against precision: which method reaches a given accuracy for the least CPU time, the
// question a user choosing a method asks. Four scenes (the spring, the chain, the cloth and the
// tennis racket), each run for workPrecisionSeconds with every method it takes at every dt, on
// one thread, its error at the end against a reference run (RK4 at kReferenceDt, far more
// accurate than any point) and its CPU time.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "pba/integrator.hpp"
#include "pba/scene/scene.hpp"

namespace pba::study {

inline constexpr std::array<const char*, 4> kWorkPrecisionScenes{"spring", "chain", "cloth", "tennis-racket"};
inline constexpr double kWorkPrecisionSeconds = 1.0;
/// The chain's run is shorter: its free end strikes the room's wall at 0.85 s.
inline constexpr double kChainSeconds = 0.8;
inline constexpr double kReferenceDt = 1e-4;
inline constexpr std::array<double, 6> kWorkPrecisionDts{0.0005, 0.001, 0.002, 0.005, 0.01, 0.02};
inline constexpr const char* kWorkPrecisionPlotFile = "work_precision.png";

struct WorkPrecisionPoint {
    std::string scene;
    Integrator integrator{};
    double dt = 0.0;
    double error = 0.0;      ///< m (the largest position error) or, for the tennis racket, rad (its orientation's)
    double cpuSeconds = 0.0; ///< the run's CPU time on one thread
    bool blewUp = false;     ///< then error and cpuSeconds mean nothing
};

/// Every scene, method and dt. Throws what loadScene throws.
std::vector<WorkPrecisionPoint> runWorkPrecision();

/// How long `scene` runs: kWorkPrecisionSeconds, but the chain kChainSeconds. From the chain's
/// first impact on the wall on, each run meets it at another step and the iterative contact solve
/// resolves it differently, so the runs part by tenths of a metre whatever the dt, and an error
/// at 1 s measured the impacts rather than the method.
double workPrecisionSeconds(const std::string& scene);

/// One point's error: `scene` run with `integrator` at dt against the reference (RK4 at
/// kReferenceDt), both for workPrecisionSeconds(scene.name). Throws BlowUpError if it blows up.
double workPrecisionError(const Scene& scene, Integrator integrator, double dt);

/// Whether the scene's error is an orientation's (rad) rather than a position's (m).
bool measuresOrientation(const std::string& scene);

/// For each scene, the method that reached `error` or better for the least CPU time, in sentences.
std::string workPrecisionFindings(const std::vector<WorkPrecisionPoint>& points, double error);

/// Writes the data files into `dir` and returns the script that draws kWorkPrecisionPlotFile.
std::string workPrecisionPlotScript(const std::filesystem::path& dir, const std::vector<WorkPrecisionPoint>& points);

} // namespace pba::study
