#include <cmath>
#include <cstdint>
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

} // namespace

Scene manyDice(std::size_t count)
{
    if (count == 0)
        throw std::invalid_argument("a pile of dice needs at least one die");
    Scene scene = loadScene("dice");
    World& world = scene.world;
    const RigidBody die = static_cast<const RigidBody&>(world.body(0));
    World many;
    many.setRoom(*world.room());
    for (std::size_t k = 0; k < world.forceCount(); ++k)
        many.addForce(world.force(k).clone());
    // 10 cm dice (the built-in's are 30 cm), thrown from anywhere in the room's lower half.
    RigidBody prototype(Shape::box(dvec3(0.1)), 600.0);
    prototype.setCor(die.getCor());
    prototype.setFriction(die.getFriction());
    const dvec3 lo = world.room()->min + 0.1, hi = world.room()->max - 0.1;
    for (std::size_t i = 0; i < count; ++i) {
        auto body = std::make_unique<RigidBody>(prototype); // copies share the shape's corners and mesh
        body->setName(fmt::format("die{}", i));
        body->setPos(lo + (hi - lo) * dvec3(uniform(i, 0), 0.5 * uniform(i, 1), uniform(i, 2)));
        body->setOrientation(dquat(uniform(i, 3) - 0.5, uniform(i, 4) - 0.5, uniform(i, 5) - 0.5, uniform(i, 6) - 0.5));
        body->setVel(6.0 * (dvec3(uniform(i, 7), uniform(i, 8), uniform(i, 9)) - 0.5));
        body->setAngularVelocity(20.0 * (dvec3(uniform(i, 10), uniform(i, 11), uniform(i, 12)) - 0.5));
        many.addBody(std::move(body));
    }
    scene.world = std::move(many);
    scene.name = fmt::format("dice x {}", count);
    scene.source = fmt::format("builtin:dice with {} dice", count);
    return scene;
}

} // namespace pba
