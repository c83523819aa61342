#pragma once
// The tunnelling workload shared by the swarm and hardening tests: the 4 m cube room with the
// reflect response and a swarm of particles at up to 500 m/s per component, which at dt = 0.1
// cross the room up to 12 times a step.
#include "pba/world.hpp"

namespace pba::test {

inline World fastSwarmWorld(std::size_t count, double restitution, std::uint64_t seed = SwarmDesc{}.seed)
{
    World world;
    world.setRoom(Aabb{dvec3(-2, 0, -2), dvec3(2, 4, 2)});
    world.setCollisionResponse(CollisionResponse::Reflect);
    SwarmDesc desc;
    desc.count = count;
    desc.regionMin = dvec3(-1.9, 0.1, -1.9);
    desc.regionMax = dvec3(1.9, 3.9, 1.9);
    desc.velocityJitter = 500.0;
    desc.restitution = restitution;
    desc.seed = seed;
    world.addSwarm(desc);
    return world;
}

} // namespace pba::test
