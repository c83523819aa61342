#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>

#include "pba/scene/scene.hpp"

namespace pba {

namespace {

/// splitmix64 (as a swarm's): die i's numbers depend on (i, k) alone.
double uniform(std::uint64_t i, int k)
{
    std::uint64_t z = i * 16 + std::uint64_t(k) + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

/// The room cut into cells a die's bounding sphere fits in with at least 4% of its diameter to spare:
/// a die anywhere in its cell's spare room overlaps no other die and no wall, however the two
/// are turned. A die's cell depends on its index alone (a stride coprime to the cell count,
/// near the golden ratio of it, so that consecutive dice land far apart and the first few
/// hundred already fill the whole room).
struct Lattice {
    glm::ivec3 cells{0};
    dvec3 lo{0.0}, side{0.0};
    std::uint64_t count = 0, stride = 1;

    Lattice(const Aabb& room, double diameter)
    {
        const dvec3 extent = room.max - room.min;
        cells = glm::max(glm::ivec3(glm::floor(extent / (1.04 * diameter))), glm::ivec3(0));
        count = std::uint64_t(cells.x) * std::uint64_t(cells.y) * std::uint64_t(cells.z);
        lo = room.min;
        side = extent / dvec3(glm::max(cells, glm::ivec3(1)));
        stride = std::max<std::uint64_t>(1, std::uint64_t(0.6180339887 * double(count)));
        while (count > 0 && std::gcd(stride, count) != 1)
            ++stride;
    }

    /// Die i's centre: its cell's centre moved by up to the spare room, by die i's numbers.
    dvec3 centre(std::uint64_t i, double diameter) const
    {
        const std::uint64_t c = (i * stride) % count;
        const auto across = std::uint64_t(cells.x) * std::uint64_t(cells.z);
        const dvec3 cell(double(c % std::uint64_t(cells.x)), double(c / across),
                         double((c / std::uint64_t(cells.x)) % std::uint64_t(cells.z)));
        const dvec3 spare = side - diameter;
        const dvec3 jitter = dvec3(uniform(i, 0), uniform(i, 1), uniform(i, 2)) - 0.5;
        return lo + (cell + 0.5) * side + spare * jitter;
    }
};

} // namespace

Scene manyDice(std::size_t count)
{
    if (count == 0)
        throw std::invalid_argument("a pile of dice needs at least one die");
    Scene scene = loadScene("dice");
    World& world = scene.world;
    const RigidBody die = static_cast<const RigidBody&>(world.body(scene.dice.at(0)));
    // 10 cm dice, thrown all over the room (the built-in's tray is left out).
    RigidBody prototype(Shape::box(dvec3(0.1)), 600.0);
    const double diameter = glm::length(dvec3(0.1));
    const Lattice lattice(*world.room(), diameter);
    if (count > lattice.count)
        throw std::invalid_argument(fmt::format("a pile of dice: the dice scene's room holds at most {} dice "
                                                "without overlaps, asked for {}", lattice.count, count));
    World many;
    many.setRoom(*world.room());
    for (std::size_t k = 0; k < world.forceCount(); ++k)
        many.addForce(world.force(k).clone());
    prototype.setCor(die.getCor());
    prototype.setFriction(die.getFriction());
    for (std::size_t i = 0; i < count; ++i) {
        auto body = std::make_unique<RigidBody>(prototype); // copies share the shape's corners and mesh
        body->setName(fmt::format("die{}", i));
        body->setPos(lattice.centre(i, diameter));
        body->setOrientation(dquat(uniform(i, 3) - 0.5, uniform(i, 4) - 0.5, uniform(i, 5) - 0.5, uniform(i, 6) - 0.5));
        body->setVel(6.0 * (dvec3(uniform(i, 7), uniform(i, 8), uniform(i, 9)) - 0.5));
        body->setAngularVelocity(20.0 * (dvec3(uniform(i, 10), uniform(i, 11), uniform(i, 12)) - 0.5));
        many.addBody(std::move(body));
    }
    scene.world = std::move(many);
    scene.dice.resize(count);
    std::iota(scene.dice.begin(), scene.dice.end(), std::size_t(0));
    scene.camera.reset(); // the whole room, not the tray's corner
    scene.name = fmt::format("dice x {}", count);
    scene.summary = fmt::format("Rigid bodies: {} 10 cm dice thrown all over the room", count);
    scene.description = scene.summary + ", each from its own cell of a lattice, with its own spin.";
    scene.source = fmt::format("builtin:dice with {} dice", count);
    return scene;
}

} // namespace pba
