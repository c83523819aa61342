#include "sim_summary.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "pba/rigid_body.hpp"

namespace pba::app {

namespace {

/// Statistics of each swarm instead of a row per particle.
void printSwarmSummary(const World& world)
{
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const Swarm& swarm = world.swarm(s);
        dvec3 mean(0.0);
        double speed = 0.0, low = INFINITY, high = -INFINITY;
        std::size_t outside = 0;
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            const dvec3 x(swarm.position(i));
            mean += x;
            speed += glm::length(dvec3(swarm.velocity(i)));
            low = std::min(low, x.y);
            high = std::max(high, x.y);
            for (const Plane& plane : world.planes())
                if (plane.distance(x) < -1e-4 && !(plane.holeRadius > 0 && plane.overHole(x))) {
                    ++outside;
                    break;
                }
        }
        const double n = double(std::max<std::size_t>(swarm.size(), 1));
        fmt::print("swarm {}: {} particles ({}), mean position ({:.3f}, {:.3f}, {:.3f}), height {:.3f} to {:.3f}, "
                   "mean speed {:.3f} m/s, {} outside the surfaces\n",
                   swarm.name(), swarm.size(), integratorName(swarm.integrator()), mean.x / n, mean.y / n, mean.z / n,
                   low, high, speed / n, outside);
    }
}

/// What the bodies did in the blow dryer's jet, and how many swarm particles are in its shaft.
void printJetSummary(const World& world, const study::JetWatch& jet)
{
    if (!jet.active())
        return;
    const double g = glm::length(world.gravity());
    fmt::print("blow dryer: {:g} N at the nozzle ({}), lifts up to {:.3g} kg; a catch is a stay of {:g} s in the cone\n",
               jet.field().strength, flowDirectionName(jet.field().direction),
               g > 0.0 ? jet.field().strength / g : INFINITY, study::kCatchStay);
    const auto bodies = jet.bodies();
    if (!bodies.empty())
        fmt::print("{:<22} {:>8} {:>10} {:>10} {:>12} {:>14} {:>15}\n", "body", "mass", "in cone", "caught at",
                   "longest stay", "height in cone", "longest in hole");
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const study::BodyInJet& b = bodies[i];
        if (world.body(i).isFixed())
            continue;
        fmt::print("{:<22} {:>6.3g}kg {:>9.1f}% {:>10} {:>11.2f}s {:>13.3f}m {:>14.2f}s\n", b.name, b.mass,
                   100.0 * jet.fractionInCone(i), b.caughtAt ? fmt::format("{:.2f}s", *b.caughtAt) : std::string("never"),
                   b.longestStay, b.meanHeightInCone, b.longestInShaft);
    }
    const auto inShaft = jet.swarmsInShaft(world);
    for (std::size_t s = 0; s < inShaft.size(); ++s) {
        const auto& figures = jet.swarms()[s];
        fmt::print("swarm {}: at most {} particles in the cone (t = {:.1f} s, counted every {:g} s); {} in "
                   "the dryer's shaft at the end; no particle stayed there longer than {:.3f} s at a stretch\n",
                   world.swarm(s).name(), figures.peakInCone, figures.peakAt, study::JetWatch::kSwarmSample,
                   inShaft[s], figures.longestInShaft);
    }
}

/// What each rigid body did, as the watch measured it: the parts that apply to it.
void printRigidSummary(const World& world, const study::RigidWatch& rigid)
{
    if (!rigid.active())
        return;
    fmt::print("rigid bodies (still: |v| < {:g} m/s and |w| < {:g} rad/s; rolling: the contact slips slower than {:g} "
               "m/s):\n", study::kStill, study::kStill, study::kNoSlip);
    for (const study::RigidFigures& f : rigid.bodies(world)) {
        std::vector<std::string> parts;
        if (!f.stillFrom)
            parts.push_back("moving at the end");
        else if (f.restingFace.empty())
            parts.push_back(fmt::format("still from t = {:.3f} s", *f.stillFrom));
        else
            parts.push_back(fmt::format("still from t = {:.3f} s on its {} face (tilted {:.2f} degrees)", *f.stillFrom,
                                        f.restingFace, f.tilt));
        if (f.rollingFrom)
            parts.push_back(fmt::format("rolls without slipping from t = {:.3f} s at {:.4f} m/s", *f.rollingFrom,
                                        f.rollingSpeed));
        if (f.free())
            parts.push_back(fmt::format("free of torques (its rotational energy and |L| stay within {:.1e} and {:.1e} "
                                        "of their start)", f.energyDrift, f.momentumDrift));
        if (f.free() && f.flips.size() >= 2)
            parts.push_back(fmt::format("turns over {} times, every {:.3f} s on average (its spin about its middle axis "
                                        "changes sign)", f.flips.size(),
                                        (f.flips.back() - f.flips.front()) / double(f.flips.size() - 1)));
        parts.push_back(fmt::format("spins at {:.3g} rad/s on average", f.meanSpin));
        fmt::print("  {}: {}\n", f.name, fmt::join(parts, "; "));
    }
}

/// E now / E start to six places, or, where those read 1.000000 and it is not 1, how far from
/// 1 it is ("1 - 4.6e-14"): a rounding-level drift is what exact integration claims.
std::string energyRatioText(double ratio)
{
    const double off = ratio - 1.0;
    if (off != 0.0 && std::abs(off) < 5e-7)
        return fmt::format("1 {} {:.1e}", off > 0.0 ? '+' : '-', std::abs(off));
    return fmt::format("{:.6f}", ratio);
}

} // namespace

void printSummary(const Scene& scene, const World& world, const std::vector<BodySummary>& summary,
                  const study::JetWatch& jet, const study::RigidWatch& rigid)
{
    fmt::print("scene {}: {} steps of dt = {:.6g} s, t = {:.6g} s, collision response {}{}\n", scene.name, world.stepCount(),
               scene.dt, world.time(), collisionResponseName(world.collisionResponse()),
               world.coupledBodiesReflect() ? " (reflect for bodies joined by springs)" : "");
    if (world.bodyCount() == 0) {
        printSwarmSummary(world);
        printJetSummary(world, jet);
        return;
    }
    fmt::print("{:<22} {:<20} {:>32} {:>11} {:>10} {:>8} {:>14}\n", "body", "integrator", "final position (m)",
               "speed (m/s)", "highest y", "bounces", "E now/E start");
    const std::vector<double> energies = world.energies();
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        const Body& b = world.body(i);
        const dvec3& x = b.getPos();
        const double ratio = summary[i].startEnergy != 0.0 ? energies[i] / summary[i].startEnergy : 1.0;
        fmt::print("{:<22} {:<20} {:>32} {:>11.4g} {:>10.4f} {:>8} {:>14}\n", b.getName(),
                   b.isFixed() ? std::string("(fixed)") : std::string(integratorName(b.getIntegrator())),
                   fmt::format("({:.4f}, {:.4f}, {:.4f})", x.x, x.y, x.z), glm::length(b.getVel()),
                   summary[i].highest, world.bounceCount(i), energyRatioText(ratio));
    }
    printRigidSummary(world, rigid);
    printSwarmSummary(world);
    printJetSummary(world, jet);
}


} // namespace pba::app
