#include "study/rigid_watch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pba/rigid_body.hpp"
#include "study/rotation_study.hpp"

namespace pba::study {

namespace {

const RigidBody& rigid(const World& world, std::size_t i)
{
    return static_cast<const RigidBody&>(world.body(i));
}

/// The body-frame axis of intermediate inertia (intermediateAxisOf), when the body frame is the
/// principal one (a box's, a cylinder's; a mesh's need not be); otherwise -1, as for a cube or a
/// sphere: no axis about which a spin is unstable.
int middleAxisOf(const dmat3& inertia)
{
    const double largest = std::max({inertia[0][0], inertia[1][1], inertia[2][2]});
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (r != c && std::abs(inertia[c][r]) > 1e-12 * largest)
                return -1;
    return intermediateAxisOf(inertia);
}

/// The speed at which a sphere's point nearest a surface it touches slips along that surface,
/// or nothing when it touches none: a room's surface within 0.1 mm, not over a hole, or else the
/// one fixed body it touches (a ball rolling on a table).
std::optional<double> sphereSlip(const World& world, const RigidBody& ball, const Touch& touch)
{
    const double r = ball.getShape().radius;
    const dvec3 x = ball.getPos(), w = ball.getAngularVelocity();
    const auto slip = [&](const dvec3& n) { // n: out of the surface, towards the centre
        // A ball that does not move along the surface (one bouncing straight up) is not rolling.
        const dvec3 v = ball.getVel();
        if (glm::length(v - glm::dot(v, n) * n) < kStill)
            return double(INFINITY);
        const dvec3 contact = v + glm::cross(w, -r * n);
        return glm::length(contact - glm::dot(contact, n) * n);
    };
    for (const Plane& plane : world.planes()) {
        if (plane.distance(x) - r > 1e-4 || (plane.holeRadius > 0.0 && plane.overHole(x)))
            continue;
        return slip(plane.normal);
    }
    if (touch.on < world.bodyCount() && world.body(touch.on).isFixed() && glm::length(touch.outward) > 0.0)
        return slip(glm::normalize(touch.outward));
    return std::nullopt;
}

/// The face a box lies on: the outward normal in its own frame that points most nearly along
/// gravity, and the angle between them in degrees.
std::pair<std::string, double> faceDown(const RigidBody& box, const dvec3& gravity)
{
    const dvec3 down = glm::transpose(glm::mat3_cast(box.getOrientation())) * glm::normalize(gravity);
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(down[k]) > std::abs(down[axis]))
            axis = k;
    const std::string face = std::string(down[axis] > 0.0 ? "+" : "-") + "xyz"[axis];
    const double pi = std::acos(-1.0);
    return {face, std::acos(std::min(std::abs(down[axis]), 1.0)) * 180.0 / pi};
}

/// Up: against gravity (+y in zero g, where the figures that need an up are not kept).
dvec3 upOf(const World& world)
{
    const dvec3 g = world.gravity();
    return glm::length(g) > 0.0 ? -glm::normalize(g) : dvec3(0.0, 1.0, 0.0);
}

/// The time between two samples where the straight line through their values crosses zero.
double crossing(double before, double beforeAt, double now, double nowAt)
{
    return beforeAt + (nowAt - beforeAt) * before / (before - now);
}

} // namespace

RigidWatch::RigidWatch(const World& world)
{
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        if (!world.isRigid(i) || world.body(i).isFixed()) // a fixed body has nothing to tell
            continue;
        const RigidBody& body = rigid(world, i);
        Track t;
        t.body = i;
        t.figures.name = body.getName();
        t.middleAxis = middleAxisOf(body.getInertiaBody());
        t.energy0 = body.getRotationalKineticEnergy();
        t.momentum0 = glm::length(body.getAngularMomentum());
        if (!(t.energy0 > 0.0 && t.momentum0 > 0.0))
            t.figures.energyDrift = t.figures.momentumDrift = std::numeric_limits<double>::quiet_NaN();
        t.start = body.getPos();
        const bool weighed = glm::length(world.gravity()) > 0.0; // in zero g nothing is up
        if (weighed && body.getShape().type != ShapeType::Sphere) {
            t.startUp = glm::transpose(glm::mat3_cast(body.getOrientation())) * upOf(world);
            t.figures.largestTilt = 0.0;
        }
        // Hung from the world alone (a pendulum's bob, a cradle's ball): its highs are its swing's.
        bool toOthers = false;
        for (std::size_t j = 0; j < world.jointCount(); ++j) {
            const JointFrame frame = world.jointFrame(j);
            t.hung = t.hung || (frame.bodyA == i && !frame.bodyB);
            toOthers = toOthers || (frame.bodyB && (frame.bodyA == i || *frame.bodyB == i));
        }
        t.hung = weighed && t.hung && !toOthers;
        look(world, t, Touch{});
        m_tracks.push_back(t);
    }
}

namespace {

/// touchedSurfaces, with the normal of a contact with what each body touches, into `on`.
void touches(const World& world, const std::vector<World::ContactPointView>& contacts, std::vector<Touch>& on)
{
    on.assign(world.bodyCount(), Touch{});
    const auto add = [&](std::size_t body, std::size_t other, const dvec3& outward) {
        on[body].on = on[body].on == kNone || on[body].on == other ? other : kMany;
        on[body].outward = outward;
    };
    for (const World::ContactPointView& c : contacts) { // the normal runs from A into B
        add(c.bodyA, c.bodyB.value_or(kRoom), -c.normal);
        if (c.bodyB)
            add(*c.bodyB, c.bodyA, c.normal);
    }
}

} // namespace

std::vector<std::size_t> touchedSurfaces(const World& world)
{
    std::vector<Touch> touch;
    touches(world, world.contactPoints(), touch);
    std::vector<std::size_t> on;
    for (const Touch& t : touch)
        on.push_back(t.on);
    return on;
}

void RigidWatch::lookAtPipeline(const World& world, const std::vector<World::ContactPointView>& contacts)
{
    const double now = world.time();
    for (const World::ContactPointView& c : contacts) {
        // The engine's own contact points: a pair's separation below zero is an overlap.
        const double overlap = -c.separation;
        if (c.bodyB && overlap > m_pipeline.deepestOverlap)
            m_pipeline.deepestOverlap = overlap, m_pipeline.deepestAt = now;
    }
    bool asleep = true;
    for (const Track& t : m_tracks)
        asleep = asleep && world.isAsleep(t.body);
    if (!asleep)
        m_pipeline.asleepFrom.reset();
    else if (!m_pipeline.asleepFrom)
        m_pipeline.asleepFrom = now;
    for (std::size_t j = 0; j < world.jointCount(); ++j) {
        const JointFrame frame = world.jointFrame(j);
        double gap = glm::length(frame.onB - frame.onA);
        if (frame.type == JointType::Distance) {
            if (frame.stiffness > 0.0) // a spring: its stretch is its own
                continue;
            gap = std::abs(gap - frame.length);
        }
        if (gap > m_pipeline.widestJoint)
            m_pipeline.widestJoint = gap, m_pipeline.widestAt = now, m_pipeline.widest = j;
    }
}

void RigidWatch::record(const World& world)
{
    world.contactPoints(m_contacts);
    lookAtPipeline(world, m_contacts);
    touches(world, m_contacts, m_on);
    for (Track& t : m_tracks) {
        look(world, t, m_on[t.body]);
        t.spinSum += glm::length(rigid(world, t.body).getAngularVelocity());
        ++t.steps;
    }
}

void RigidWatch::endSlide(const World& world, Track& t)
{
    if (!t.sliding)
        return;
    const Track::Sliding& s = *t.sliding;
    RigidFigures& f = t.figures;
    const double denominator = s.n * s.stt - s.st * s.st;
    const double distance = s.n > 0.0 ? s.sv / s.n * (s.to - s.from) : 0.0; // its mean speed over the stretch
    if (s.to - s.from >= RigidFigures::kLeastSlide && distance >= RigidFigures::kLeastSlideDistance &&
        denominator > 0.0 &&
        (!f.slide || s.to - s.from > f.slide->to - f.slide->from))
        f.slide = RigidFigures::Slide{s.on != kRoom ? world.body(s.on).getName() : world.room() ? "the room" : "the ground", s.from, s.to,
                                      (s.n * s.stv - s.st * s.sv) / denominator};
    t.sliding.reset();
}

void RigidWatch::look(const World& world, Track& t, const Touch& touch) const
{
    const std::size_t surface = touch.on; // what it touches
    const RigidBody& body = rigid(world, t.body);
    RigidFigures& f = t.figures;
    const double now = world.time();
    const dvec3 w = body.getAngularVelocity();
    const double speed = glm::length(body.getVel());
    const bool still = speed < kStill && glm::length(w) < kStill;
    // Sliding: on one surface that does not move, moving without turning (a box down a ramp).
    constexpr double kNoTurn = 1e-3; // rad/s
    const bool onFixed = surface == kRoom || (surface < world.bodyCount() && world.body(surface).isFixed());
    const bool slides = onFixed && speed >= kStill && glm::length(w) < kNoTurn;
    if (t.sliding && (!slides || t.sliding->on != surface))
        endSlide(world, t);
    if (slides) {
        if (!t.sliding)
            t.sliding = Track::Sliding{surface, now, now};
        Track::Sliding& s = *t.sliding;
        const double at = now - s.from;
        s.to = now;
        s.n += 1.0, s.st += at, s.sv += speed, s.stt += at * at, s.stv += at * speed;
    }
    if (!still)
        f.stillFrom.reset();
    else if (!f.stillFrom)
        f.stillFrom = now;
    if (body.getShape().type == ShapeType::Sphere && !f.rollingFrom && !still) {
        if (const auto slip = sphereSlip(world, body, touch); slip && *slip < kNoSlip) {
            f.rollingFrom = now;
            f.rollingSpeed = glm::length(body.getVel());
        }
    }
    if (t.middleAxis >= 0) {
        const double middle = (glm::transpose(glm::mat3_cast(body.getOrientation())) * w)[t.middleAxis];
        // The crossing between the samples, not the step after it: a flip's time to a small
        // fraction of dt rather than to dt (the sign changes once in a step, at the scenes' dt).
        if (middle * t.lastMiddle < 0.0)
            f.flips.push_back(crossing(t.lastMiddle, t.lastMiddleAt, middle, now));
        if (middle != 0.0)
            t.lastMiddle = middle, t.lastMiddleAt = now;
    }
    const dvec3 up = upOf(world);
    if (f.largestTilt) {
        const double cosine = glm::dot(glm::mat3_cast(body.getOrientation()) * t.startUp, up);
        f.largestTilt = std::max(*f.largestTilt, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::acos(-1.0));
        if (*f.largestTilt > 45.0 && !f.tippedAt)
            f.tippedAt = now;
    }
    if (t.hung) {
        // A turning point between a rise and a fall each faster than still: a body at rest whose
        // speed's rounding changes sign has none.
        const double rise = glm::dot(body.getVel(), up);
        if (t.lastRise >= kStill && rise <= -kStill)
            f.highs.push_back(crossing(t.lastRise, t.lastRiseAt, rise, now));
        if (std::abs(rise) >= kStill)
            t.lastRise = rise, t.lastRiseAt = now;
    }
    // NaN (and so never "free") for a body that started without a spin: no ratio to keep.
    f.energyDrift = std::max(f.energyDrift, std::abs(body.getRotationalKineticEnergy() / t.energy0 - 1.0));
    f.momentumDrift = std::max(f.momentumDrift, std::abs(glm::length(body.getAngularMomentum()) / t.momentum0 - 1.0));
}

std::vector<RigidFigures> RigidWatch::bodies(const World& world) const
{
    std::vector<RigidFigures> out;
    for (Track t : m_tracks) {
        endSlide(world, t); // a slide that lasts to the end of the run
        RigidFigures f = t.figures;
        f.meanSpin = t.steps > 0 ? t.spinSum / double(t.steps) : 0.0;
        const RigidBody& body = rigid(world, t.body);
        f.fromStart = glm::length(body.getPos() - t.start);
        if (f.stillFrom && body.getShape().type == ShapeType::Box && glm::length(world.gravity()) > 0.0)
            std::tie(f.restingFace, f.tilt) = faceDown(body, world.gravity());
        out.push_back(std::move(f));
    }
    return out;
}

} // namespace pba::study
