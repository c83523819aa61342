#pragma once
// Whether the scene's rigid bodies start where they can be: each shape, at its orientation,
// clear of the floor (or reaching down only into the blow dryer's hole, and there not through
// the grille or the shaft's wall), the walls and the ceiling. The contacts push a body back out
// of a surface by its speed, not its depth, so one that starts 0.14 m into the floor stays there,
// and one larger than the room is thrown about by every wall at once. Touching is allowed: a box
// resting on the floor starts exactly on it. Likewise clear of each other.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "pba/fabric.hpp"
#include "pba/world.hpp"

namespace pba::scene_detail {

/// Throws SceneError for the first rigid body that starts through a surface of the world (its
/// planes, the floor's hole and grille): rigid_bodies[i].shape when the shape at its orientation
/// is larger than the room along an axis, else rigid_bodies[i].position, naming the surface and
/// the depth. Call when the world is complete: the blow dryer cuts its hole after the bodies.
void requireRigidBodiesInside(const World& world, const std::string& file);

/// Two world indices, the lower first.
using BodyPair = std::pair<std::size_t, std::size_t>;

/// Throws SceneError (rigid_bodies[i].position) for the first rigid body, in the file's order,
/// that starts more than a millimetre inside another (a fixed one, or a moving one but for the
/// sorted `joinedApart`, whose joints keep them from colliding): the contacts would push it out
/// through the nearest face in one step, lifting it (energy from nowhere: a box started 15 cm
/// into another rose with a third more energy) or through the body (a sphere wholly inside a
/// fixed box dropped out of its bottom).
void requireRigidBodiesApart(const World& world, const std::string& file, const std::vector<BodyPair>& joinedApart);
/// Refuses a particle with a radius (which meets rigid bodies) that starts more than a millimetre
/// inside a rigid body it is not joined to, naming its particles[i] or its rope's or cloth's key.
void requireParticlesOutsideRigidBodies(const World& world, const FabricLayout& fabric, const std::string& file,
                                        const std::vector<BodyPair>& joinedApart);

} // namespace pba::scene_detail
