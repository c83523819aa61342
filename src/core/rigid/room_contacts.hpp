#pragma once
// The room as static geometry of the contact pipeline: each of its planes (floor, walls, ceiling,
// the grille under a hole) and each hole's shaft is one more static body that a rigid body's
// shape can touch, so a contact with the room is one more pair type for the one solver.
#include <optional>
#include <span>
#include <vector>

#include "contact/narrow_phase.hpp"
#include "pba/collision.hpp"
#include "rigid/contact.hpp"

namespace pba::rigid {

/// The surface ids of a room of `planeCount` planes: plane p is p, the shaft under plane p's
/// hole is planeCount + p.
inline std::uint32_t shaftSurface(std::size_t planeCount, std::size_t plane) { return std::uint32_t(planeCount + plane); }
inline std::uint32_t surfaceCount(std::size_t planeCount) { return std::uint32_t(2 * planeCount); }

/// Appends to `out` the contacts of `shape` at `pose` (body `body`) with the room: one Contact
/// per surface it is within `margin` of, with B = firstSurface + the surface's id, its points
/// the shape's vertices (a sphere's point nearest the surface) at most four, the deepest and
/// the widest spread kept. A point over a floor's hole meets no floor; a body whose centre is
/// below the floor and over the hole is in the hole's shaft, and its points meet the shaft's
/// round wall instead (each with its own normal). Friction and restitution are left to the caller.
/// A surface farther than `sphereMargin` (by default `margin`) from the shape's bounding sphere
/// is passed over: what the body's turning adds to the margin stays within that sphere.
void collideWithRoom(const contact::CollisionShape& shape, const contact::Transform& pose, std::span<const Plane> planes,
                     double margin, BodyIndex body, BodyIndex firstSurface, std::vector<Contact>& out,
                     std::optional<double> sphereMargin = std::nullopt);

/// Moves a body at (x, q) out of every surface of the room one of its points is beyond, along
/// that surface's normal by its deepest point's overlap; returns whether it moved. The room is
/// the world's boundary: what a turning body's arcs leave beyond a wall after the solver is
/// taken back at once, not over the next steps.
bool pushOutOfRoom(const contact::CollisionShape& shape, dvec3& x, const dquat& q, std::span<const Plane> planes);

} // namespace pba::rigid
