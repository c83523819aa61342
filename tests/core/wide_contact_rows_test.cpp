// A large island's velocity sweeps four contacts at a time (src/core/rigid/wide_contact_rows.hpp)
// against the one-at-a-time sweep in double, written out here, over the same contacts in the
// same order (the wide rows' colours, then those no colour took): the same velocities and
// impulses to single precision. The colouring is held to its promise too: no moving body twice
// in one block of four.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/rigid/wide_contact_rows.hpp"

namespace {

using namespace pba;
using namespace pba::rigid;

struct Island {
    std::vector<SolverBody> bodies;
    std::vector<IslandContact> contacts;
    std::vector<VelocityRows> rows;
};

Jacobian jacobian(const SolverBody& a, const SolverBody& b, const dvec3& ra, const dvec3& rb, const dvec3& u)
{
    const dvec3 ma = glm::cross(ra, u), mb = glm::cross(rb, u);
    const dvec3 ta = a.inverseInertia * ma, tb = b.inverseInertia * mb;
    const double k = a.inverseMass + b.inverseMass + glm::dot(ma, ta) + glm::dot(mb, tb);
    return {glm::vec3(u), glm::vec3(ma), glm::vec3(mb), glm::vec3(ta), glm::vec3(tb), float(1.0 / k)};
}

/// `moving` bodies and the floor (static), `count` contacts of one to four points between random
/// pairs, each point with last step's impulses.
Island randomIsland(unsigned seed, int moving = 60, int count = 300)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.5, 2.0);
    Island island;
    for (int k = 0; k < moving; ++k) {
        SolverBody b;
        b.inverseMass = 1.0 / positive(random);
        b.inverseInertia = dmat3(positive(random), 0.1 * unit(random), 0.0, 0.1 * unit(random), positive(random), 0.0,
                                 0.0, 0.0, positive(random));
        b.inverseInertia = 0.5 * (b.inverseInertia + glm::transpose(b.inverseInertia));
        b.v = dvec3(unit(random), unit(random), unit(random));
        b.w = dvec3(unit(random), unit(random), unit(random));
        island.bodies.push_back(b);
    }
    island.bodies.push_back(SolverBody{}); // the floor
    std::uniform_int_distribution<int> body(0, moving), points(1, 4);
    for (int c = 0; c < count; ++c) {
        int a = body(random), b = body(random);
        if (a == b)
            continue;
        if (a > b)
            std::swap(a, b);
        IslandContact s;
        s.a = BodyIndex(a);
        s.b = BodyIndex(b);
        s.friction = 0.3 + 0.4 * (unit(random) + 1.0) / 2.0;
        s.first = std::uint32_t(island.rows.size());
        s.count = points(random);
        const dvec3 n = glm::normalize(dvec3(unit(random), unit(random), unit(random)));
        const dvec3 t0 = glm::normalize(glm::cross(n, dvec3(0.3, 1.0, 0.2))), t1 = glm::cross(n, t0);
        for (int i = 0; i < s.count; ++i) {
            const dvec3 ra(0.1 * unit(random), 0.1 * unit(random), 0.1 * unit(random));
            const dvec3 rb(0.1 * unit(random), 0.1 * unit(random), 0.1 * unit(random));
            const SolverBody &A = island.bodies[std::size_t(a)], &B = island.bodies[std::size_t(b)];
            VelocityRows r;
            r.along = jacobian(A, B, ra, rb, n);
            r.across[0] = jacobian(A, B, ra, rb, t0);
            r.across[1] = jacobian(A, B, ra, rb, t1);
            r.normalImpulse = 0.05 * (unit(random) + 1.0);
            r.tangentImpulse[0] = 0.01 * unit(random);
            r.tangentImpulse[1] = 0.01 * unit(random);
            r.target = -0.05 * (unit(random) + 1.0);
            island.rows.push_back(r);
        }
        island.contacts.push_back(s);
    }
    return island;
}

double speed(const Jacobian& j, const SolverBody& a, const SolverBody& b)
{
    return glm::dot(dvec3(j.u), b.v - a.v) + glm::dot(dvec3(j.momentB), b.w) - glm::dot(dvec3(j.momentA), a.w);
}

void apply(const Jacobian& j, double lambda, SolverBody& a, SolverBody& b)
{
    a.v -= lambda * a.inverseMass * dvec3(j.u);
    a.w -= lambda * dvec3(j.turnA);
    b.v += lambda * b.inverseMass * dvec3(j.u);
    b.w += lambda * dvec3(j.turnB);
}

/// One contact, as the one-at-a-time sweep solves it: its points' friction, then their normals.
void solveOne(const IslandContact& s, std::vector<VelocityRows>& rows, std::vector<SolverBody>& bodies)
{
    SolverBody &a = bodies[s.a], &b = bodies[s.b];
    for (int i = 0; i < s.count; ++i) {
        VelocityRows& r = rows[s.first + std::uint32_t(i)];
        double want[2];
        for (int k = 0; k < 2; ++k)
            want[k] = r.tangentImpulse[k] - r.across[k].mass * speed(r.across[k], a, b);
        const double length = std::hypot(want[0], want[1]), limit = s.friction * r.normalImpulse;
        const double scale = length > limit ? limit / length : 1.0;
        for (int k = 0; k < 2; ++k) {
            apply(r.across[k], want[k] * scale - r.tangentImpulse[k], a, b);
            r.tangentImpulse[k] = want[k] * scale;
        }
    }
    for (int i = 0; i < s.count; ++i) {
        VelocityRows& r = rows[s.first + std::uint32_t(i)];
        const double next = std::max(r.normalImpulse - r.along.mass * (speed(r.along, a, b) - r.target), 0.0);
        apply(r.along, next - r.normalImpulse, a, b);
        r.normalImpulse = next;
    }
}

TEST(WideContactRows, SweepAsOneContactAtATimeInTheSameOrderToSinglePrecision)
{
    for (unsigned seed = 1; seed <= 5; ++seed) {
        Island wide = randomIsland(seed), one = wide;
        WideContactRows rows;
        std::vector<std::uint32_t> leftOver;
        rows.colour(wide.contacts, wide.bodies);
        rows.build(wide.contacts, wide.rows, wide.bodies, leftOver);
        ASSERT_FALSE(rows.empty());
        std::vector<std::uint32_t> order = rows.order();
        ASSERT_EQ(order.size() % 4, 0u);
        // Four lanes at a time: no moving body twice among them.
        for (std::size_t first = 0; first < order.size(); first += 4) {
            std::vector<BodyIndex> moving;
            for (std::size_t k = first; k < first + 4; ++k) {
                if (order[k] == WideContactRows::kEmptyLane)
                    continue;
                for (const BodyIndex b : {wide.contacts[order[k]].a, wide.contacts[order[k]].b})
                    if (!wide.bodies[b].isStatic())
                        moving.push_back(b);
            }
            std::sort(moving.begin(), moving.end());
            EXPECT_EQ(std::adjacent_find(moving.begin(), moving.end()), moving.end()) << "seed " << seed;
        }
        std::erase(order, WideContactRows::kEmptyLane);
        ASSERT_EQ(order.size() + leftOver.size(), wide.contacts.size());
        for (int sweep = 0; sweep < 10; ++sweep) {
            double change = 0.0, largest = 0.0;
            rows.sweep(wide.bodies, change, largest);
            for (const std::uint32_t c : leftOver)
                solveOne(wide.contacts[c], wide.rows, wide.bodies);
            for (const std::uint32_t c : order)
                solveOne(one.contacts[c], one.rows, one.bodies);
            for (const std::uint32_t c : leftOver)
                solveOne(one.contacts[c], one.rows, one.bodies);
        }
        rows.storeImpulses(wide.rows);
        for (std::size_t k = 0; k < wide.bodies.size(); ++k) {
            EXPECT_LT(glm::length(wide.bodies[k].v - one.bodies[k].v), 1e-4) << "seed " << seed << ", body " << k;
            EXPECT_LT(glm::length(wide.bodies[k].w - one.bodies[k].w), 1e-4) << "seed " << seed << ", body " << k;
        }
        for (std::size_t r = 0; r < wide.rows.size(); ++r)
            EXPECT_NEAR(wide.rows[r].normalImpulse, one.rows[r].normalImpulse, 1e-5) << "seed " << seed << ", row " << r;
    }
}

} // namespace
