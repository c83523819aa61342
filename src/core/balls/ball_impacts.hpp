#pragma once
// Balls that meet within a step: two 4 cm balls closing at 5 m/s passed through each other at
// dt 1/60 s when only the sweeps (particle_contacts.hpp) looked, since they see only where the
// step left the balls. Each ball's path over the step is the straight line from where it
// started to where its integrator put it; a pair that was apart when the step began, came within
// its reach on those paths and closed by over a tenth of its reach in the step meets at its time
// of impact, by the sweeps' rule (restitution, Coulomb friction) on the velocities the step
// ends with, and goes on from there with its new velocities for the rest of the step: where
// they go and how fast is then exact for straight paths. Slower pairs overlap by under a tenth
// of their reach at the step's end, and the sweeps push them apart.
//
// A ball meets the pieces of another net (net_pieces.hpp) so too, at the piece's point it came
// nearest, as a ball of that point's mass whose impulse goes to the piece's balls by their
// weights. A net's balls take an impact's velocity but not its move over the rest of the step
// (Ball::sprung): moved as if in free flight, a sheet's balls stretched its springs, and a ball
// dropped on a 2 kg sheet gave the world 65 J in one step. A ball much heavier than the piece's
// point therefore still goes through it: the impact leaves the point behind, where only a solve
// with the sheet's springs would bring the net behind it. Private to the core.
//
// The impacts are met in rounds, each ball's earliest in a round, in the order of their times,
// then of their balls' indices, so the result does not depend on the thread count. A free ball
// goes on from an impact on a new path, from where it met the other, and the next round looks
// along that path for the ball it may knock into next: up to kRounds impacts a ball a step.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "balls/ball.hpp"
#include "balls/net_pieces.hpp"
#include "balls/particle_grid.hpp"
#include "pba/collision.hpp"

namespace pba::detail {

/// A pair whose relative move in a step is under this many of its reach is left to the sweeps
/// (a resting heap's step never looks for impacts).
inline constexpr double kImpactMove = 0.1;

/// Where the ball is at fraction t of the step on its path.
dvec3 placeAt(const Ball& ball, double t);

/// When, as a fraction of the step, balls a and b first touched on their paths, if they were
/// apart where both paths begin and moved far enough against each other to be met at that time.
std::optional<double> impactTime(const Ball& a, const Ball& b);

/// Balls a and b met at fraction t of a step of dt: their velocities changed by the impact at
/// the point they touched; a free ball's end moved by that change over the rest of the step, its
/// path then running from where it met the other (a sprung one keeps its place). Whether the
/// pair rebounded (not a resting contact); nothing, and nothing changed, if their velocities
/// part them already.
std::optional<bool> meetAt(Ball& a, Ball& b, double t, double dt);

class BallImpacts {
public:
    /// Every pair of `balls` (but those `together(a, b)` rules out) that meets within the step,
    /// and every ball that meets a piece of a net (`findPasses(out)` lists them), met at its time
    /// of impact; a ball moved then kept in the room of `planes`.
    template <class Together, class FindPasses>
    void meet(std::span<Ball> balls, std::span<const Plane> planes, double dt, Together&& together,
              FindPasses&& findPasses)
    {
        m_met.clear();
        if (!anyMoved(balls))
            return;
        m_impacts.clear();
        findCandidates(balls);
        for (const auto& [a, b] : m_candidates)
            if (together(a, b) && balls[a].inverseMass + balls[b].inverseMass > 0.0)
                if (const auto t = impactTime(balls[a], balls[b]))
                    m_impacts.push_back({*t, a, b, kNoPass});
        findPasses(m_passes);
        for (std::uint32_t k = 0; k < m_passes.size(); ++k)
            m_impacts.push_back({m_passes[k].t, m_passes[k].ball, m_passes[k].ball, k});
        meetInOrder(balls, planes, dt);
        // A free ball sent on by its impact may meet another later in the step, on its new path.
        for (int round = 1; round < kRounds && !m_moved.empty(); ++round) {
            m_impacts.clear();
            for (const std::uint32_t k : m_moved) {
                m_grid.near(0.5 * (balls[k].start + balls[k].x), balls[k].radius + 0.5 * glm::length(balls[k].x - balls[k].start),
                            [&](std::size_t i) { return m_middle[i]; }, [&](std::size_t i) { return m_around[i]; }, m_found);
                for (const std::uint32_t j : m_found) {
                    const auto [a, b] = std::minmax(k, j);
                    if (a != b && together(a, b) && balls[a].inverseMass + balls[b].inverseMass > 0.0)
                        if (const auto t = impactTime(balls[a], balls[b]))
                            m_impacts.push_back({*t, a, b, kNoPass});
                }
            }
            meetInOrder(balls, planes, dt);
        }
    }

    /// The pairs met in the last step (a ball and a piece of a net: b is the ball again), and
    /// whether each rebounded.
    struct Met {
        std::uint32_t a, b;
        bool rebounded;
    };
    const std::vector<Met>& met() const { return m_met; }

private:
    static constexpr std::uint32_t kNoPass = ~std::uint32_t(0);
    /// Rounds of impacts a step: a free ball takes up to one a round, each later than its last.
    static constexpr int kRounds = 4;
    struct Impact {
        double t;
        std::uint32_t a, b;
        std::uint32_t pass; ///< into m_passes, for a ball and a piece
    };
    /// Whether any ball moved far enough in the step for an impact.
    static bool anyMoved(std::span<const Ball> balls);
    /// The pairs whose paths' bounding spheres overlap, those spheres kept in the grid.
    void findCandidates(std::span<const Ball> balls);
    /// The impacts found, in order of their times, each ball's earliest (those moved, if free, into
    /// m_moved).
    void meetInOrder(std::span<Ball> balls, std::span<const Plane> planes, double dt);
    /// Ball k met the piece of pass p: the point's change of velocity and move shared out to the
    /// piece's balls by their weights, as a push at it would be. Whether it met (as meetAt).
    std::optional<bool> meetPiece(std::span<Ball> balls, std::uint32_t k, const NetPoint& piece, double t, double dt);

    ParticleGrid m_grid;
    std::vector<dvec3> m_middle; ///< each path's sphere, as the grid holds it
    std::vector<double> m_around;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> m_candidates;
    std::vector<std::uint32_t> m_found, m_moved;
    std::vector<PiecePass> m_passes;
    std::vector<Impact> m_impacts;
    std::vector<std::uint8_t> m_done;
    std::vector<Met> m_met;
};

} // namespace pba::detail
