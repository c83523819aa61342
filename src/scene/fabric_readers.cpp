#include "fabric_readers.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "one_line.hpp"
#include "pba/spring_network.hpp"

namespace pba::scene_detail {

namespace {

/// What every particle of one rope or cloth shares.
struct FabricParticles {
    std::string name;
    double mass = 1.0; ///< each particle's
    double restitution = 1.0;
    ContactKeys contact;
    Integrator integrator = Integrator::SemiImplicitEuler;
};

FabricParticles readShared(ObjectReader& reader, std::size_t count, std::set<std::string>& names)
{
    FabricParticles shared;
    shared.name = readName(reader, "name");
    if (shared.name.empty())
        reader.fail("name", "must not be empty");
    // The summary's row of the whole rope or cloth goes by its name, as a body's does.
    if (!names.insert(shared.name).second)
        reader.fail("name", fmt::format("'{}' is already taken", oneLine(shared.name)));
    // The whole rope or cloth weighs `mass`, so that its resolution does not change its weight.
    const double total = reader.positive("mass", 1.0);
    shared.mass = total / double(count);
    // A share below the smallest normal double has no finite inverse (or is zero): every force
    // on the particle would turn into an infinite acceleration.
    if (!(shared.mass >= std::numeric_limits<double>::min()))
        reader.fail("mass", fmt::format("{} kg shared among {} particles is {} kg each, below the smallest normal "
                                        "number ({:g}): give a larger mass", total, count, shared.mass,
                                        std::numeric_limits<double>::min()));
    shared.restitution = reader.number("restitution", 1.0);
    if (!(shared.restitution >= 0.0 && shared.restitution <= 1.0))
        reader.fail("restitution", fmt::format("must be in [0, 1], got {}", shared.restitution));
    shared.contact = readContactKeys(reader);
    shared.integrator = readIntegrator(reader, "integrator", Integrator::SemiImplicitEuler);
    return shared;
}

std::size_t addFabricParticle(ObjectReader& reader, const std::string& key, FabricTarget& target,
                              const FabricParticles& shared, const std::string& name, const dvec3& at)
{
    if (!target.names.insert(name).second)
        reader.fail("name", fmt::format("its particle '{}' is named like another particle", oneLine(name)));
    if (!insideSurfaces(target.world, at))
        reader.fail(key, fmt::format("particle '{}' at {}", oneLine(name), outsideText(target.world, at)));
    if (!insideSurfaces(target.world, at, shared.contact.radius))
        reader.fail("radius", fmt::format("particle '{}': {}", oneLine(name),
                                          ballOutsideText(target.world, at, shared.contact.radius)));
    Particle p;
    p.setName(name);
    p.setPos(at);
    p.setMass(shared.mass);
    p.setCor(shared.restitution);
    p.setRadius(shared.contact.radius);
    p.setFriction(shared.contact.friction);
    p.setIntegrator(shared.integrator);
    target.world.addParticle(p);
    return target.world.bodyCount() - 1;
}

/// A rope's or a cloth's springs, added to the world as one force (a SpringNetwork: evaluated
/// in one call, on all cores) when they are all known.
struct Springs {
    World& world;
    std::vector<SpringNetwork::Link> links;

    /// A spring at rest where the two particles start.
    void join(std::size_t a, std::size_t b, double stiffness, double damping)
    {
        const double rest = glm::length(world.body(a).getPos() - world.body(b).getPos());
        links.push_back({a, b, stiffness, rest, damping});
    }
    void addToWorld() { world.addForce(std::make_unique<SpringNetwork>(links)); }
};

std::size_t readWholeCount(ObjectReader& reader, const std::string& key, std::size_t limit)
{
    const double x = reader.number(key);
    if (!(x >= 2 && x <= double(limit) && std::floor(x) == x))
        reader.fail(key, fmt::format("must be a whole number from 2 to {}, got {}", limit, x));
    return static_cast<std::size_t>(x);
}

/// A stiffness of 0 (or none given, when optional) leaves those springs out.
double readStiffness(ObjectReader& reader, const std::string& key, bool required)
{
    return required ? reader.positive(key) : reader.nonNegative(key, 0.0);
}

/// Pins of a rope: "start" and/or "end".
std::vector<std::size_t> readRopePins(ObjectReader& reader, std::size_t count)
{
    std::vector<std::size_t> pins;
    reader.array("pinned", [&](const Json& item, const std::string&, std::size_t) {
        const std::string name = item.is_string() ? item.get<std::string>() : "";
        if (name != "start" && name != "end")
            reader.fail("pinned", fmt::format("unknown end {} (expected \"start\" or \"end\")", item.dump()));
        pins.push_back(name == "start" ? 0 : count - 1);
    });
    return pins;
}

} // namespace

void readRope(const Json& value, const std::string& path, const std::string& file, FabricTarget target)
{
    ObjectReader reader(value, path, file);
    reader.expectKeys({"name", "from", "to", "count", "mass", "stiffness", "bending_stiffness", "damping", "pinned",
                       "restitution", "radius", "friction", "integrator"});
    const std::size_t count = readWholeCount(reader, "count", 100000);
    const FabricParticles shared = readShared(reader, count, target.names);
    const dvec3 from = reader.vec3("from");
    const dvec3 to = reader.vec3("to");
    if (glm::length(to - from) == 0.0)
        reader.fail("to", "must differ from \"from\": a rope has a length");
    const double stiffness = readStiffness(reader, "stiffness", true);
    const double bending = readStiffness(reader, "bending_stiffness", false);
    const double damping = reader.nonNegative("damping", 0.0);
    const std::vector<std::size_t> pins = readRopePins(reader, count);
    reader.finish();

    RopeLayout rope{shared.name, {}};
    for (std::size_t k = 0; k < count; ++k) {
        const dvec3 at = from + (double(k) / double(count - 1)) * (to - from);
        const std::string name = fmt::format("{}[{}]", shared.name, k);
        rope.particles.push_back(addFabricParticle(reader, k == 0 ? "from" : "to", target, shared, name, at));
    }
    for (const std::size_t pin : pins)
        target.world.body(rope.particles[pin]).setFixed(true);
    Springs springs{target.world, {}};
    for (std::size_t k = 0; k + 1 < count; ++k)
        springs.join(rope.particles[k], rope.particles[k + 1], stiffness, damping);
    if (bending > 0.0)
        for (std::size_t k = 0; k + 2 < count; ++k)
            springs.join(rope.particles[k], rope.particles[k + 2], bending, damping);
    springs.addToWorld();
    target.layout.ropes.push_back(std::move(rope));
}

namespace {

struct GridIndex {
    std::size_t column;
    std::size_t row;
};

/// A pin: a corner's name, or [column, row].
GridIndex readClothPin(ObjectReader& reader, const Json& item, std::size_t columns, std::size_t rows)
{
    if (item.is_string()) {
        const std::string name = item.get<std::string>();
        if (name == "top-left")
            return {0, 0};
        if (name == "top-right")
            return {columns - 1, 0};
        if (name == "bottom-left")
            return {0, rows - 1};
        if (name == "bottom-right")
            return {columns - 1, rows - 1};
        reader.fail("pinned", fmt::format("unknown corner '{}' (expected top-left, top-right, bottom-left, "
                                          "bottom-right, or [column, row])", oneLine(name)));
    }
    const bool pair = item.is_array() && item.size() == 2 && item[0].is_number() && item[1].is_number();
    if (!pair)
        reader.fail("pinned", fmt::format("expected a corner's name or [column, row], got {}", item.dump()));
    const double c = item[0].get<double>(), r = item[1].get<double>();
    if (!(c >= 0 && c < double(columns) && std::floor(c) == c && r >= 0 && r < double(rows) && std::floor(r) == r))
        reader.fail("pinned", fmt::format("[{}, {}] is not a grid index of a {} x {} cloth (column below {}, row "
                                          "below {})", c, r, columns, rows, columns, rows));
    return {std::size_t(c), std::size_t(r)};
}

struct ClothStiffness {
    double structural = 0.0;
    double shear = 0.0;
    double bending = 0.0;
};

ClothStiffness readClothStiffness(ObjectReader& reader)
{
    ObjectReader stiffness = reader.object("stiffness");
    stiffness.expectKeys({"structural", "shear", "bending"});
    ClothStiffness k;
    k.structural = readStiffness(stiffness, "structural", true);
    k.shear = readStiffness(stiffness, "shear", false);
    k.bending = readStiffness(stiffness, "bending", false);
    stiffness.finish();
    return k;
}

/// Structural springs join each particle to its neighbours along a row and a column, shear
/// springs cross each cell's diagonals, and bending springs skip one particle along a row and
/// a column (they resist folding, not stretching).
void joinCloth(World& world, const ClothLayout& cloth, const ClothStiffness& k, double damping)
{
    Springs springs{world, {}};
    const std::size_t w = cloth.width, h = cloth.height;
    for (std::size_t j = 0; j < h; ++j)
        for (std::size_t i = 0; i < w; ++i) {
            if (i + 1 < w)
                springs.join(cloth.at(i, j), cloth.at(i + 1, j), k.structural, damping);
            if (j + 1 < h)
                springs.join(cloth.at(i, j), cloth.at(i, j + 1), k.structural, damping);
            if (k.shear > 0.0 && i + 1 < w && j + 1 < h) {
                springs.join(cloth.at(i, j), cloth.at(i + 1, j + 1), k.shear, damping);
                springs.join(cloth.at(i + 1, j), cloth.at(i, j + 1), k.shear, damping);
            }
            if (k.bending > 0.0 && i + 2 < w)
                springs.join(cloth.at(i, j), cloth.at(i + 2, j), k.bending, damping);
            if (k.bending > 0.0 && j + 2 < h)
                springs.join(cloth.at(i, j), cloth.at(i, j + 2), k.bending, damping);
        }
    springs.addToWorld();
}

} // namespace

void readCloth(const Json& value, const std::string& path, const std::string& file, FabricTarget target)
{
    ObjectReader reader(value, path, file);
    reader.expectKeys({"name", "origin", "across", "down", "columns", "rows", "mass", "stiffness", "damping", "pinned",
                       "restitution", "radius", "friction", "integrator"});
    const std::size_t columns = readWholeCount(reader, "columns", 1000);
    const std::size_t rows = readWholeCount(reader, "rows", 1000);
    const FabricParticles shared = readShared(reader, columns * rows, target.names);
    const dvec3 origin = reader.vec3("origin");
    const dvec3 across = reader.vec3("across");
    const dvec3 down = reader.vec3("down");
    if (glm::length(glm::cross(across, down)) == 0.0)
        reader.fail("down", "must not be parallel to \"across\" (or zero): the two span the sheet");
    const ClothStiffness stiffness = readClothStiffness(reader);
    const double damping = reader.nonNegative("damping", 0.0);
    std::vector<GridIndex> pins;
    reader.array("pinned", [&](const Json& item, const std::string&, std::size_t) {
        pins.push_back(readClothPin(reader, item, columns, rows));
    });
    reader.finish();

    ClothLayout cloth{shared.name, target.world.bodyCount(), columns, rows};
    for (std::size_t j = 0; j < rows; ++j)
        for (std::size_t i = 0; i < columns; ++i) {
            const dvec3 at =
                origin + (double(i) / double(columns - 1)) * across + (double(j) / double(rows - 1)) * down;
            addFabricParticle(reader, "origin", target, shared, fmt::format("{}[{},{}]", shared.name, i, j), at);
        }
    for (const GridIndex& pin : pins)
        target.world.body(cloth.at(pin.column, pin.row)).setFixed(true);
    joinCloth(target.world, cloth, stiffness, damping);
    target.layout.cloths.push_back(std::move(cloth));
}

} // namespace pba::scene_detail
