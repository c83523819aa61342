#pragma once
// The integrator study: run one scene for every (integrator, collision response, dt), measure
// each moving particle against the exact solution (a system without one, a rope or a cloth, as
// a whole against a fine-dt run of the same method), and measure each integrator's order of
// accuracy on the harmonic oscillator. Runs are independent and deterministic, so the results
// do not depend on how many run at once.
#include <functional>
#include <optional>
#include <limits>
#include <string>
#include <vector>

#include "pba/scene/scene.hpp"
#include "series.hpp"
#include "stability.hpp"

namespace pba::study {

struct StudyConfig {
    Scene scene;
    std::vector<Integrator> integrators{kAllIntegrators.begin(), kAllIntegrators.end()};
    std::vector<CollisionResponse> collisions{kAllCollisionResponses.begin(), kAllCollisionResponses.end()};
    std::vector<double> dts{0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1};
    double duration = 10.0;
    int jobs = 1;
    /// What the stability study (scenes with springs only) counts as stable.
    StabilityCriterion stability;
};

/// The name of the row that stands for the whole system in a study that follows one
/// (StudyResult::followsSystem): its energy is the world's total, its position the centre of mass.
inline constexpr const char* kSystemRow = "(system)";

/// What one particle did in one run. NaN where a measure does not apply (no exact solution,
/// no complete bounce).
struct ParticleResult {
    std::string particle;
    Integrator integrator{};
    CollisionResponse collision{};
    double dt = 0.0;
    std::uint64_t steps = 0;
    double energyRatioEnd = 0.0;     ///< E(end) / E(0)
    double maxEnergyDeviation = 0.0; ///< max |E(t)/E(0) - 1|
    double meanEnergyRatio = 0.0;    ///< E/E(0) averaged over the steps: drift without the phase of the last step
    std::uint64_t bounces = 0;
    double apexRatioLast = 0.0;      ///< apex after the last bounce / drop height
    double periodError = 0.0;        ///< (measured mean period - exact) / exact
    double maxPositionError = 0.0;   ///< max |x(t) - x_exact(t)|, m; for the system row, its centre of mass against the reference run's
    /// The system row's: its centre of mass's largest distance from the reference's before the
    /// reference's first impact, m (the runs part at impacts, where the responses act on
    /// positions found a step late); NaN for other rows and without a reference.
    double errorBeforeImpact = std::numeric_limits<double>::quiet_NaN();
    /// The system row's: when a moving body first met a surface, s (NaN: never, or another row).
    double firstImpactAt = std::numeric_limits<double>::quiet_NaN();
    /// The time at which the run's state stopped being finite (NaN when it did not): the run
    /// stops there, its energy ratios read infinite and its series end there.
    double blewUpAt = std::numeric_limits<double>::quiet_NaN();
    /// The first row's of a run (the one the plots follow: the first moving particle, or the
    /// system); empty for the others.
    Series series;
};

/// The order is fitted where the error behaves as C dt^p: dt small enough for the leading term
/// to dominate, error large enough to stand above rounding.
inline constexpr double kOrderMaxDt = 0.02;        ///< s
inline constexpr double kOrderRoundingError = 1e-11; ///< m

struct OrderResult {
    Integrator integrator{};
    std::vector<double> dts;
    std::vector<double> errors; ///< max position error over the window, m
    std::vector<double> fitted; ///< the dt in the asymptotic range, the fit's points
    double measured = 0.0;      ///< least-squares slope of log(error) against log(dt); NaN with fewer than two points
    int expected = 0;
};

struct StudyResult {
    /// In (integrator, collision, dt, particle) order; a study that follows the system puts its
    /// row first in each run.
    std::vector<ParticleResult> runs;
    /// Whether the study follows the whole system (total energy, centre of mass) rather than one
    /// particle: several bodies move and the first has no exact solution. One particle of a rope
    /// says little about the rope, and has nothing exact to be compared with.
    bool followsSystem = false;
    /// The dt of the reference runs a system is compared with (the same method and response at a
    /// quarter of the smallest dt studied); NaN when the study does not follow a system.
    double referenceDt = std::numeric_limits<double>::quiet_NaN();
    /// Whether every moving body is coupled: then `exact` acts as `reflect` (a coupled body has
    /// no path of its own to find a time of impact on) and the two responses give the same runs.
    bool exactActsAsReflect = false;
    /// Whether a force of the scene may add energy (the blow dryer): then every energy of the
    /// runs is the bodies' less the work those sources did on them (BlowUpWatch), so that its
    /// ratios show what the integration and the contacts made of the energy, not the push.
    bool lessSourceWork = false;
    std::vector<OrderResult> orders;
    double orderWindow = 2.0;         ///< s, the time window of the order study
    /// The scene's highest natural frequency, rad/s; empty without springs on moving bodies,
    /// and then there is no stability study.
    std::optional<double> omegaMax;
    std::vector<StabilityResult> stability; ///< one per integrator, in the config's order
};

/// The runs runStudy reports progress in: the study's runs, the order fits and, for a scene
/// with springs, the stability limits.
long studyTaskCount(const StudyConfig& config);

/// `progress(done, total)` is called from the calling thread only.
StudyResult runStudy(const StudyConfig& config, const std::function<void(long, long)>& progress = {});

/// Runs `scene` with the given integrator and response and measures its moving particles; with
/// `system`, a row for the whole system first (see kSystemRow), whose series keeps
/// `seriesPoints` samples at most, the centre of mass included.
std::vector<ParticleResult> measureRun(const Scene& scene, Integrator integrator, CollisionResponse collision,
                                       double dt, double duration, bool system = false,
                                       std::size_t seriesPoints = 2000);

/// Whether a study of `world` follows the whole system (see StudyResult::followsSystem).
bool followsSystem(const World& world);

/// Order of accuracy from the spring scene: max position error over [0, window] for each dt;
/// the slope is fitted over the dt <= kOrderMaxDt whose error stands above rounding
/// (> kOrderRoundingError), and is NaN unless there are two of them.
OrderResult measureOrder(const Scene& spring, Integrator integrator, const std::vector<double>& dts, double window);

} // namespace pba::study
