#pragma once
// The surfaces a World gives its bodies (a ground or a room, the blow dryer's hole in the floor
// and the grille at the bottom of its shaft) in the form a swarm's fused pass holds in
// registers: every plane a wall known to face along an axis when the code is compiled, in the
// order World::planes() lists them. Private to the core.
#include <array>
#include <limits>
#include <optional>
#include <span>
#include <utility>

#include "surfaces/axis_plane.hpp"
#include "surfaces/collision_rules.hpp"

namespace pba {

/// A world's planes as walls: the floor (with a hole or without), the ceiling, the low and high
/// x and z walls, and the grille. One the world does not have (the ceiling and walls over a
/// ground, the grille without a hole) is a plane at infinity: no finite point is beyond it, so
/// every select of the rule leaves a point as it was (but for the sign of a zero coordinate,
/// which a plane facing -axis may turn positive).
template <class T>
struct RoomSurfacesT {
    AxisPlaneT<T, 1> floor, ceiling;
    AxisPlaneT<T, 0> lowX, highX;
    AxisPlaneT<T, 2> lowZ, highZ;
    AxisPlaneT<T, 1> grille;
    /// A point below the floor closer than this to the hole's axis (squared) is in the shaft,
    /// where it may be: 8 units in the last place inside the wall, for rounding (pushIntoShaft
    /// puts a body 16 inside).
    T shaftInnerSquared;
    /// The room's inside as bounds on x, y and z (the grille's height below, the ceiling's
    /// above; infinite where there is no such surface): each plane faces along its axis with the
    /// sign roomSurfaces checked, so sign x - offset < 0 is x < offset, or x > -offset, exactly.
    Vec3<T> low, high;

    /// The part of the rule's first pass that most bodies meet, reflect (`back` 2: mirror) or
    /// clamp (1: put back on the plane): the floor, its hole letting bodies through. The
    /// ceiling, the walls, the shaft's wall and the grille are left out: a body that meets one
    /// is one that needsWholeRule, and so is any that this pass leaves outside. For every
    /// other body it is the whole first pass, the surfaces it leaves out doing nothing to it
    /// (see Swarm's passInRoom). `kHole` false, for a floor without a hole, skips the hole's
    /// arithmetic (the same result). The grille is left out too: the few particles on it (of the
    /// 0.1% in the shaft) take the whole rule, and the pass's loop keeps its registers for the
    /// floor's constants, which a swarm at rest feels most (docs/performance.md).
    /// It moves x and v along y only and reads no other component of v: passInRoom relies on it.
    template <bool kHole>
    void commonPass(T restitution, T back, const Vec3<T>& start, Vec3<T>& x, Vec3<T>& v, int& bounces) const
    {
        using collision_detail::pushBack;
        pushBack<kHole, false>(floor, restitution, back, start, x, v, bounces);
    }

    /// The rule's whole first pass, as reflectAfterStep's and clampAfterStep's first visits the
    /// planes: every surface in turn, the shaft's wall with the floor. The scalar start of the
    /// whole rule for a body commonPass hands on (at a wall it costs a tenth of the generic
    /// planes' pass, which works out every plane's hole).
    template <bool kHole>
    void firstPass(T restitution, T back, const Vec3<T>& start, Vec3<T>& x, Vec3<T>& v, int& bounces) const
    {
        using collision_detail::pushBack;
        pushBack<kHole>(floor, restitution, back, start, x, v, bounces);
        pushBack<false>(ceiling, restitution, back, start, x, v, bounces);
        pushBack<false>(lowX, restitution, back, start, x, v, bounces);
        pushBack<false>(highX, restitution, back, start, x, v, bounces);
        pushBack<false>(lowZ, restitution, back, start, x, v, bounces);
        pushBack<false>(highZ, restitution, back, start, x, v, bounces);
        pushBack<false>(grille, restitution, back, start, x, v, bounces);
    }

    /// Whether x is beyond a surface, not counting the floor where x is in the hole's shaft
    /// (within its wall): after commonPass, a body at the ceiling, a wall or the grille, at a
    /// corner, faster than the room is wide or at the shaft's wall, which the rest of the rule
    /// must see to.
    /// As comparisons with the bounds rather than each plane's distance (a product and a
    /// difference), it left the collision pass's loop seven constants fewer to keep.
    /// The six bounds are one comparison, of the least of the six margins: a difference of two
    /// floats rounds to a number of the exact difference's sign (zero only when they are
    /// equal), so the least margin is >= 0 exactly when x is within every bound. Six
    /// comparisons joined by `and` were a chain of masked compares, each waiting for the last,
    /// the pass's hottest instructions, and a swarm at rest ran about 10% slower with them
    /// (docs/performance.md). The one difference is
    /// a NaN coordinate, which the minimum may drop: that particle may stay with the pass, but its
    /// state is already flagged as not finite by the integration's check, which saw it.
    bool needsWholeRule(const Vec3<T>& x) const
    {
        const auto rho = floor.fromHoleAxis(x);
        const bool aboveFloor = (x.y >= floor.offset) | (glm::dot(rho, rho) < shaftInnerSquared);
        using collision_detail::lesser;
        const T margin = lesser(lesser(lesser(x.x - low.x, high.x - x.x), lesser(x.z - low.z, high.z - x.z)),
                                lesser(x.y - low.y, high.y - x.y));
        return !(aboveFloor & (margin >= T(0)));
    }

    bool hasHole() const { return floor.holeRadius > T(0); }
};

/// The planes as RoomSurfacesT when they are a World's: a floor facing +y (which alone may have
/// a hole), then, for a room, the ceiling and the x and z walls in roomPlanes' order, then a
/// grille facing +y below a floor with a hole. Anything else (a plane at an angle, another
/// order) is not, and takes the rule one particle at a time.
template <class T>
inline std::optional<RoomSurfacesT<T>> roomSurfaces(std::span<const PlaneT<T>> planes)
{
    constexpr T kFar = std::numeric_limits<T>::infinity();
    const auto wall = [&](int axis, T sign) {
        PlaneT<T> far{Vec3<T>(T(0)), -kFar};
        far.normal[axis] = sign;
        return far;
    };
    const auto faces = [](const PlaneT<T>& plane, int axis, T sign) {
        return plane.axis() == axis && plane.normal[axis] == sign;
    };
    if (planes.empty() || !faces(planes[0], 1, T(1)))
        return std::nullopt;
    const bool hole = planes[0].holeRadius > T(0);
    const bool room = planes.size() >= 6;
    if (planes.size() != (room ? 6u : 1u) + (hole ? 1u : 0u))
        return std::nullopt;
    std::array<PlaneT<T>, 7> p{planes[0],     wall(1, T(-1)), wall(0, T(1)), wall(0, T(-1)),
                               wall(2, T(1)), wall(2, T(-1)), wall(1, T(1))};
    static constexpr std::array<std::pair<int, int>, 5> kRoomWalls{{{1, -1}, {0, 1}, {0, -1}, {2, 1}, {2, -1}}};
    for (std::size_t w = 0; room && w < kRoomWalls.size(); ++w) {
        const auto [axis, sign] = kRoomWalls[w];
        if (!faces(planes[1 + w], axis, T(sign)))
            return std::nullopt;
        p[1 + w] = planes[1 + w];
    }
    if (hole) {
        if (!faces(planes.back(), 1, T(1)))
            return std::nullopt;
        p[6] = planes.back();
    }
    for (std::size_t k = 1; k < p.size(); ++k)
        if (p[k].holeRadius != T(0))
            return std::nullopt;
    const T inner = p[0].holeRadius * (T(1) - T(8) * std::numeric_limits<T>::epsilon());
    return RoomSurfacesT<T>{AxisPlaneT<T, 1>(p[0]), AxisPlaneT<T, 1>(p[1]), AxisPlaneT<T, 0>(p[2]),
                            AxisPlaneT<T, 0>(p[3]), AxisPlaneT<T, 2>(p[4]), AxisPlaneT<T, 2>(p[5]),
                            AxisPlaneT<T, 1>(p[6]), inner * inner,
                            Vec3<T>(p[2].offset, p[6].offset, p[4].offset),
                            Vec3<T>(-p[3].offset, -p[1].offset, -p[5].offset)};
}

} // namespace pba
