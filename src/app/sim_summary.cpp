#include "sim_summary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "pba/particle.hpp"
#include "pba/rigid_body.hpp"
#include "study/exact_solution.hpp"
#include "study/mound.hpp"

namespace pba::app {

namespace {

/// c for printing to `places` decimals: 0 where it rounds to zero, which would print as -0.000.
double placed(double c, int places)
{
    return std::abs(c) < 0.5 * std::pow(10.0, -places) ? 0.0 : c;
}

/// A coordinate to four places while that fits a table's column; one flung far off in figures
/// (1.272e+06), where four places pushed the rest of its row along.
std::string coordinateText(double c)
{
    return std::abs(c) < 1e4 ? fmt::format("{:.4f}", placed(c, 4)) : fmt::format("{:.4g}", c);
}

/// A vector to four places.
std::string vectorText(const dvec3& v)
{
    return fmt::format("({}, {}, {})", coordinateText(v.x), coordinateText(v.y), coordinateText(v.z));
}

/// Which bodies are a rope's or cloth's particles.
std::vector<bool> fabricMembers(const render::BodyGroups& groups, std::size_t bodies)
{
    std::vector<bool> in(bodies);
    for (std::size_t i = 0; i < in.size(); ++i)
        in[i] = groups.inFabric(i);
    return in;
}

/// Whether `exact` acts as `reflect` on some body of this run: a coupled one that XPBD does not
/// step (XPBD meets the room in each substep, under any response).
bool reflectsCoupledBodies(const World& world)
{
    if (!world.coupledBodiesReflect())
        return false;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (world.isCoupled(i) && !world.body(i).isFixed() && world.body(i).getIntegrator() != Integrator::Xpbd)
            return true;
    return false;
}

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
        if (swarm.size() == 0) {
            fmt::print("swarm {}: no particles ({})\n", swarm.name(), integratorName(swarm.integrator()));
            continue;
        }
        const double n = double(swarm.size());
        fmt::print("swarm {}: {} particle{} ({}), mean position ({:.3f}, {:.3f}, {:.3f}), height {:.3f} to {:.3f}, "
                   "mean speed {:.3f} m/s, {} beyond the room's surfaces{}\n",
                   swarm.name(), swarm.size(), swarm.size() == 1 ? "" : "s", integratorName(swarm.integrator()),
                   placed(mean.x / n, 3), placed(mean.y / n, 3), placed(mean.z / n, 3),
                   low, high, speed / n, outside, world.floorHole() ? " (those in the floor's hole not counted)" : "");
        if (!swarm.desc().collide || swarm.size() < 2)
            continue;
        const dvec3 g = world.gravity();
        const std::string mound = glm::length(g) > 0.0 && swarm.size() >= 3
                                      ? fmt::format("its grains' mound stands at {:.1f} degrees (a line through each "
                                                    "ring's highest grain about its axis), ",
                                                    study::angleOfRepose(swarm, -glm::normalize(g)))
                                      : std::string("its grains: ");
        fmt::print("swarm {}: {}the deepest two grains overlap by {:.3f} of a radius\n", swarm.name(), mound,
                   study::deepestGrainOverlap(swarm));
    }
}

/// Each rope and cloth in the jet, in one line instead of a row per particle.
void printFabricInJet(const World& world, const study::JetWatch& jet, const render::BodyGroups& groups)
{
    const auto bodies = jet.bodies();
    for (const render::BodyGroup& g : groups.groups()) {
        if (!g.fabric())
            continue;
        double mean = 0.0, least = 1.0, height = 0.0;
        std::optional<double> allCaught = 0.0; // when the last particle was caught, if every one was
        std::size_t moving = 0;
        for (const std::size_t i : g.members) {
            if (i >= bodies.size() || world.body(i).isFixed())
                continue;
            ++moving;
            mean += jet.fractionInCone(i);
            least = std::min(least, jet.fractionInCone(i));
            height += std::isfinite(bodies[i].meanHeightInCone) ? bodies[i].meanHeightInCone : 0.0;
            allCaught = allCaught && bodies[i].caughtAt ? std::optional(std::max(*allCaught, *bodies[i].caughtAt))
                                                        : std::nullopt;
        }
        if (moving == 0)
            continue;
        fmt::print("{} {}: its {} particles spent {:.1f}% of the run in the cone on average (the least {:.1f}%), "
                   "{}, mean height in the cone {:.3f} m\n",
                   g.kind == render::BodyGroup::Kind::Rope ? "rope" : "cloth", g.name, g.members.size(),
                   100.0 * mean / double(moving), 100.0 * least,
                   allCaught ? fmt::format("every one caught by {:.2f} s", *allCaught) : std::string("not every one caught"),
                   height / double(moving));
    }
}

/// In air with a density, what the jet lifts of each size of ball in the world: (1/2) rho C_d pi r^2 U^2 / g.
std::string ballLifts(const World& world, const BlowDryerField& field, double g)
{
    if (!(field.airDensity > 0.0 && field.airSpeed > 0.0 && g > 0.0))
        return {};
    std::vector<double> radii;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (const auto* p = dynamic_cast<const Particle*>(&world.body(i)); p && p->getRadius() > 0.0)
            radii.push_back(p->getRadius());
    std::sort(radii.begin(), radii.end());
    radii.erase(std::unique(radii.begin(), radii.end()), radii.end());
    std::string text;
    for (const double r : radii) {
        const double lift = 0.5 * field.airDensity * field.dragCoefficient * std::numbers::pi * r * r *
                            field.airSpeed * field.airSpeed / g;
        text += fmt::format("{} a ball of radius {:g} m up to {:.3g} kg", text.empty() ? " (a point);" : ",", r, lift);
    }
    return text.empty() ? text : text + fmt::format(" in its air ({:g} m/s, {:g} kg/m^3)", field.airSpeed, field.airDensity);
}

/// What the bodies did in the blow dryer's jet, and how many swarm particles are in its shaft.
void printJetSummary(const World& world, const study::JetWatch& jet, const render::BodyGroups& groups,
                     bool everyParticle)
{
    if (!jet.active())
        return;
    const double g = glm::length(world.gravity());
    fmt::print("blow dryer: {:g} N at the nozzle ({}), lifts up to {:.3g} kg{}; a catch is a stay of {:g} s in the "
               "cone\n",
               jet.field().strength, flowDirectionName(jet.field().direction),
               g > 0.0 ? jet.field().strength / g : INFINITY, ballLifts(world, jet.field(), g), study::kCatchStay);
    const auto bodies = jet.bodies();
    bool rows = false;
    for (std::size_t i = 0; i < bodies.size(); ++i)
        rows = rows || !(world.body(i).isFixed() || (groups.inFabric(i) && !everyParticle));
    if (rows)
        fmt::print("{:<22} {:>8} {:>10} {:>10} {:>12} {:>14} {:>14} {:>15}\n", "body", "mass", "in cone", "caught at",
                   "longest stay", "mean height", "mean off axis", "longest in hole");
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const study::BodyInJet& b = bodies[i];
        if (world.body(i).isFixed() || (groups.inFabric(i) && !everyParticle))
            continue;
        // A body never in the cone has no height there: a dash, not "nanm".
        const auto inCone = [](double m) { return std::isnan(m) ? std::string("-") : fmt::format("{:.3f}m", m); };
        fmt::print("{:<22} {:>6.3g}kg {:>9.1f}% {:>10} {:>11.2f}s {:>14} {:>14} {:>14.2f}s\n", b.name, b.mass,
                   100.0 * jet.fractionInCone(i), b.caughtAt ? fmt::format("{:.2f}s", *b.caughtAt) : std::string("never"),
                   b.longestStay, inCone(b.meanHeightInCone), inCone(b.meanOffAxisInCone), b.longestInShaft);
    }
    printFabricInJet(world, jet, groups);
    const auto inShaft = jet.swarmsInShaft(world);
    for (std::size_t s = 0; s < inShaft.size(); ++s) {
        const auto& figures = jet.swarms()[s];
        fmt::print("swarm {}: at most {} particles in the cone (t = {:.1f} s, counted every {:g} s); {} in "
                   "the dryer's shaft at the end; no particle stayed there longer than {:.3f} s at a stretch\n",
                   world.swarm(s).name(), figures.peakInCone, figures.peakAt, study::JetWatch::kSwarmSample,
                   inShaft[s], figures.longestInShaft);
    }
}

/// What the contacts and joints did over the run, as the engine saw them after each step.
void printPipelineSummary(const World& world, const study::PipelineFigures& p)
{
    std::size_t rigidBodies = 0;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        rigidBodies += world.isRigid(i) ? 1 : 0;
    std::vector<std::string> parts;
    if (rigidBodies >= 2)
        parts.push_back(p.deepestOverlap > 0.0 ? fmt::format("the deepest overlap of two bodies {:.3g} mm (t = {:.3f} s)",
                                                             1e3 * p.deepestOverlap, p.deepestAt)
                                               : std::string("no two bodies overlapped"));
    if (p.asleepFrom)
        parts.push_back(fmt::format("every moving body asleep from t = {:.3f} s", *p.asleepFrom));
    if (!parts.empty())
        fmt::print("  contacts: {}\n", fmt::join(parts, "; "));
    if (!p.widest)
        return;
    const JointFrame frame = world.jointFrame(*p.widest);
    const std::string joining = frame.bodyB ? fmt::format("'{}' to '{}'", world.body(frame.bodyA).getName(),
                                                          world.body(*frame.bodyB).getName())
                                            : fmt::format("'{}' to the world", world.body(frame.bodyA).getName());
    fmt::print("  joints: held to {:.2g} m at worst (joints[{}], joining {}, at t = {:.3f} s)\n", p.widestJoint,
               *p.widest, joining, p.widestAt);
}

/// A length in millimetres under 10 cm, else in metres.
std::string distanceText(double metres)
{
    return metres < 0.1 ? fmt::format("{:.2f} mm", 1e3 * metres) : fmt::format("{:.3f} m", metres);
}

/// What each rigid body did, as the watch measured it: the parts that apply to it.
void printRigidSummary(const World& world, const study::RigidWatch& rigid)
{
    if (!rigid.active())
        return;
    fmt::print("rigid bodies (still: |v| < {:g} m/s and |w| < {:g} rad/s; rolling: the contact slips slower than {:g} "
               "m/s):\n", study::kStill, study::kStill, study::kNoSlip);
    double nearest = INFINITY, farthest = 0.0;
    for (const study::RigidFigures& f : rigid.bodies(world)) {
        std::vector<std::string> parts;
        if (!f.stillFrom)
            parts.push_back("moving at the end");
        else if (f.restingFace.empty())
            parts.push_back(fmt::format("still from t = {:.3f} s", *f.stillFrom));
        else
            parts.push_back(fmt::format("still from t = {:.3f} s, its {} face down (tilted {:.2f} degrees)", *f.stillFrom,
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
        if (f.slide)
            parts.push_back(fmt::format("slides on {} without turning from t = {:.3f} to {:.3f} s, its speed changing "
                                        "at {:.3f} m/s^2", f.slide->on, f.slide->from, f.slide->to,
                                        f.slide->acceleration));
        if (f.largestTilt && *f.largestTilt >= 0.005) // (what reads 0.00 says nothing)
            parts.push_back(fmt::format("its start's up tilted by up to {:.2f} degrees{}", *f.largestTilt,
                                        f.tippedAt ? fmt::format(" (past 45 at t = {:.3f} s)", *f.tippedAt)
                                                   : std::string()));
        if (f.highs.size() >= 2)
            parts.push_back(fmt::format("at its highest every {:.4f} s on average ({} times)",
                                        (f.highs.back() - f.highs.front()) / double(f.highs.size() - 1), f.highs.size()));
        parts.push_back(fmt::format("spins at {:.3g} rad/s on average", f.meanSpin));
        parts.push_back(fmt::format("ends {} from its start", distanceText(f.fromStart)));
        fmt::print("  {}: {}\n", f.name, fmt::join(parts, "; "));
        nearest = std::min(nearest, f.fromStart);
        farthest = std::max(farthest, f.fromStart);
    }
    if (nearest < farthest)
        fmt::print("  moved: the bodies that are not fixed end {} to {} from where they started\n", distanceText(nearest),
                   distanceText(farthest));
    printPipelineSummary(world, rigid.pipeline());
}

/// A percentage to `figures` figures, but never with an exponent where it is large (150%, not
/// 1.5e+02%): from where rounding to those figures would need one, whole.
std::string percentText(double percent, int figures = 3)
{
    return percent >= std::pow(10.0, figures) - 0.5 ? fmt::format("{:.0f}", percent)
                                                    : fmt::format("{:.{}g}", percent, figures);
}

/// What the balls (particles with a radius) did, as the ball watch saw them at the start and
/// every tenth step.
void printBallSummary(const World& world, const study::BallFigures& f)
{
    if (f.balls == 0 || (f.balls == 1 && !world.hasRigidBodies()))
        return; // a lone ball in a room: nothing to say
    std::vector<std::string> parts;
    if (f.balls >= 2)
        parts.push_back(f.deepestPair > 0.0 ? fmt::format("two that collide overlapped by {}% of the smaller's "
                                                          "diameter at most (t = {:.2f} s)",
                                                          percentText(100.0 * f.deepestPair, 2),
                                                          f.deepestPairAt)
                                            : std::string("no two that collide overlapped"));
    if (world.hasRigidBodies())
        parts.push_back(f.deepestInBody > 0.0 ? fmt::format("one went {:.2f} mm into '{}' at most (t = {:.2f} s)",
                                                            1e3 * f.deepestInBody, f.deepestBody, f.deepestInBodyAt)
                                              : std::string("none went into a rigid body"));
    if (world.hasRigidBodies() && f.segments > 0)
        parts.push_back(f.deepestBetween > 0.0
                            ? fmt::format("a rope's or cloth's edge or cell between its balls went {:.2f} mm into "
                                          "'{}' at most (t = {:.2f} s)",
                                          1e3 * f.deepestBetween, f.deepestBetweenBody, f.deepestBetweenAt)
                            : std::string("no rope's or cloth's edge or cell between its balls went into a rigid body"));
    if (f.freeBalls >= 1 && f.segments > 0)
        parts.push_back(f.deepestFreeInEdge > 0.0
                            ? fmt::format("a free ball went {:.2f} mm into a rope's or cloth's edge or cell between "
                                          "its balls at most (t = {:.2f} s)",
                                          1e3 * f.deepestFreeInEdge, f.deepestFreeInEdgeAt)
                            : std::string("no free ball went into a rope's or cloth's edge or cell between its balls"));
    if (f.nets >= 2)
        parts.push_back(f.deepestNetBallInEdge > 0.0
                            ? fmt::format("a rope's or cloth's ball or edge went {:.2f} mm into another's edge or "
                                          "cell between its balls at most (t = {:.2f} s)",
                                          1e3 * f.deepestNetBallInEdge, f.deepestNetBallInEdgeAt)
                            : std::string("no rope's or cloth's ball or edge went into another's edge or cell "
                                          "between its balls"));
    if (f.freeBalls >= 2)
        parts.push_back(f.oneGroupFrom ? fmt::format("the {} free balls touch as one group (within {:g} mm, or {:g}% "
                                                     "of their radii if less) from t = {:.2f} s to the end", f.freeBalls,
                                                     1e3 * study::BallWatch::kTouch,
                                                     100.0 * study::BallWatch::kTouchShare, *f.oneGroupFrom)
                                       : fmt::format("the {} free balls are not one touching group at the end",
                                                     f.freeBalls));
    fmt::print("balls ({} particle{} with a radius, seen at the start and every {} steps): {}\n", f.balls,
               f.balls == 1 ? "" : "s", study::BallWatch::kEvery, fmt::join(parts, "; "));
}

/// Where each particle with a known exact motion is against it at the end.
void printExactSolutions(const World& world, const RunWatches& watches)
{
    for (const auto& [i, solution] : watches.exact) {
        const dvec3 exact = solution.position(world.time()), x = world.body(i).getPos();
        fmt::print("{}: the exact solution ({}) puts it at {} at t = {:.6g} s: {:.3g} m from it\n",
                   world.body(i).getName(),
                   solution.kind() == study::ExactSolution::Kind::Bounce
                       ? fmt::format("elastic bounces from {:g} m, every {:.4g} s", solution.height(), solution.period())
                       : fmt::format("an undamped oscillator of amplitude {:g} m and period {:.4g} s", solution.height(),
                                     solution.period()),
                   vectorText(exact), world.time(), glm::length(x - exact));
    }
}

/// E now / E start to six places, or, where those read 1.000000 and it is not 1, how far from
/// 1 it is ("1 - 4.6e-14"): a rounding-level drift is what exact integration claims. A dash where
/// the start's energy is zero: no ratio (a body at rest in zero g that something set moving read 1).
std::string energyRatioText(double now, double start)
{
    if (start == 0.0)
        return "-";
    const double ratio = now / start;
    const double off = ratio - 1.0;
    if (off != 0.0 && std::abs(off) < 5e-7)
        return fmt::format("1 {} {:.1e}", off > 0.0 ? '+' : '-', std::abs(off));
    return fmt::format("{:.6f}", ratio);
}

/// Whether the blow dryer pushed any of these bodies: it does work on a body in its cone, so
/// their energy is not kept (a ratio of 1.76 is the push, not an error).
bool dryerWorked(const study::JetWatch& jet, const std::vector<std::size_t>& bodies)
{
    return jet.active() && std::any_of(bodies.begin(), bodies.end(), [&](std::size_t i) { return jet.fractionInCone(i) > 0.0; });
}

constexpr const char* kDryerNote = "  (+ the dryer's work)";

/// A row per body that is no rope's or cloth's (every particle too, with everyParticle).
void printBodyRows(const World& world, const render::BodyGroups& groups, const std::vector<BodySummary>& summary,
                   const std::vector<double>& energies, const study::JetWatch& jet, bool everyParticle)
{
    std::vector<std::size_t> rows;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (everyParticle || !groups.inFabric(i))
            rows.push_back(i);
    if (rows.empty())
        return;
    fmt::print("{:<22} {:<20} {:>32} {:>11} {:>10} {:>8} {:>14}\n", "body", "integrator", "final position (m)",
               "speed (m/s)", "highest y", "bounces", "E now/E start");
    for (const std::size_t i : rows) {
        const Body& b = world.body(i);
        const dvec3& x = b.getPos();
        fmt::print("{:<22} {:<20} {:>32} {:>11.4g} {:>10} {:>8} {:>14}{}\n", b.getName(),
                   b.isFixed() ? std::string("(fixed)") : std::string(integratorName(b.getIntegrator())),
                   vectorText(x), glm::length(b.getVel()), coordinateText(summary[i].highest), world.bounceCount(i),
                   energyRatioText(energies[i], summary[i].startEnergy),
                   dryerWorked(jet, {i}) ? kDryerNote : "");
    }
}

/// A row per rope and cloth: its particles, integrator, centre of mass, momentum and the ratio
/// of its total energy, in place of a row per particle.
void printSystemRows(const World& world, const render::BodyGroups& groups, const std::vector<BodySummary>& summary,
                     const std::vector<double>& energies, const study::JetWatch& jet)
{
    bool header = false;
    for (const render::BodyGroup& g : groups.groups()) {
        if (!g.fabric())
            continue;
        if (!std::exchange(header, true))
            fmt::print("{:<22} {:>9} {:<20} {:>32} {:>32} {:>14}\n", "rope or cloth", "particles", "integrator",
                       "centre of mass (m)", "momentum (kg m/s)", "E now/E start");
        double mass = 0.0, start = 0.0;
        dvec3 centre(0.0);
        std::string integrator = "(fixed)";
        for (const std::size_t i : g.members) {
            const Body& b = world.body(i);
            mass += b.getMass();
            centre += b.getMass() * b.getPos();
            start += summary[i].startEnergy;
            if (!b.isFixed())
                integrator = std::string(integratorName(b.getIntegrator()));
        }
        const double energy = render::groupEnergy(g, energies);
        fmt::print("{:<22} {:>9} {:<20} {:>32} {:>32} {:>14}{}\n",
                   fmt::format("{} {}", g.kind == render::BodyGroup::Kind::Rope ? "rope" : "cloth", g.name),
                   g.members.size(), integrator, vectorText(centre / std::max(mass, 1e-300)),
                   vectorText(render::groupMomentum(world, g)), energyRatioText(energy, start),
                   dryerWorked(jet, g.members) ? kDryerNote : "");
    }
}

/// Where each rope's and cloth's particles are at the end, the fastest of them, and how many
/// bounced: a sheet lying in folds, a sheet come to rest, a rope's end striking the floor.
void printFabricEnds(const World& world, const render::BodyGroups& groups)
{
    for (const render::BodyGroup& g : groups.groups()) {
        if (!g.fabric() || g.members.empty())
            continue;
        double low = INFINITY, high = -INFINITY, fastest = 0.0;
        std::uint64_t most = 0;
        std::size_t bounced = 0;
        for (const std::size_t i : g.members) {
            low = std::min(low, world.body(i).getPos().y);
            high = std::max(high, world.body(i).getPos().y);
            fastest = std::max(fastest, glm::length(world.body(i).getVel()));
            most = std::max(most, world.bounceCount(i));
            bounced += world.bounceCount(i) > 0 ? 1 : 0;
        }
        fmt::print("{} {} at the end: its particles {:.3f} to {:.3f} m high, the fastest at {:.3g} m/s; {}\n",
                   g.kind == render::BodyGroup::Kind::Rope ? "rope" : "cloth", g.name, low, high, fastest,
                   bounced == 0 ? std::string("none bounced")
                                : fmt::format("{} of its {} particles bounced, {}", bounced, g.members.size(),
                                              most == 1 ? std::string("once each") : fmt::format("up to {} times", most)));
    }
}

/// What may take a scene's energy, for its balance: bounces, contacts, its drag and damped springs
/// (forces or joints) where it has them, and the integration.
std::string whatTakesEnergy(const World& world)
{
    const study::ForceKinds kinds = study::forceKinds(world);
    bool dampedJoints = false;
    for (std::size_t j = 0; j < world.jointCount(); ++j)
        dampedJoints = dampedJoints || world.jointFrame(j).damping > 0.0;
    std::string text = "bounces, contacts";
    if (kinds.drag)
        text += ", drag";
    if (kinds.dampedSprings || dampedJoints)
        text += ", the springs' damping";
    return text + " and the integration";
}

/// The energy the dryer's work leaves unexplained, as a balance in joules: E start + W - E now is
/// what bounces, contacts and the integration took (or gave). A ratio (E now - W) / E start read
/// as an energy ratio, and went negative where the dryer's work outgrew the start's energy.
void printDryerBalance(const World& world, double start, double work, double now)
{
    const double lost = start + work - now;
    const std::string share =
        start > 0.0 ? fmt::format(", {}% of the start's energy", percentText(100.0 * std::abs(lost) / start)) : std::string();
    fmt::print("(+ the dryer's work): the blow dryer did {:.6g} J of work on the bodies in its cone (its force as "
               "each body's integrator applies it, against each step's mean velocity), so their energy is not kept; "
               "the balance: {:.6g} J at the start {} {:.6g} J of work - {:.6g} J now = {:.3g} J {} by {}{}\n",
               work, start, work < 0.0 ? '-' : '+', std::abs(work), now, std::abs(lost), lost >= 0.0 ? "taken" : "given",
               // Drag and damping only take: what gave energy is among the others.
               lost >= 0.0 ? whatTakesEnergy(world) : std::string("bounces, contacts and the integration"), share);
}

/// The whole scene's energy and momentum, now and at the start (swarms not included), of its
/// moving bodies where some are fixed (movingEnergy). Returns the start's energy.
double printSceneTotals(const World& world, const render::BodyGroups& groups, const std::vector<BodySummary>& summary,
                        const std::vector<double>& energies, const study::JetWatch& jet, double sourceWork)
{
    std::vector<double> startEnergies(world.bodyCount());
    dvec3 momentum(0.0), startMomentum(0.0);
    std::vector<std::size_t> all;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        startEnergies[i] = summary[i].startEnergy;
        if (!world.body(i).isFixed())
            momentum += world.body(i).getMass() * world.body(i).getVel();
        startMomentum += summary[i].startMomentum;
        all.push_back(i);
    }
    const double energy = render::movingEnergy(world, groups, energies);
    const double start = render::movingEnergy(world, groups, startEnergies);
    fmt::print("{}: energy {:.6g} J, {:.6g} J at the start: E now/E start {}{}; momentum {} kg m/s, {} at "
               "the start\n", render::anyGroupFixed(world, groups) ? "all moving bodies" : "all bodies", energy, start,
               energyRatioText(energy, start), dryerWorked(jet, all) ? kDryerNote : "",
               vectorText(momentum), vectorText(startMomentum));
    if (dryerWorked(jet, all))
        printDryerBalance(world, start, sourceWork, energy);
    return start;
}

/// The largest rise of the energy (less a dryer's work) from one step to the next: what a
/// description's "its energy never grows" claims.
void printLargestStepRise(const World& world, const BlowUpWatch& watch, double startEnergy)
{
    if (world.bodyCount() == 0 || !watch.watchesGrowth())
        return;
    // A rise of a trillionth of the energy's scale is the sum's rounding, not the step's.
    const std::string less = watch.hasSources() ? " less the dryer's work" : ""; // a scene's one source
    const double rise = watch.largestStepRise(), rounding = 1e-12 * watch.energyScale();
    if (rise > rounding)
        fmt::print("the energy{} rose by at most {:.2g} J in one step (t = {:.3f} s){}\n", less, rise,
                   watch.largestStepRiseAt(), startEnergy > 0.0 ? fmt::format(", {}% of the start's energy",
                                                                             percentText(100.0 * rise / startEnergy, 2))
                                                                : std::string());
    else if (rise > 0.0)
        fmt::print("the energy{} never rose from one step to the next by more than rounding ({:.2g} J at most, "
                   "of energy terms adding up to {:.3g} J)\n", less, rise, watch.energyScale());
    else
        fmt::print("the energy{} never rose from one step to the next\n", less);
}

} // namespace

RunWatches::RunWatches(const Scene& scene)
    : groups(scene.world, scene.fabric), blowUp(scene.world), jet(scene.world), rigid(scene.world),
      balls(scene.world, fabricMembers(groups, scene.world.bodyCount()), scene.fabric.edges())
{
    for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
        if (!scene.world.isRigid(i) && !scene.world.body(i).isFixed())
            if (auto solution = study::ExactSolution::find(scene.world, i))
                exact.emplace_back(i, *solution);
}

void RunWatches::record(const World& world)
{
    blowUp.check(world);
    jet.record(world);
    rigid.record(world);
    balls.record(world);
}

void printSummary(const Scene& scene, const World& world, const std::vector<BodySummary>& summary,
                  const RunWatches& watches, bool everyParticle)
{
    const study::JetWatch& jet = watches.jet;
    const BlowUpWatch& watch = watches.blowUp;
    const double sourceWork = watch.sourceWork();
    // A run takes round(duration / dt) steps, at least one: where that is not the duration, the
    // line says so rather than let t = 20 s on a 10 s scene look like a bug.
    const bool rounded = std::abs(world.time() - scene.duration) > 1e-9 * scene.duration;
    fmt::print("scene {}: {} step{} of dt = {:.6g} s, t = {:.6g} s{}, collision response {}{}\n", scene.name,
               world.stepCount(), world.stepCount() == 1 ? "" : "s", scene.dt, world.time(),
               rounded ? fmt::format(" (the duration, {:.6g} s, is {:.6g} steps: a run takes the nearest whole number, "
                                     "at least one)", scene.duration, scene.duration / scene.dt)
                       : "",
               collisionResponseName(world.collisionResponse()),
               reflectsCoupledBodies(world) ? " (reflect for bodies joined by springs)" : "");
    if (world.bodyCount() == 0) {
        printSwarmSummary(world);
        printJetSummary(world, jet, watches.groups, everyParticle);
        return;
    }
    const render::BodyGroups& groups = watches.groups;
    const std::vector<double> energies = world.energies();
    printBodyRows(world, groups, summary, energies, jet, everyParticle);
    printSystemRows(world, groups, summary, energies, jet);
    printFabricEnds(world, groups);
    const double startEnergy = printSceneTotals(world, groups, summary, energies, jet, sourceWork);
    printLargestStepRise(world, watch, startEnergy);
    printExactSolutions(world, watches);
    printRigidSummary(world, watches.rigid);
    printBallSummary(world, watches.balls.figures());
    printSwarmSummary(world);
    printJetSummary(world, jet, groups, everyParticle);
}


} // namespace pba::app
