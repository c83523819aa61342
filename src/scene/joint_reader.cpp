#include "joint_reader.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "one_line.hpp"

namespace pba::scene_detail {

namespace {

/// How far a rigid rod's anchors may start from its length: a millimetre's jerk is not seen.
constexpr double kRodLengthTolerance = 1e-3;
/// How far an anchor may be from the body it joins, and a spring's length (m): a joint a thousand
/// kilometres off holds nothing a scene can show, and at 1e300 its arms overflowed.
constexpr double kMaxAnchorReach = 1e6;
/// The stiffest spring (N/m): the implicit spring holds to 1e20; stiffer is a rigid rod.
constexpr double kMaxStiffness = 1e15;
/// How far a ball joint's anchor may be from a particle it joins (m): a particle does not turn,
/// so an anchor beside it would hold it at a fixed offset in the world's frame from the body's
/// point, which no joint does.
constexpr double kParticleAnchorTolerance = 1e-3;

/// Refuses `anchor` (the key `key`) too far from body `index`, or, with `atParticle`, not at it
/// when it is a particle.
void checkAnchor(const ObjectReader& reader, const World& world, const std::string& key, const dvec3& anchor,
                 std::size_t index, bool atParticle = false)
{
    const Body& body = world.body(index);
    const dvec3 d = anchor - body.getPos();
    const double scale = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}); // 1e300 squared overflows
    const double apart = scale > 0.0 ? scale * glm::length(d / scale) : 0.0;
    if (atParticle && !world.isRigid(index) && !(apart <= kParticleAnchorTolerance))
        reader.fail(key, fmt::format("must be at the particle '{}', ({:g}, {:g}, {:g}), not {:.3g} m from it: a "
                                     "particle does not turn, so it is joined at its centre",
                                     oneLine(body.getName()), body.getPos().x, body.getPos().y, body.getPos().z,
                                     apart));
    if (!(apart <= kMaxAnchorReach))
        reader.fail(key, fmt::format("is {:.3g} m from '{}': an anchor must be within {:g} m of the body it joins",
                                     apart, oneLine(body.getName()), kMaxAnchorReach));
}

JointType readType(ObjectReader& reader)
{
    const std::string name = reader.string("type");
    if (const auto type = jointTypeFromName(name))
        return *type;
    const std::vector<std::string> names{"ball", "hinge", "distance", "fixed"};
    const auto close = closestName(name, names);
    reader.fail("type", fmt::format("unknown joint type '{}'{} (expected ball, hinge, distance or fixed)",
                                    oneLine(name), close ? fmt::format(": did you mean '{}'?", *close) : ""));
}

/// The body a joint names, by its name: a rigid body, or a particle (a rope's or cloth's by the
/// name its CSV columns have, `rope[19]`), which World::addJoint then checks.
std::size_t bodyNamed(const ObjectReader& reader, const World& world, const Json& entry, std::size_t k)
{
    const std::string key = fmt::format("bodies[{}]", k);
    if (!entry.is_string())
        reader.fail(key, "must be a body's name (a string)");
    const std::string name = entry.get<std::string>();
    const auto index = world.findBody(name);
    if (!index) {
        std::vector<std::string> names;
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            names.push_back(world.body(i).getName());
        const auto close = closestName(name, names);
        reader.fail(key, fmt::format("no body is named '{}'{}", oneLine(name),
                                     close ? fmt::format(": did you mean '{}'?", *close) : ""));
    }
    return *index;
}

std::array<dvec3, 2> readAnchors(ObjectReader& reader)
{
    const Json& value = reader.raw("anchors");
    if (!value.is_array() || value.size() != 2)
        reader.fail("anchors", "must be two points [[x, y, z], [x, y, z]]: on the first body and on the second "
                               "(or the world)");
    std::array<dvec3, 2> anchors;
    for (std::size_t k = 0; k < 2; ++k) {
        const Json& p = value[k];
        if (!p.is_array() || p.size() != 3 || !std::all_of(p.begin(), p.end(), [](const Json& x) {
                return x.is_number() && std::isfinite(x.get<double>());
            }))
            reader.fail(fmt::format("anchors[{}]", k), "must be a point [x, y, z] of three finite numbers");
        anchors[k] = dvec3(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    }
    return anchors;
}

/// A joint whose ends are both fixed (or a fixed body and the world) holds nothing: said, not
/// ignored.
void failIfNothingMoves(const ObjectReader& reader, const World& world, const JointDesc& joint)
{
    const Body& a = world.body(joint.bodyA);
    if (!a.isFixed())
        return;
    if (!joint.bodyB)
        reader.fail("bodies", fmt::format("joins '{}' to the world, and it is fixed: the joint would hold nothing",
                                          oneLine(a.getName())));
    const Body& b = world.body(*joint.bodyB);
    if (b.isFixed())
        reader.fail("bodies", fmt::format("joins '{}' and '{}', and both are fixed: the joint would hold nothing",
                                          oneLine(a.getName()), oneLine(b.getName())));
}

/// A rigid rod whose length is not its anchors' distance would jerk its bodies into place in the
/// first step, adding the energy of the jump (a ball 0.8 m up: 1.8 times the scene's).
void failIfRodIsNotAtItsLength(const ObjectReader& reader, const JointDesc& joint)
{
    const double apart = glm::length(joint.anchors[1] - joint.anchors[0]);
    if (std::abs(apart - *joint.length) > kRodLengthTolerance)
        reader.fail("length", fmt::format("a rigid rod starts at its length, and its anchors are {:.6g} m apart, not "
                                          "{:.6g} (give a stiffness for a spring that pulls them there, or move the "
                                          "anchors)",
                                          apart, *joint.length));
}

std::array<double, 2> readLimits(ObjectReader& reader)
{
    const Json& value = reader.raw("limits");
    if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number())
        reader.fail("limits", "must be [lower, upper], two angles in radians");
    double lower = value[0].get<double>(), upper = value[1].get<double>();
    // pi written to ten digits, 3.1415926536, is past pi by 7e-12: it is pi.
    constexpr double kPiRounding = 1e-9;
    if (std::abs(lower + std::numbers::pi) <= kPiRounding)
        lower = -std::numbers::pi;
    if (std::abs(upper - std::numbers::pi) <= kPiRounding)
        upper = std::numbers::pi;
    if (!(std::isfinite(lower) && std::isfinite(upper) && lower <= 0.0 && 0.0 <= upper))
        reader.fail("limits", fmt::format("must hold the start's angle, 0 (lower <= 0 <= upper), got [{}, {}]",
                                          lower, upper));
    if (!(lower >= -std::numbers::pi && upper <= std::numbers::pi))
        reader.fail("limits", fmt::format("must be within [-pi, pi], [-{1}, {1}], got [{0}, {2}]", lower,
                                          std::numbers::pi, upper));
    return {lower, upper};
}

/// `bodies`: one body, joined to the world, or two different ones.
void readBodies(ObjectReader& reader, const World& world, JointDesc& joint)
{
    const Json& bodies = reader.raw("bodies");
    if (!bodies.is_array() || bodies.empty() || bodies.size() > 2)
        reader.fail("bodies", "must name one rigid body (joined to the world) or two (a rigid body and a rigid "
                              "body or particle): [\"a\"] or [\"a\", \"b\"]");
    joint.bodyA = bodyNamed(reader, world, bodies[0], 0);
    if (bodies.size() == 2) {
        joint.bodyB = bodyNamed(reader, world, bodies[1], 1);
        if (*joint.bodyB == joint.bodyA)
            reader.fail("bodies", "names the same body twice");
    }
}

/// A distance joint's anchors, and its length, stiffness and damping.
void readRod(ObjectReader& reader, const World& world, JointDesc& joint)
{
    joint.anchors = readAnchors(reader);
    checkAnchor(reader, world, "anchors[0]", joint.anchors[0], joint.bodyA);
    checkAnchor(reader, world, "anchors[1]", joint.anchors[1], joint.bodyB.value_or(joint.bodyA));
    if (reader.has("length")) {
        joint.length = reader.nonNegative("length");
        if (*joint.length > kMaxAnchorReach)
            reader.fail("length", fmt::format("must be at most {:g} m, got {:g}", kMaxAnchorReach, *joint.length));
    }
    if (reader.has("stiffness")) {
        joint.stiffness = reader.positive("stiffness");
        if (*joint.stiffness > kMaxStiffness)
            reader.fail("stiffness", fmt::format("must be at most {:g} N/m (stiffer, leave the stiffness out: "
                                                 "a rigid rod), got {:g}", kMaxStiffness, *joint.stiffness));
    }
    if (joint.length && !joint.stiffness)
        failIfRodIsNotAtItsLength(reader, joint);
    if (reader.has("damping") && !joint.stiffness)
        reader.fail("damping", "belongs to a spring: give a stiffness too (without one the rod is rigid)");
    joint.damping = reader.nonNegative("damping", 0.0);
    if (joint.damping > kMaxStiffness)
        reader.fail("damping", fmt::format("must be at most {:g} N s/m, got {:g}", kMaxStiffness, joint.damping));
}

/// A ball, hinge or fixed joint's one anchor (a weld's defaults to its first body's centre).
void readAnchor(ObjectReader& reader, const World& world, JointDesc& joint)
{
    joint.anchor = joint.type == JointType::Fixed ? reader.vec3("anchor", world.body(joint.bodyA).getPos())
                                                  : reader.vec3("anchor");
    // A ball joint of a particle and a rigid body (the only one a particle may have) holds the
    // particle at its centre.
    const bool ballAcross = joint.type == JointType::Ball && joint.bodyB &&
                            world.isRigid(joint.bodyA) != world.isRigid(*joint.bodyB);
    checkAnchor(reader, world, "anchor", joint.anchor, joint.bodyA, ballAcross);
    if (joint.bodyB)
        checkAnchor(reader, world, "anchor", joint.anchor, *joint.bodyB, ballAcross);
}

} // namespace

JointDesc readJoint(const Json& value, const std::string& path, const std::string& file, World& world)
{
    ObjectReader reader(value, path, file);
    reader.expectKeys(
        {"type", "bodies", "anchor", "anchors", "axis", "limits", "length", "stiffness", "damping", "collide"});
    JointDesc joint;
    joint.type = readType(reader);
    readBodies(reader, world, joint);
    failIfNothingMoves(reader, world, joint);
    auto onlyFor = [&](const char* key, bool allowed, const char* types) {
        if (reader.has(key) && !allowed)
            reader.fail(key, fmt::format("belongs to {} joints only", types));
    };
    const bool distance = joint.type == JointType::Distance, hinge = joint.type == JointType::Hinge;
    onlyFor("anchors", distance, "distance");
    onlyFor("length", distance, "distance");
    onlyFor("stiffness", distance, "distance");
    onlyFor("damping", distance, "distance");
    onlyFor("anchor", !distance, "ball, hinge and fixed");
    onlyFor("axis", hinge, "hinge");
    onlyFor("limits", hinge, "hinge");
    if (distance)
        readRod(reader, world, joint);
    else
        readAnchor(reader, world, joint);
    if (hinge) {
        joint.axis = unitOrZero(reader.vec3("axis"));
        if (joint.axis == dvec3(0.0))
            reader.fail("axis", "must not be zero");
        if (reader.has("limits"))
            joint.limits = readLimits(reader);
    }
    if (reader.has("collide") && !joint.bodyB)
        reader.fail("collide", "belongs to a joint of two bodies (one joined to the world still collides with "
                               "everything)");
    joint.collide = reader.boolean("collide", false);
    reader.finish();
    try {
        world.addJoint(joint);
    } catch (const std::invalid_argument& e) {
        reader.failHere(e.what());
    }
    return joint;
}

} // namespace pba::scene_detail
