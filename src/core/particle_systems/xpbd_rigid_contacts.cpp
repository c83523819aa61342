#include "particle_systems/xpbd_rigid_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "pba/rigid_body.hpp"
#include "material_rule.hpp"
#include "rigid/solver_body.hpp"
#include "balls/spatial_hash.hpp"

namespace pba::detail {

dvec3 XpbdRigidContacts::Body::spin() const
{
    const dmat3 r = glm::mat3_cast(q);
    return r * (inverseInertiaBody * (glm::transpose(r) * momentum));
}

void XpbdRigidContacts::begin(std::span<const std::pair<std::size_t, const RigidBody*>> bodies,
                              const Members& members, std::span<const Joint> joints, double dt)
{
    m_bodies.clear();
    m_joined.clear();
    m_held.clear();
    m_radius = members.radius;
    m_mass = members.mass;
    m_friction = members.friction;
    m_restitution = members.restitution;
    // The members' box, grown by how far a member may go in the step.
    dvec3 lo(INFINITY), hi(-INFINITY);
    double reach = 0.0;
    for (std::size_t p = 0; p < members.x.size(); ++p) {
        if (!(members.radius[p] > 0.0))
            continue;
        lo = glm::min(lo, members.x[p]);
        hi = glm::max(hi, members.x[p]);
        reach = std::max(reach, members.radius[p] + glm::length(members.v[p]) * dt);
    }
    const auto isJoined = [&](std::size_t world) {
        return std::any_of(joints.begin(), joints.end(), [&](const Joint& j) { return j.body == world; });
    };
    for (const auto& [world, b] : bodies) {
        const bool moving = !b->isFixed();
        Body body;
        body.world = world;
        body.shape = b->getCollisionShape().get();
        body.x = b->getPos();
        body.q = b->getOrientation();
        if (moving) {
            body.v = b->getVel();
            body.accel = b->getAcc();
            body.momentum = b->getAngularMomentum();
            body.inverseMass = 1.0 / b->getMass();
            body.inverseInertiaBody = b->getInverseInertiaBody();
        }
        body.friction = b->getFriction();
        body.restitution = b->getCor();
        body.reach = b->getBoundingRadius();
        const double travel = glm::length(body.v) * dt + glm::length(body.accel) * dt * dt;
        const dvec3 nearest = glm::clamp(body.x, lo, hi);
        if ((reach > 0.0 && glm::length(body.x - nearest) <= body.reach + travel + reach) || isJoined(world))
            m_bodies.push_back(body);
    }
    if (m_bodies.empty())
        return;
    sortBodies();
    m_pushes.resize(members.x.size());
    m_touch.assign(members.x.size(), Touch{});
    for (auto& pushes : m_pushes) // (emptied by each react, but for a step a blow-up cut short)
        pushes.clear();
    for (const Joint& j : joints) { // (a few joints: a line through the members each)
        const auto p = std::find(members.world.begin(), members.world.end(), j.particle);
        const auto k = std::find_if(m_bodies.begin(), m_bodies.end(), [&](const Body& b) { return b.world == j.body; });
        if (p == members.world.end() || k == m_bodies.end())
            continue;
        const Held held{std::uint32_t(p - members.world.begin()), std::uint32_t(k - m_bodies.begin()), j};
        m_held.push_back(held);
        if (!j.collide)
            m_joined.emplace_back(held.member, held.body);
    }
    std::sort(m_joined.begin(), m_joined.end());
    std::stable_sort(m_held.begin(), m_held.end(), [](const Held& a, const Held& b) { return a.member < b.member; });
}

void XpbdRigidContacts::SphereGrid::build(double cell, std::span<const Sphere> spheres)
{
    m_cell = cell;
    const std::uint32_t buckets = detail::bucketsFor(2 * 8 * spheres.size());
    m_mask = buckets - 1;
    // A counting sort, the spheres taken in order: each bucket's list is in body order, and a
    // body two of whose cells share a bucket is listed there once.
    const auto forEachBucket = [&](const Sphere& s, auto&& f) {
        std::int64_t lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = detail::cellIndex(s.centre[a] - s.radius, m_cell);
            hi[a] = detail::cellIndex(s.centre[a] + s.radius, m_cell);
        }
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
            for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
                for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
                    f(detail::bucketOf({x, y, z}, m_mask));
    };
    constexpr std::uint32_t kNobody = 0xffffffffu;
    m_start.assign(buckets + 1, 0);
    m_last.assign(buckets, kNobody);
    for (const Sphere& s : spheres)
        forEachBucket(s, [&](std::uint32_t b) {
            if (m_last[b] != s.body) {
                m_last[b] = s.body;
                ++m_start[b + 1];
            }
        });
    for (std::uint32_t b = 0; b < buckets; ++b)
        m_start[b + 1] += m_start[b];
    m_bodies.resize(m_start[buckets]);
    m_last.assign(buckets, kNobody);
    std::vector<std::uint32_t>& fill = m_fill;
    fill.assign(m_start.begin(), m_start.end() - 1);
    for (const Sphere& s : spheres)
        forEachBucket(s, [&](std::uint32_t b) {
            if (m_last[b] != s.body) {
                m_last[b] = s.body;
                m_bodies[fill[b]++] = s.body;
            }
        });
}

std::span<const std::uint32_t> XpbdRigidContacts::SphereGrid::near(const dvec3& x) const
{
    if (m_bodies.empty())
        return {};
    const std::uint32_t b = detail::bucketOf(detail::cellOf(x, m_cell), m_mask);
    return std::span(m_bodies).subspan(m_start[b], m_start[b + 1] - m_start[b]);
}

void XpbdRigidContacts::sortBodies()
{
    m_always.clear();
    m_moving.clear();
    m_fixedGrid.clear();
    m_movingGrid.clear();
    // A member at x meets body k only if |x - k's centre| <= its radius + k's reach: a body is
    // listed in every cell its sphere of that size overlaps (and a radius more, for a member that
    // an earlier body of the same substep put back out of it), cells as wide as the median
    // sphere's radius (finer cells hand a member fewer bodies to test, at more cells a body).
    constexpr std::size_t kFew = 8;
    if (m_bodies.size() <= kFew) {
        for (std::size_t k = 0; k < m_bodies.size(); ++k)
            m_always.push_back(std::uint32_t(k));
        return;
    }
    double largestRadius = 0.0;
    for (const double r : m_radius)
        largestRadius = std::max(largestRadius, r);
    m_margin = 2.0 * largestRadius;
    std::vector<double> reach;
    for (const Body& b : m_bodies)
        reach.push_back(b.reach + m_margin);
    std::nth_element(reach.begin(), reach.begin() + std::ptrdiff_t(reach.size() / 2), reach.end());
    m_cell = std::max(reach[reach.size() / 2], 1e-9);
    m_spheres.clear();
    for (std::size_t k = 0; k < m_bodies.size(); ++k) {
        const Body& b = m_bodies[k];
        const double r = b.reach + m_margin;
        if (r > 2.0 * m_cell) // over five cells wide
            m_always.push_back(std::uint32_t(k));
        else if (b.inverseMass != 0.0)
            m_moving.push_back(std::uint32_t(k));
        else
            m_spheres.push_back({std::uint32_t(k), b.x, r});
    }
    m_fixedGrid.build(m_cell, m_spheres); // (the moving ones: in each substep's advance)
}

void XpbdRigidContacts::gridMovingBodies()
{
    if (m_moving.empty())
        return;
    m_spheres.clear();
    for (const std::uint32_t k : m_moving)
        m_spheres.push_back({k, m_bodies[k].x, m_bodies[k].reach + m_margin});
    m_movingGrid.build(m_cell, m_spheres);
}

template <class F>
void XpbdRigidContacts::forEachNear(const dvec3& x, F&& f) const
{
    // Three lists, each in increasing order, merged.
    std::span<const std::uint32_t> lists[3] = {m_always, m_fixedGrid.near(x), m_movingGrid.near(x)};
    std::size_t at[3] = {0, 0, 0};
    for (;;) {
        int next = -1;
        for (int l = 0; l < 3; ++l)
            if (at[l] < lists[l].size() && (next < 0 || lists[l][at[l]] < lists[next][at[next]]))
                next = l;
        if (next < 0)
            return;
        f(lists[next][at[next]++]);
    }
}

void XpbdRigidContacts::advance(double h)
{
    m_h = h;
    for (Held& held : m_held)
        held.lambda = 0.0;
    for (Body& b : m_bodies) {
        if (b.inverseMass == 0.0)
            continue;
        b.v += b.accel * h;
        b.x += b.v * h;
        b.q = rigid::turned(b.q, b.spin() * h);
    }
    gridMovingBodies();
}

void XpbdRigidContacts::hold(std::span<dvec3> x, std::span<const dvec3> start)
{
    for (Held& held : m_held) {
        const Joint& j = held.joint;
        Body& b = m_bodies[held.body];
        const std::uint32_t member = held.member;
        const dmat3 turn = glm::mat3_cast(b.q);
        const dvec3 arm = turn * j.local;
        const dvec3 d = (x[member] + j.offset) - (b.x + arm);
        const double distance = glm::length(d);
        if (!(distance > 0.0))
            continue; // held exactly, or no line to hold it along
        const dvec3 n = d / distance;
        const dmat3 inverseInertia = turn * b.inverseInertiaBody * glm::transpose(turn);
        const double wBody = b.inverseMass + glm::dot(glm::cross(arm, n), inverseInertia * glm::cross(arm, n));
        const double wMember = 1.0 / m_mass[member];
        // A spring as XPBD's (xpbd.hpp): compliance 1 / (k h^2), its damping over the two points'
        // moves in the substep, and its multiplier kept over the sweeps.
        double error = distance - j.length, compliance = 0.0, gamma = 0.0;
        if (j.stiffness > 0.0) {
            compliance = 1.0 / (j.stiffness * m_h * m_h);
            gamma = j.damping / (j.stiffness * m_h);
            const dvec3 bodyMoved = (b.v + glm::cross(b.spin(), arm)) * m_h;
            error += gamma * glm::dot(n, (x[member] - start[member]) - bodyMoved) - compliance * held.lambda;
        }
        const double change = error / ((1.0 + gamma) * (wMember + wBody) + compliance);
        held.lambda += change;
        const dvec3 p = change * n; // towards the member, kg m
        x[member] -= wMember * p;
        if (b.inverseMass == 0.0)
            continue;
        // The body's share of the move, and the velocity and spin that make it over the substep.
        const dvec3 impulse = p / m_h, moment = glm::cross(arm, p) / m_h;
        b.x += b.inverseMass * p;
        b.q = rigid::turned(b.q, inverseInertia * glm::cross(arm, p));
        b.v += b.inverseMass * impulse;
        b.momentum += moment;
        b.impulse += impulse;
        b.moment += moment;
    }
    if (!m_held.empty())
        gridMovingBodies(); // (where the joints moved them)
}

void XpbdRigidContacts::keepOut(std::size_t p, const dvec3& start, dvec3& x)
{
    const double r = m_radius[p];
    if (!(r > 0.0))
        return;
    m_touch[p] = Touch{};
    contact::CollisionShape ball;
    ball.radius = r;
    forEachNear(x, [&](std::uint32_t k) {
        const Body& b = m_bodies[k];
        if (!(glm::length(x - b.x) <= r + b.reach) || // (false for a member blown up: the step's checks name it)
            std::binary_search(m_joined.begin(), m_joined.end(), std::pair(std::uint32_t(p), k)))
            return;
        const contact::Transform at{b.x, glm::mat3_cast(b.q)};
        const contact::Manifold m = contact::collide(ball, contact::Transform{x, dmat3(1.0)}, *b.shape, at, 0.0);
        double depth = 0.0;
        for (int i = 0; i < m.count; ++i)
            depth = std::max(depth, -m.points[std::size_t(i)].separation);
        if (!(depth > 0.0))
            return;
        // Back on the surface (the normal points from the ball into the body), and its move along
        // it relative to the body's surface in the substep cut by up to mu times the depth.
        const dvec3 before = x;
        x -= depth * m.normal;
        const dvec3 arm = x + r * m.normal - b.x;
        const dvec3 moved = (x - start) - (b.v + glm::cross(b.spin(), arm)) * m_h;
        x -= heldBack(moved, m.normal, detail::combinedFriction(m_friction[p], b.friction), depth);
        // The body gave the member m dx / h: it takes the opposite, at the contact point.
        const dvec3 impulse = -m_mass[p] * (x - before) / m_h;
        m_pushes[p].push_back({std::uint32_t(k), impulse, glm::cross(arm, impulse)});
        m_touch[p] = {k, m.normal, arm};
    });
}

bool XpbdRigidContacts::bounce(std::size_t p, const dvec3& arriving, double resting, dvec3& v)
{
    const Touch t = m_touch.empty() ? Touch{} : m_touch[p];
    if (t.body == kNone)
        return false;
    const Body& b = m_bodies[t.body];
    const dvec3 surface = b.v + glm::cross(b.spin(), t.arm); // the body's point, this substep
    const double arrival = glm::dot(t.normal, arriving - surface);
    if (!(arrival > resting))
        return false;
    const double e = detail::combinedRestitution(m_restitution[p], b.restitution);
    const dvec3 change = (-e * arrival - glm::dot(t.normal, v - surface)) * t.normal;
    v += change;
    const dvec3 impulse = -m_mass[p] * change;
    m_pushes[p].push_back({t.body, impulse, glm::cross(t.arm, impulse)});
    return true;
}

void XpbdRigidContacts::react()
{
    // Member by member, in order: the same sums on any number of threads.
    for (auto& pushes : m_pushes) {
        for (const Push& push : pushes) {
            Body& b = m_bodies[push.body];
            if (b.inverseMass == 0.0)
                continue;
            b.v += push.impulse * b.inverseMass;
            b.momentum += push.moment;
            b.impulse += push.impulse;
            b.moment += push.moment;
        }
        pushes.clear();
    }
}

std::vector<XpbdRigidContacts::Reaction> XpbdRigidContacts::reactions() const
{
    std::vector<Reaction> out;
    for (const Body& b : m_bodies)
        if (b.inverseMass != 0.0 && (b.impulse != dvec3(0.0) || b.moment != dvec3(0.0)))
            out.push_back({b.world, b.impulse, b.moment});
    return out;
}

} // namespace pba::detail
