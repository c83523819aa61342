#include "force_parsers.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "one_line.hpp"
#include "pba/blow_dryer.hpp"
#include "pba/forces.hpp"

namespace pba::scene_detail {

namespace {

std::size_t readParticle(ObjectReader& reader, const std::string& key, const std::string& name, const World& world)
{
    const auto index = world.findBody(name);
    if (!index)
        reader.fail(key, fmt::format("no particle or rigid body named '{}'", oneLine(name)));
    return *index;
}

/// `"particles": ["a", "b"]`: a spring between two particles, which then move as one coupled
/// group and so must share one integrator (unless one of them is fixed).
std::unique_ptr<Force> parseTwoBodySpring(ObjectReader& reader, World& world)
{
    if (reader.has("particle"))
        reader.fail("particle", "give either \"particle\" (with an anchor) or \"particles\" (two of them), not both");
    if (reader.has("anchor"))
        reader.fail("anchor", "a spring between two particles has no anchor");
    if (reader.has("attachment"))
        reader.fail("attachment", "a spring between two particles ties their centres (an attachment is a rigid body's)");
    std::vector<std::string> names;
    const Json& value = reader.raw("particles");
    if (value.is_array())
        for (const Json& item : value)
            if (item.is_string())
                names.push_back(item.get<std::string>());
    if (!value.is_array() || value.size() != 2 || names.size() != 2)
        reader.fail("particles", "expected an array of two particle names");
    const std::size_t a = readParticle(reader, "particles", names[0], world);
    const std::size_t b = readParticle(reader, "particles", names[1], world);
    if (a == b)
        reader.fail("particles", fmt::format("joins '{}' to itself: name two different particles", oneLine(names[0])));
    for (const auto& [index, name] : {std::pair{a, names[0]}, std::pair{b, names[1]}})
        if (world.isRigid(index))
            reader.fail("particles", fmt::format("'{}' is a rigid body: a spring between two bodies joins particles "
                                                 "(tie a rigid body to an anchor with \"particle\" and \"attachment\")",
                                                 oneLine(name)));
    const Body& first = world.body(a);
    const Body& second = world.body(b);
    if (!first.isFixed() && !second.isFixed() && first.getIntegrator() != second.getIntegrator())
        reader.fail("particles", fmt::format("the spring joins '{}' ({}) and '{}' ({}): particles joined by springs "
                                             "move as one system and must share one integrator",
                                             oneLine(names[0]), integratorName(first.getIntegrator()),
                                             oneLine(names[1]), integratorName(second.getIntegrator())));
    const double stiffness = reader.positive("stiffness");
    const double restLength = reader.nonNegative("rest_length", 0.0);
    const double damping = reader.nonNegative("damping", 0.0);
    return std::make_unique<TwoBodySpring>(a, b, stiffness, restLength, damping);
}

std::unique_ptr<Force> parseSpring(ObjectReader& reader, World& world)
{
    if (reader.has("particles"))
        return parseTwoBodySpring(reader, world);
    const std::size_t index = readParticle(reader, "particle", reader.string("particle"), world);
    const dvec3 anchor = reader.vec3("anchor");
    const double stiffness = reader.positive("stiffness");
    const double restLength = reader.nonNegative("rest_length", 0.0);
    const double damping = reader.nonNegative("damping", 0.0);
    const dvec3 attachment = reader.vec3("attachment", dvec3(0.0));
    if (attachment != dvec3(0.0) && !world.isRigid(index))
        reader.fail("attachment", fmt::format("'{}' is a particle, a point: only a rigid body has points to tie a "
                                              "spring to", oneLine(reader.string("particle"))));
    return std::make_unique<Spring>(index, anchor, stiffness, restLength, damping, attachment);
}

std::unique_ptr<Force> parseDrag(ObjectReader& reader, World&)
{
    return std::make_unique<Drag>(reader.nonNegative("coefficient"), reader.nonNegative("angular_coefficient", 0.0));
}

template <class Enum>
Enum readChoice(ObjectReader& reader, const std::string& key, Enum fallback, std::optional<Enum> (*fromName)(std::string_view),
                const char* expected)
{
    if (!reader.has(key))
        return fallback;
    const std::string name = reader.string(key);
    const auto value = fromName(name);
    if (!value)
        reader.fail(key, fmt::format("unknown value '{}' (expected {})", oneLine(name), expected));
    return *value;
}

BlowDryerField readBlowDryerField(ObjectReader& reader)
{
    BlowDryerField f;
    f.nozzle = reader.vec3("nozzle");
    f.axis = unitOrZero(reader.vec3("axis", dvec3(0, 1, 0)));
    if (f.axis == dvec3(0.0))
        reader.fail("axis", "must not be the zero vector");
    f.height = reader.positive("height");
    f.nozzleRadius = reader.nonNegative("nozzle_radius", 0.0);
    f.topRadius = reader.nonNegative("top_radius");
    if (f.topRadius <= 0.0)
        reader.fail("top_radius", "must be positive");
    if (f.axis.y > 0.0 && f.topRadius < f.nozzleRadius)
        reader.fail("top_radius", fmt::format("must not be smaller than nozzle_radius ({}) when the axis points up",
                                              f.nozzleRadius));
    f.strength = reader.number("strength");
    f.axialFalloff = readChoice(reader, "axial_falloff", Falloff::Linear, &falloffFromName, "linear, quadratic or smooth");
    f.radialFalloff = readChoice(reader, "radial_falloff", Falloff::Linear, &falloffFromName, "linear, quadratic or smooth");
    f.direction = readChoice(reader, "direction", FlowDirection::Vertical, &flowDirectionFromName, "vertical or cone-flow");
    f.airSpeed = reader.nonNegative("air_speed", 0.0);
    f.axisPull = reader.nonNegative("axis_pull", 0.0);
    if (f.axisPull > 0.0 && f.airSpeed == 0.0)
        reader.fail("axis_pull", "needs air_speed: the pull comes from the air's speed");
    if (f.airSpeed > 0.0 && f.strength <= 0.0)
        reader.fail("air_speed", "needs a positive strength (the drag coefficient is strength / air_speed)");
    f.airDensity = reader.nonNegative("air_density", 0.0);
    if (f.airDensity > 0.0 && f.airSpeed == 0.0)
        reader.fail("air_density", "needs air_speed: a ball feels the air's density through its speed");
    f.dragCoefficient = reader.positive("drag_coefficient", f.dragCoefficient);
    return f;
}

/// A dryer whose nozzle sits on the floor blows up through a hole of the nozzle's radius,
/// with its grille `grille_depth` below the floor, and pushes in that hole's shaft.
void cutHoleForNozzle(ObjectReader& reader, BlowDryerField& f, World& world)
{
    const double depth = reader.positive("grille_depth", 0.05);
    const std::optional<double> floor = world.room() ? std::optional<double>(world.room()->min.y) : world.ground();
    if (!floor || f.nozzleRadius <= 0.0 || std::abs(f.nozzle.y - *floor) > 1e-9 || f.axis.y <= 0.0)
        return;
    if (world.floorHole())
        reader.fail("nozzle", "only one blow dryer may sit in the floor");
    world.setFloorHole(FloorHole{f.nozzle, f.nozzleRadius, depth});
    f.shaft = true;
}

std::unique_ptr<Force> parseBlowDryer(ObjectReader& reader, World& world)
{
    BlowDryerField field = readBlowDryerField(reader);
    // The field must be computable: on the axis a quarter and halfway up, a finite force, and
    // not zero unless the strength is (a height or radius so large that its square overflows
    // gives none; a strength near the largest double gives infinities and NaN).
    for (const double s : {0.25, 0.5}) {
        const dvec3 force = blowDryerForce(field, field.nozzle + s * field.height * field.axis);
        if (!(std::isfinite(force.x) && std::isfinite(force.y) && std::isfinite(force.z)) ||
            (field.strength != 0.0 && glm::length(force) == 0.0))
            reader.fail("strength", fmt::format("the field cannot be computed with these numbers (strength {}, height "
                                                "{}, radii {} and {}): its force on the axis is ({}, {}, {})",
                                                field.strength, field.height, field.nozzleRadius, field.topRadius,
                                                force.x, force.y, force.z));
    }
    cutHoleForNozzle(reader, field, world);
    return std::make_unique<BlowDryer>(field);
}

} // namespace

const std::vector<ForceType>& forceTypes()
{
    static const std::vector<ForceType> types{
        {"spring", &parseSpring, {"particle", "particles", "anchor", "stiffness", "rest_length", "damping", "attachment"}},
        {"drag", &parseDrag, {"coefficient", "angular_coefficient"}},
        {"blow-dryer", &parseBlowDryer,
         {"nozzle", "axis", "height", "nozzle_radius", "top_radius", "strength", "axial_falloff", "radial_falloff",
          "direction", "air_speed", "axis_pull", "air_density", "drag_coefficient", "grille_depth"}},
    };
    return types;
}

} // namespace pba::scene_detail
