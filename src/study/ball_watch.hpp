#pragma once
// What the balls (particles with a radius) did over a run, seen at the start and every tenth
// step: how far two that collide went into each other, how far one went into a rigid body, how
// far a rope's or cloth's edges between two went into a rigid body and a free ball into them, and
// when the balls that are no rope's or cloth's came together in one touching group. `pba sim` prints these, so that
// descriptions such as "no particle is ever inside the box" say what it measures.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "pba/world.hpp"

namespace pba::study {

struct BallFigures {
    std::size_t balls = 0;       ///< particles with a radius
    /// Two balls that collide (World::ballsCollide), not both fixed: their deepest overlap, as a
    /// share of the smaller one's diameter, and when.
    double deepestPair = 0.0, deepestPairAt = 0.0;
    /// A ball and a rigid body no joint joins: how far the ball went into it (m), which body, and when.
    double deepestInBody = 0.0, deepestInBodyAt = 0.0;
    std::string deepestBody;
    /// A rope's or cloth's edges between two balls (the segments the contacts hold, as thick as
    /// the balls but no thicker than half the gap between them), looked at in 16 pieces, and a
    /// cloth's triangles between three (as thick): how far one went into a rigid body none of
    /// its balls is joined to, which, and when.
    std::size_t segments = 0;
    double deepestBetween = 0.0, deepestBetweenAt = 0.0;
    std::string deepestBetweenBody;
    /// A free ball (below) against those edges and the cloths' triangles between them (as thick):
    /// how far it went into one at most (m), and when.
    double deepestFreeInEdge = 0.0, deepestFreeInEdgeAt = 0.0;
    /// The ropes and cloths (balls joined by edges), and, when there are two or more, how far a
    /// ball or an edge of one (looked at in 16 pieces) went into another's edges and triangles at
    /// most (m), and when.
    std::size_t nets = 0;
    double deepestNetBallInEdge = 0.0, deepestNetBallInEdgeAt = 0.0;
    /// The free balls (moving, in no rope or cloth), when there are two or more: every one of them
    /// touching another, all in one group, from then to the end.
    std::size_t freeBalls = 0;
    std::optional<double> oneGroupFrom;
};

class BallWatch {
public:
    /// `inFabric[i]`: body i is a rope's or cloth's particle; `edges`, the ropes' and cloths'
    /// (FabricLayout::edges).
    BallWatch(const World& world, const std::vector<bool>& inFabric,
              const std::vector<std::pair<std::size_t, std::size_t>>& edges = {});
    bool active() const { return !m_balls.empty(); }
    /// Call after every step; it looks every kEvery steps.
    void record(const World& world);
    /// Call after the last step: it looks there too.
    void finish(const World& world);
    static constexpr int kEvery = 10;
    /// Two balls touch when their surfaces are this close (m), or this share of their radii' sum
    /// if that is less (sand grains a millimetre apart do not touch).
    static constexpr double kTouch = 1e-3;
    static constexpr double kTouchShare = 0.01;
    const BallFigures& figures() const { return m_figures; }

private:
    void look(const World& world);
    void lookAtPairs(const World& world, const std::vector<dvec3>& centres, double now);
    void lookIntoBodies(const World& world, const std::vector<dvec3>& centres, double now);
    void lookBetweenBalls(const World& world, const std::vector<dvec3>& centres, double now);
    void lookIntoEdges(const std::vector<dvec3>& centres, double now);
    /// Two nets' edges crossing between their balls; `around` and `reach`, the spheres around the
    /// edges, then the triangles.
    void lookAtCrossings(const std::vector<dvec3>& centres, const std::vector<dvec3>& around,
                         const std::vector<double>& reach, double now);
    std::vector<dvec3> centresOf(const World& world) const;
    std::vector<dvec3> m_startCentres; ///< looked at for pairs after the first step
    double m_startTime = 0.0;
    std::vector<std::size_t> m_balls;     ///< world indices of the particles with a radius
    std::vector<double> m_radii;
    std::vector<bool> m_free;             ///< of m_balls: in the touching group
    std::vector<bool> m_fixed;            ///< of m_balls
    std::vector<std::pair<std::size_t, std::size_t>> m_joined; ///< world indices a joint joins, both ways, sorted
    std::vector<std::size_t> m_bodies;    ///< the rigid bodies
    std::vector<std::pair<std::size_t, std::size_t>> m_segments; ///< of m_balls: two balls an edge joins
    std::vector<std::array<std::size_t, 3>> m_triangles;          ///< of m_balls: three edges' balls
    static constexpr std::size_t kNoNet = ~std::size_t(0);
    std::vector<std::size_t> m_netOf; ///< of m_balls: its rope's or cloth's (a ball of it), or kNoNet
    long m_steps = 0;
    BallFigures m_figures;
};

} // namespace pba::study
