#pragma once
// The integrator study of rotation: a scene with rigid bodies run with every integrator and dt,
// measuring how far each method lets the first moving rigid body's energy and |L| drift, and,
// for a body spun near its intermediate axis, the period of its flips against the exact one
// (the complete elliptic integral of the first kind). The particles' study (study.hpp) measures
// positions against exact trajectories; a tumbling body's exact state is an elliptic function,
// so its invariants and its period are what is compared.
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "pba/scene/scene.hpp"

namespace pba::study {

struct RotationConfig {
    Scene scene;
    std::optional<std::size_t> body; ///< the body measured; the first moving rigid body if none
    std::vector<Integrator> integrators{kRigidIntegrators.begin(), kRigidIntegrators.end()};
    std::vector<double> dts{0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05};
    double duration = 10.0;
    int jobs = 1; ///< runs at once; the results do not depend on it
};

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One run of the studied body.
struct RotationRun {
    Integrator integrator{};
    double dt = 0.0;
    std::uint64_t steps = 0;
    double maxEnergyDrift = 0.0;   ///< max |E(t)/E(0) - 1| (E with its rotational term)
    double maxMomentumDrift = 0.0; ///< max ||L(t)| / |L(0)| - 1|, L about the centre of mass; NaN if L(0) = 0
    double energyRatioEnd = 0.0;   ///< E(end) / E(0)
    double flipPeriod = kNaN;      ///< mean time between two flips of the same sense, s (NaN: fewer than 3 flips)
    std::uint64_t flips = 0;
    bool touched = false;          ///< whether the body touched another body or the room in the run
    double blewUpAt = kNaN;        ///< the time the state stopped being finite, if it did
    /// Sampled series: t, E/E0, and the body-frame angular velocity about the intermediate axis.
    std::vector<double> t, energyRatio, intermediateOmega;
};

struct RotationResult {
    std::string body;           ///< the studied body's name
    bool joined = false;        ///< whether a joint holds it (then no run of it is a free body's)
    int intermediateAxis = -1;  ///< the body axis of intermediate inertia (-1: two moments equal)
    double exactPeriod = kNaN;  ///< torque-free flip period, s (NaN where the formula does not apply)
    /// Whether it starts spun nearer its intermediate axis than the others (its angular
    /// momentum's largest body-frame component there): it flips over and back. Spun nearer the
    /// largest or smallest axis it only wobbles, its intermediate spin changing sign as often.
    bool flips = false;
    bool spins = false; ///< whether it starts with any angular momentum
    std::vector<RotationRun> runs; ///< in (integrator, dt) order
};

/// Which body axis is the intermediate one, for an inertia tensor diagonal in the body's own
/// frame (every built-in shape's); -1 if two moments are equal.
int intermediateAxisOf(const dmat3& inertia);

/// The first moving rigid body of the scene, or nothing.
std::optional<std::size_t> studiedRigidBody(const World& world);

/// A torque-free body's flip period from its moments, energy and |L|: with the moments ordered
/// a < b < c and L^2 < 2 E b, T = 4 K(k) sqrt(a b c / ((b - a)(2 E c - L^2))),
/// k^2 = (c - b)(L^2 - 2 E a) / ((b - a)(2 E c - L^2)); with L^2 > 2 E b the roles of a and c
/// swap. NaN for a symmetric body, or one spinning exactly on an axis (no flip).
double torqueFreeFlipPeriod(const RigidBody& body);

/// `progress(done, total)` after each run, from the calling thread.
RotationResult runRotationStudy(const RotationConfig& config, const std::function<void(long, long)>& progress = {});

} // namespace pba::study
