#include "swarm_reader.hpp"

#include <cmath>

#include <fmt/format.h>

#include "fabric_readers.hpp"
#include "one_line.hpp"
#include "pba/detail/swarm_kernel.hpp"
#include "pba/swarm.hpp"
#include "pba/scene/scene.hpp"

namespace pba::scene_detail {

namespace {

std::uint64_t readCount(ObjectReader& reader, const std::string& key, double limit)
{
    const double x = reader.number(key);
    // A whole number written in full is compared exactly: 2^53 + 1 rounds to 2^53 as a double.
    const Json& raw = reader.raw(key);
    const bool past = raw.is_number_unsigned() && raw.get<std::uint64_t>() > static_cast<std::uint64_t>(limit);
    if (past || !(x >= 0 && x <= limit && std::floor(x) == x))
        reader.fail(key, fmt::format("must be a whole number from 0 to {:.0f}, got {}", limit,
                                     raw.is_number_integer() ? raw.dump() : fmt::format("{}", x)));
    return static_cast<std::uint64_t>(x);
}

void requireFloat(const ObjectReader& reader, const std::string& key, const dvec3& v)
{
    for (int i = 0; i < 3; ++i)
        if (!fitsFloat(v[i]))
            reader.fail(key, fmt::format("{} cannot be represented in single precision, as a swarm's numbers are "
                                         "(at most {:.3g} in size)", v[i], kFloatMax));
}

} // namespace

bool fitsFloat(double x) { return std::abs(x) <= kFloatMax; }

void readSwarm(const Json& value, const std::string& path, const std::string& file, World& world,
               std::set<std::string>& names)
{
    ObjectReader reader(value, path, file);
    reader.expectKeys({"name", "count", "region", "velocity", "velocity_jitter", "mass", "restitution", "radius",
                       "friction", "collide", "integrator", "seed"});
    SwarmDesc desc;
    desc.name = readName(reader, "name");
    if (desc.name.empty() || !names.insert(desc.name).second)
        reader.fail("name", desc.name.empty() ? "must not be empty"
                                              : fmt::format("'{}' is already taken", oneLine(desc.name)));
    // Its particles' rows are NAME[i], like a rope's particles; it comes after every other body.
    if (const auto taken = names.lower_bound(desc.name + "["); taken != names.end() && taken->starts_with(desc.name + "["))
        reader.fail("name", fmt::format("its particles' rows would be named {0}[0], {0}[1], ..., and '{1}' is already a "
                                        "body's name", oneLine(desc.name), oneLine(*taken)));
    desc.count = readCount(reader, "count", 1e8);
    ObjectReader region = reader.object("region");
    region.expectKeys({"min", "max"});
    desc.regionMin = region.vec3("min");
    desc.regionMax = region.vec3("max");
    for (int i = 0; i < 3; ++i)
        if (desc.regionMin[i] > desc.regionMax[i])
            region.fail("min", fmt::format("must not be above max (axis {})", "xyz"[i]));
    region.finish();
    if (!insideSurfaces(world, desc.regionMin) || !insideSurfaces(world, desc.regionMax))
        reader.fail("region", fmt::format("its corner {}", outsideText(world, insideSurfaces(world, desc.regionMin)
                                                                             ? desc.regionMax : desc.regionMin)));
    desc.velocity = reader.vec3("velocity", dvec3(0.0));
    desc.velocityJitter = reader.nonNegative("velocity_jitter", 0.0);
    requireFloat(region, "min", desc.regionMin);
    requireFloat(region, "max", desc.regionMax);
    requireFloat(reader, "velocity", desc.velocity + dvec3(desc.velocityJitter) * glm::sign(desc.velocity));
    requireFloat(reader, "velocity_jitter", dvec3(desc.velocityJitter));
    desc.mass = reader.positive("mass", 1.0);
    if (!(desc.mass >= kFloatMin && desc.mass <= kFloatMax))
        reader.fail("mass", fmt::format("{} cannot be represented in single precision with its inverse, as a "
                                        "swarm's numbers are (from {:.3g} to {:.3g} kg)",
                                        desc.mass, kFloatMin, kFloatMax));
    desc.restitution = reader.number("restitution", 1.0);
    if (!(desc.restitution >= 0.0 && desc.restitution <= 1.0))
        reader.fail("restitution", fmt::format("must be in [0, 1], got {}", desc.restitution));
    const ContactKeys contact = readContactKeys(reader);
    desc.radius = contact.radius;
    desc.friction = contact.friction;
    // In single precision a radius below the smallest normal float is none, and would get past
    // "collide"'s need of one.
    if (desc.radius != 0.0 && !(desc.radius >= kFloatMin && desc.radius <= kFloatMax))
        reader.fail("radius", fmt::format("{} cannot be represented in single precision, as a swarm's numbers are "
                                          "(0, or from {:.3g} to {:.3g} m)", desc.radius, kFloatMin, kFloatMax));
    requireFloat(reader, "friction", dvec3(desc.friction));
    if (!insideSurfaces(world, desc.regionMin, desc.radius) || !insideSurfaces(world, desc.regionMax, desc.radius))
        reader.fail("radius", fmt::format("its region's corner: {}",
                                          ballOutsideText(world, insideSurfaces(world, desc.regionMin, desc.radius)
                                                                     ? desc.regionMax : desc.regionMin,
                                                          desc.radius)));
    desc.collide = reader.boolean("collide", false);
    if (desc.collide && desc.radius == 0.0)
        reader.fail("collide", "its particles need a \"radius\" to collide: points never touch");
    if (desc.collide && desc.count > 1 && desc.regionMin == desc.regionMax)
        reader.fail("region", "its colliding grains would all start at one point, with no direction to part along: "
                              "give the region a size");
    desc.integrator = readIntegrator(reader, "integrator", Integrator::SemiImplicitEuler);
    if (isSpringSystemMethod(desc.integrator))
        reader.fail("integrator", fmt::format("{} steps particles joined by springs; a swarm has none: take "
                                              "forward-euler, semi-implicit-euler, velocity-verlet or rk4",
                                              integratorName(desc.integrator)));
    desc.seed = readCount(reader, "seed", 9007199254740992.0);
    reader.finish();
    world.addSwarm(desc);
}

bool swarmFieldsFit(const World& world)
{
    const SwarmFields fields = world.swarmFields();
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const SwarmKernelFields k(fields, 1.0f / world.swarm(s).mass(), world.swarm(s).radius());
        auto finite = [](float x) { return std::isfinite(x); };
        bool ok = finite(k.gravity.x) && finite(k.gravity.y) && finite(k.gravity.z) && finite(k.dragPerMass);
        std::vector<BlowDryerKernelT<float>> dryers{k.dryer};
        dryers.insert(dryers.end(), k.more.begin(), k.more.end());
        for (const auto& d : dryers)
            ok = ok && finite(d.axial.a) && finite(d.axial.b) && finite(d.axial.c) && finite(d.shaftPush) &&
                 finite(d.airDrag) && finite(d.pull) && finite(d.airPerPush) && finite(d.dragPerArea) &&
                 finite(d.pullPerVolume) && finite(d.inverseHeight) && finite(d.height * d.height) &&
                 finite(d.nozzle.x) && finite(d.nozzle.y) && finite(d.nozzle.z) && finite(d.shaftRadius2);
        if (!ok)
            return false;
    }
    return true;
}

} // namespace pba::scene_detail
