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
    /// The longest stretch (kLeastSlide or more) in which the body slid on one fixed body or the
    /// room alone without turning: what it slid on, when, and its acceleration (the slope of its
    /// speed against time, least squares): the incline's g (sin a - mu cos a).
    struct Slide {
        std::string on;
        double from = 0.0, to = 0.0, acceleration = 0.0;
    };
    std::optional<Slide> slide;
    static constexpr double kLeastSlide = 0.1; ///< s
    /// and at least this far: a box held at the friction angle creeps a few hundredths of a millimetre
    static constexpr double kLeastSlideDistance = 1e-3; ///< m
    /// Not a sphere: the largest angle (degrees) by which the body's own axis that pointed up at
    /// the start tilted away from up over the run: a box rocking in the jet, a domino falling.
    std::optional<double> largestTilt;
    std::optional<double> tippedAt;    ///< when that tilt first passed 45 degrees, s (a domino's fall)
    double fromStart = 0.0;            ///< how far its centre ends from where it started, m
    /// A body joined to the world and to no other body: the times its centre was at its highest
    /// (its upward speed changing sign, between the steps as flips): a pendulum's turning points,
    /// two a period.
    std::vector<double> highs;
    double meanSpin = 0.0;             ///< |w| over the run, rad/s
    double energyDrift = 0.0;          ///< the largest |E_rot / E_rot(0) - 1| over the run; NaN without a spin at 0
    double momentumDrift = 0.0;        ///< the largest ||L| / |L(0)| - 1| over the run; NaN as energyDrift

    /// Whether the body turned free of torques: it kept its rotational energy and |L| within
    /// kFree (neither a contact nor a field turned it).
    bool free() const { return energyDrift < kFree && momentumDrift < kFree; }
    static constexpr double kFree = 1e-3;
};

/// What each body touches after the last step: the one body (a world index) or the room it
/// touches, or kNone, or kMany when it touches more than one.
inline constexpr std::size_t kRoom = std::size_t(-1), kNone = std::size_t(-2), kMany = std::size_t(-3);
std::vector<std::size_t> touchedSurfaces(const World& world);
/// What a body touches (as touchedSurfaces) and the normal of its last contact with it, out of
/// what it touches towards the body.
struct Touch {
    std::size_t on = kNone;
    dvec3 outward{0.0};
};

/// What the contacts and joints did over the whole run, as the engine saw them after each step:
/// what a scene's description claims of them ("none inside another", "the rod stays within a
/// millimetre", "asleep by 3 s").
struct PipelineFigures {
    double deepestOverlap = 0.0;          ///< m, of two bodies in touch (0 if none overlapped)
    double deepestAt = 0.0;               ///< s
    std::optional<double> asleepFrom;     ///< every moving rigid body asleep from then to the end
    double widestJoint = 0.0;             ///< m: a ball, hinge or fixed joint's two points apart, or a rod's length off
    double widestAt = 0.0;                ///< s
    std::optional<std::size_t> widest;    ///< which joint
};

class RigidWatch {
public:
    explicit RigidWatch(const World& world);
    bool active() const { return !m_tracks.empty(); }

    /// Call after every step.
    void record(const World& world);
    /// One per rigid body that is not fixed, in the world's order.
    std::vector<RigidFigures> bodies(const World& world) const;
    const PipelineFigures& pipeline() const { return m_pipeline; }

private:
    void lookAtPipeline(const World& world, const std::vector<World::ContactPointView>& contacts);
    PipelineFigures m_pipeline;
    struct Track {
        std::size_t body = 0;
        RigidFigures figures;
        int middleAxis = -1;     ///< the body-frame axis of intermediate inertia; -1 if none
        double lastMiddle = 0.0; ///< the last nonzero angular velocity about it
        double lastMiddleAt = 0.0; ///< the time it was seen
        double energy0 = 0.0, momentum0 = 0.0, spinSum = 0.0;
        dvec3 startUp{0.0};      ///< up at the start, in the body's frame; zero for a sphere
        dvec3 start{0.0};        ///< its centre at the start
        bool hung = false;       ///< joined to the world and to no other body: its highs are recorded
        double lastRise = 0.0, lastRiseAt = 0.0; ///< its last nonzero upward speed and when
        long steps = 0;
        /// The slide going on: its surface (a world index, or kRoom) and its speed's sums for
        /// the least-squares slope, times from its start.
        struct Sliding {
            std::size_t on = 0;
            double from = 0.0, to = 0.0;
            double n = 0.0, st = 0.0, sv = 0.0, stt = 0.0, stv = 0.0;
        };
        std::optional<Sliding> sliding;
    };
    void look(const World& world, Track& t, const Touch& touch) const;
    static void endSlide(const World& world, Track& t);
    std::vector<Track> m_tracks;
    /// The last step's contact points and what each body touches: kept from look to look, since
    /// a heap asleep keeps its thousands of points and allocating them each step cost more than
    /// its step.
    std::vector<World::ContactPointView> m_contacts;
    std::vector<Touch> m_on;
};

} // namespace pba::study
