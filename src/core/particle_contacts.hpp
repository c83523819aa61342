#pragma once
// Balls against balls: the particles with a radius that touch after a step are pushed apart
// and exchange impulses, with restitution and Coulomb friction, the room standing by as an
// immovable partner. Private to the core.
//
// Contacts are solved a pair at a time in the grid's order (Gauss-Seidel), a few sweeps a step:
// each sweep separates the pair's overlap in inverse proportion to the masses, and takes away
// the part of their approach speed that restitution does not give back, then puts every ball
// back inside the room (whose push it cannot share). A stack converges by halves each sweep.
// The order is the pairs' index order, so the result does not depend on the thread count.
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "particle_grid.hpp"
#include "pba/collision.hpp"

namespace pba::detail {

struct Ball {
    dvec3 x{0.0}, v{0.0};
    double inverseMass = 0.0; ///< 0: a fixed ball, which pushes and is not pushed
    double radius = 0.0;
    double cor = 1.0;
    double friction = 0.0;
    double restingSpeed = 0.0; ///< what its acceleration gives in one step, |a| dt
};

struct BallContacts {
    ParticleGrid grid;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::vector<Ball> balls;
    std::vector<std::size_t> bodies; ///< each ball's world index

    std::unique_ptr<BallContacts> clone() const { return std::make_unique<BallContacts>(*this); }

    /// Sweeps over the touching pairs of `balls` (found anew), with `planes` the room's.
    /// `together(a, b)`: whether balls a and b may touch (a rope's neighbours are joined instead).
    template <class Together>
    void solve(std::span<const Plane> planes, int sweeps, Together&& together)
    {
        double largest = 0.0;
        for (const Ball& b : balls)
            largest = std::max(largest, b.radius);
        grid.findPairs(
            balls.size(), [&](std::size_t i) { return balls[i].x; }, [&](std::size_t i) { return balls[i].radius; },
            largest, pairs);
        std::erase_if(pairs, [&](const auto& p) { return !together(p.first, p.second); });
        if (pairs.empty())
            return;
        findWalls(planes, largest);
        for (int sweep = 0; sweep < sweeps; ++sweep) {
            for (const auto& [a, b] : pairs)
                touch(balls[a], balls[b]);
            for (const auto& [k, walls] : nearWall)
                keepInRoom(planes, walls, balls[k]);
        }
    }

    /// One pair's share of a sweep.
    static void touch(Ball& a, Ball& b);
    /// A ball pushed out of the room by a sweep back on its surfaces (those of `walls`, a bit a
    /// plane), its speed into them taken away.
    static void keepInRoom(std::span<const Plane> planes, std::uint32_t walls, Ball& ball);

private:
    /// Each moving ball within eight of the largest radii of a surface, with those surfaces
    /// (wallsWithin), into nearWall: the sweeps move a ball by its overlaps, each under a diameter.
    void findWalls(std::span<const Plane> planes, double largest);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> nearWall;
};

} // namespace pba::detail
