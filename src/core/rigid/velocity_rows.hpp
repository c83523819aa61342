#pragma once
// One contact point as the velocity sweeps see it: its three rows (the normal and two tangents),
// their impulses and the normal's target; and one contact of an island, as every pass of the
// solver finds its rows. Private to the core.
#include <cstdint>

#include <glm/vec3.hpp>

#include "rigid/contact.hpp"
#include "rigid/solver_body.hpp"

namespace pba::rigid {

/// What an impulse of 1 along a direction u at a point does, worked out once a step so that a
/// sweep is dot products and additions: the arms' moments rA x u and rB x u, and what they
/// turn each body by, IA^-1 (rA x u) and IB^-1 (rB x u). In single precision: a sweep streams
/// every row of an island, and at 64 bytes a row a heap's rows stay in the core's cache (in
/// double they did not, and the sweeps waited on memory). The impulses add up in double, but in a
/// large island's wide sweeps, whose arithmetic is single precision throughout.
struct Jacobian {
    glm::vec3 u{0.0f};
    glm::vec3 momentA{0.0f}, momentB{0.0f};
    glm::vec3 turnA{0.0f}, turnB{0.0f};
    float mass = 0.0f; ///< 1 / (1/mA + 1/mB + (rA x u).IA^-1(rA x u) + (rB x u).IB^-1(rB x u))
};

/// What the velocity sweeps read and write of one contact point, and nothing else.
struct VelocityRows {
    Jacobian along, across[2]; ///< the normal and the two tangents
    double normalImpulse = 0.0;
    double tangentImpulse[2] = {0.0, 0.0};
    double target = 0.0; ///< the normal speed that closes the start's gap within the step, no more
};

/// One contact of an island as the solver's passes work on it: which of the world's contacts,
/// its two bodies, what it is made of, and where its points' rows are: rows[first, first + count).
struct IslandContact {
    std::uint32_t contact = 0;
    BodyIndex a = 0, b = 0;
    double friction = 0.0, restitution = 0.0;
    double radiusA = 0.0, radiusB = 0.0; ///< a sphere's radius, 0 for any other shape
    std::uint32_t first = 0;
    int count = 0;
};

/// The two points' relative speed along a row. `Body` is a SolverBody, or anything with its
/// v, w, inverseMass and isStatic() (the exact solve's scratch velocity changes).
template <class Body>
double speedAlong(const Jacobian& j, const Body& a, const Body& b)
{
    return glm::dot(dvec3(j.u), b.v - a.v) + glm::dot(dvec3(j.momentB), b.w) - glm::dot(dvec3(j.momentA), a.w);
}

/// An impulse `lambda` along a row: on B, and its opposite on A (a static body untouched: the
/// islands that touch one share it).
template <class Body>
void applyAlong(const Jacobian& j, double lambda, Body& a, Body& b)
{
    if (!a.isStatic()) {
        a.v -= (lambda * a.inverseMass) * dvec3(j.u);
        a.w -= lambda * dvec3(j.turnA);
    }
    if (!b.isStatic()) {
        b.v += (lambda * b.inverseMass) * dvec3(j.u);
        b.w += lambda * dvec3(j.turnB);
    }
}

} // namespace pba::rigid
