#pragma once
// What rigid bodies do over a run: when each comes to rest for good and on which face, when a
// ball's contact stops slipping, how often a free body turns over and how well it keeps its
// energy and angular momentum. `pba sim` prints these, so that the rigid scenes' descriptions
// say only what it measures; the tests hold the descriptions to them.
#include <optional>
#include <string>
#include <vector>

#include "pba/world.hpp"

namespace pba::study {

/// Still: a speed below this (m/s) and an angular speed below this (rad/s).
inline constexpr double kStill = 1e-6;
/// Rolling: a contact point slipping slower than this (m/s).
inline constexpr double kNoSlip = 1e-6;

struct RigidFigures {
    std::string name;
    std::optional<double> stillFrom;   ///< the start of the run's last stretch at rest, s
    /// A box at rest at the end: the face it lies on ("+x" ... "-z", the outward normal that
    /// points down in its own frame) and the angle between that normal and gravity, degrees.
    std::string restingFace;
    double tilt = 0.0;
    std::optional<double> rollingFrom; ///< a sphere: the first time it touched a surface without slipping, s
    double rollingSpeed = 0.0;         ///< its speed then, m/s
    /// A body whose principal moments differ, its body frame the principal one: the times its
    /// angular velocity about the middle axis changed sign (it turned over, in a free body),
    /// each between the two steps that saw the sign change, where the straight line through
    /// their values crosses zero.
    std::vector<double> flips;
    double meanSpin = 0.0;             ///< |w| over the run, rad/s
    double energyDrift = 0.0;          ///< the largest |E_rot / E_rot(0) - 1| over the run; NaN without a spin at 0
    double momentumDrift = 0.0;        ///< the largest ||L| / |L(0)| - 1| over the run; NaN as energyDrift

    /// Whether the body turned free of torques: it kept its rotational energy and |L| within
    /// kFree (neither a contact nor a field turned it).
    bool free() const { return energyDrift < kFree && momentumDrift < kFree; }
    static constexpr double kFree = 1e-3;
};

class RigidWatch {
public:
    explicit RigidWatch(const World& world);
    bool active() const { return !m_tracks.empty(); }

    /// Call after every step.
    void record(const World& world);
    /// One per rigid body, in the world's order.
    std::vector<RigidFigures> bodies(const World& world) const;

private:
    struct Track {
        std::size_t body = 0;
        RigidFigures figures;
        int middleAxis = -1;     ///< the body-frame axis of intermediate inertia; -1 if none
        double lastMiddle = 0.0; ///< the last nonzero angular velocity about it
        double lastMiddleAt = 0.0; ///< the time it was seen
        double energy0 = 0.0, momentum0 = 0.0, spinSum = 0.0;
        long steps = 0;
    };
    void look(const World& world, Track& t) const;
    std::vector<Track> m_tracks;
};

} // namespace pba::study
