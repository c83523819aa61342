#pragma once
// What the World keeps for its systems stepped by backward Euler and by XPBD: each one's springs,
// gathered once, and its solver's state (the conjugate gradients' buffers, the constraints'
// colours), made anew when the system's members or the world's forces change.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "particle_systems/backward_euler.hpp"
#include "particle_systems/spring_system.hpp"
#include "balls/particle_grid.hpp"
#include "particle_systems/xpbd.hpp"
#include "particle_systems/xpbd_rigid_contacts.hpp"

namespace pba::detail {

struct SpringSolver {
    std::vector<std::size_t> members; ///< what it was made for
    std::size_t forces = 0;
    SpringSystem springs;
    BackwardEuler backwardEuler;
    Xpbd xpbd;
    /// Scratch of a step: where every body is (for the fixed ends), and the members' forces at the
    /// start. Members, not thread_local: a lambda run on a pool thread names that thread's copy.
    std::vector<dvec3> positions, startForces;
    std::vector<dvec3> heldOn; ///< backward Euler's: the normal of the surface each member rests on, or zero
    std::vector<char> heldOnRoom; ///< backward Euler's: whether that surface is the room's
    /// Backward Euler's: each member's mass in the solve, with a rigid body it carries at a ball
    /// joint; its mass in some directions only (pinned along a rod to a fixed body; a joint
    /// point's whole mass matrix), or none (empty); and the bodies that take what the solve gave
    /// the mass they lent: the member (or joint point), the body (a world index), the mass, the
    /// directions it acts in, the arm, and the velocity before the solve.
    std::vector<double> solveMass;
    std::vector<dmat3> directionalMass;
    struct Carried {
        std::size_t member, body;
        double mass;
        dmat3 along;
        dvec3 arm, before;
    };
    std::vector<Carried> carried;
    /// Backward Euler's: how each joint between a member and a rigid body enters the solve (the
    /// member carries the body's mass at a ball joint, pinned along a rod to a fixed body; a
    /// spring joint's or rod's body point is one more member: world_particle_systems.cpp).
    struct Link {
        enum Kind { Carried, PinnedAlongRod, Point } kind = Carried;
        std::size_t joint = 0, member = 0, body = 0; ///< the body a world index
        bool moves = true;                           ///< the body is not fixed
        /// How many points and carriers share the body (1: a body only carried is carried whole)
        std::size_t sharing = 1;
    };
    std::vector<Link> links;
    static constexpr std::size_t kNoBody = std::size_t(-1);
    /// The body points, solved as members after the system's own: their states and bodies (a
    /// fixed body's: kNoBody), the springs with them, the system with those springs (made anew
    /// when they change), and the whole state of members and points for the solve.
    std::vector<dvec3> pointX, pointV;
    std::vector<std::size_t> pointBody;
    std::vector<SpringSystem::LocalSpring> jointSprings, joinedWith;
    SpringSystem joined;
    std::vector<dvec3> wholeX, wholeV;
    /// Backward Euler's: the moving bodies members rest on (world indices, and as the solve's
    /// bearers), each member's bearer and arm, and the friction of what it is held on (the
    /// pair's, or below zero: the room's, the member's own).
    std::vector<std::size_t> bearerBodies;
    std::vector<BackwardEuler::Bearer> bearers;
    std::vector<std::uint32_t> bearerOf;
    std::vector<dvec3> bearerArm;
    std::vector<double> heldFriction;
    std::vector<dvec3> bearerImpulse; ///< per member, what it gives its bearer this step
    std::vector<double> radius, restitution, friction; ///< XPBD's: each member's, for its room
    XpbdRigidContacts rigidContacts; ///< XPBD's: the rigid bodies its substeps meet
    /// XPBD's: the members that may touch each other in the step, found with their grid.
    ParticleGrid grid;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
    std::vector<Xpbd::Touching> touching;

    /// The springs to solve with: the system's own, with the joint points' when there are any.
    /// Made anew when the joint points' springs join other ends; their values change every step
    /// (a rod's stiffness follows the body's mass along it).
    const SpringSystem& solvedSprings()
    {
        if (jointSprings.empty())
            return springs;
        const auto sameEnds = [](const SpringSystem::LocalSpring& a, const SpringSystem::LocalSpring& b) {
            return a.a == b.a && a.b == b.b;
        };
        if (joined.bodies() != springs.bodies() + pointX.size() ||
            !std::equal(joinedWith.begin(), joinedWith.end(), jointSprings.begin(), jointSprings.end(), sameEnds)) {
            joined = springs.withExtraMembers(pointX.size(), jointSprings);
            joinedWith = jointSprings;
        }
        joined.setLastSprings(jointSprings);
        joined.placeFixedEnds(positions);
        return joined;
    }

    /// Makes the springs (and, for XPBD, their colours) anew unless they were made for these
    /// members and forces.
    void prepare(std::span<const ClonePtr<Force>> worldForces, std::span<const std::size_t> system,
                 std::size_t bodyCount, bool colour)
    {
        if (forces == worldForces.size() && members.size() == system.size() &&
            std::equal(members.begin(), members.end(), system.begin()))
            return;
        members.assign(system.begin(), system.end());
        forces = worldForces.size();
        springs = SpringSystem(worldForces, system, bodyCount);
        joinedWith.clear(); // (joined is made from springs)
        xpbd = colour ? Xpbd(springs) : Xpbd();
    }
};

struct SpringSolvers {
    SpringSolver backwardEuler, xpbd;
    std::unique_ptr<SpringSolvers> clone() const { return std::make_unique<SpringSolvers>(*this); }
};

} // namespace pba::detail
