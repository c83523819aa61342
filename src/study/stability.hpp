#pragma once
// Each integrator's stability limit, measured and set beside the theory. The theory needs the
// scene's highest natural frequency, from the largest eigenvalue of M^-1 K (K the springs'
// stiffness matrix linearised at the start state, found by power iteration); the measurement
// bisects on dt for the largest dt whose energy stays bounded over a number of periods of that
// mode.
#include <optional>
#include <string>
#include <vector>

#include "pba/scene/scene.hpp"
#include "series.hpp"

namespace pba::study {

/// What "stable" means: the world's energy (kinetic + potential) never rises above
/// E(0) + (energyFactor - 1) |E(0)| over `periods` periods 2 pi / omega_max of the highest mode,
/// stays finite, and no spring (of positive rest length L) leaves lengths (0, 2 L), where the
/// linear theory ends. The factor is large because a stable run near its limit swings far: semi-
/// implicit Euler released at rest reaches E(0) / (1 - omega dt / 2) and stays bounded there,
/// while above a limit the energy grows geometrically with every step and crosses any bound
/// within a few periods.
struct StabilityCriterion {
    double energyFactor = 1000.0;
    double periods = 50.0;
    double tolerance = 1e-4; ///< the bisection stops when the bracket is this narrow, relative
};

/// Largest eigenvalue's square root of M^-1 K over the moving bodies: the anchored springs
/// (sqrt(k/m) for one) and the two-body springs (chains, ropes, cloths), each contributing blocks
/// +-k u u^T with u its unit direction at the start state (the geometric term, zero at rest
/// length, is left out); fixed bodies drop out. Empty if the world has no spring acting on a
/// moving body, or a spring has no direction (zero length).
std::optional<double> highestFrequency(const World& world);
/// Whether some spring acts on a moving body: cheap, unlike highestFrequency, whose power
/// iteration takes seconds on a large cloth (its highest modes lie close together).
bool hasMovingSprings(const World& world);

/// The largest |length - L| / L over the springs (of rest length L > 0) at the start: how far
/// from small swings, the linear theory's premise, the scene starts (0 without such springs).
double largestStartStretch(const World& world);

/// The largest stable dt an undamped harmonic oscillator of frequency omega allows: 2 / omega
/// for semi-implicit Euler and velocity Verlet, 2 sqrt(2) / omega for RK4; NaN for forward
/// Euler, which gains energy at every dt.
double theoryDtLimit(Integrator integrator, double omega);

/// One run at one dt: stopped where it crossed the energy bound.
struct StabilityRun {
    double dt = 0.0;
    bool stable = false;
    bool leftLinearRegime = false; ///< unstable because a spring left lengths (0, 2 L), not by the energy bound
    Series series; ///< t and E/E(0) (y unused)
};

struct StabilityResult {
    Integrator integrator{};
    double omegaMax = 0.0;
    double theoryDt = 0.0;   ///< NaN: no finite limit (forward Euler)
    double measuredDt = 0.0; ///< the bisection's largest stable dt; NaN if not measured
    std::string unmeasured;  ///< why measuredDt is NaN ("" when measured)
    /// At measuredDt (1 - kStabilityMargin); when the scene leaves the linear regime whatever
    /// the dt (the limit not measured), the smallest dt tried, to show how it leaves.
    StabilityRun below;
    /// At measuredDt (1 + kStabilityMargin); stable when stability is not monotone in dt near the
    /// limit. Not measured as for `below`: at omega dt = 1.
    StabilityRun above;
    /// For a method the theory calls stable at every dt (implicit-euler, xpbd): a run at each
    /// omega dt of kLadderOmegaDt, whose end energy over the start is the damping it costs, and
    /// measuredDt the largest stable one ("stable up to the largest dt tried" when it is the last).
    std::vector<StabilityRun> ladder;
};

/// The omega dt an unconditionally stable method is run at, up to 128 times semi-implicit
/// Euler's limit of 2: its damping at each, and whether it stays stable.
inline constexpr double kLadderOmegaDt[] = {0.25, 1.0, 4.0, 16.0, 64.0, 256.0};

/// The bracket's range: below kMinOmegaDt a run of 50 periods is 60,000 steps and more.
inline constexpr double kMinOmegaDt = 0.005;
inline constexpr double kMaxOmegaDt = 64.0;

/// How far below and above the measured limit the plotted runs are, relative.
inline constexpr double kStabilityMargin = 0.02;

/// Runs `scene` with every moving body on `integrator` at `dt` for criterion.periods periods of
/// omega, stopping early where the energy crosses the bound.
StabilityRun runStability(const Scene& scene, Integrator integrator, double dt, double omega,
                          const StabilityCriterion& criterion);

/// Brackets the limit (doubling or halving dt from 1 / omega, within omega dt from kMinOmegaDt
/// to kMaxOmegaDt) and bisects it to the criterion's tolerance, then runs just below and just
/// above it for the plot. Not measured (NaN, with the reason) for a scene that starts with no
/// energy, which leaves no bound to set, or a limit outside the bracket's range.
StabilityResult measureStabilityLimit(const Scene& scene, Integrator integrator, double omega,
                                      const StabilityCriterion& criterion);

} // namespace pba::study
