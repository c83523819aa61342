#include "particle_systems/xpbd.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "surfaces/collision_rules.hpp"
#include "parallel.hpp"

namespace pba::detail {

Xpbd::Xpbd(const SpringSystem& springs)
{
    // Greedy colouring: each spring takes the lowest colour neither of its (moving) ends has yet.
    std::vector<std::vector<std::uint32_t>> used(springs.bodies());
    std::vector<std::uint32_t> colour(springs.size());
    std::uint32_t count = 0;
    for (std::size_t s = 0; s < springs.size(); ++s) {
        const std::uint32_t a = springs.a(s), b = springs.b(s);
        auto taken = [&](std::uint32_t c) {
            const auto has = [c](const std::vector<std::uint32_t>& list) {
                return std::find(list.begin(), list.end(), c) != list.end();
            };
            return has(used[a]) || (b != SpringSystem::kFixed && has(used[b]));
        };
        std::uint32_t c = 0;
        while (taken(c))
            ++c;
        colour[s] = c;
        used[a].push_back(c);
        if (b != SpringSystem::kFixed)
            used[b].push_back(c);
        count = std::max(count, c + 1);
    }
    m_colourStart.assign(count + 1, 0);
    for (const std::uint32_t c : colour)
        ++m_colourStart[c + 1];
    for (std::uint32_t c = 0; c < count; ++c)
        m_colourStart[c + 1] += m_colourStart[c];
    // A spring of no stiffness is no constraint: marked by a negative compliance, and skipped.
    m_constraints.resize(springs.size());
    std::vector<std::uint32_t> next(m_colourStart.begin(), m_colourStart.end() - 1);
    for (std::size_t s = 0; s < springs.size(); ++s) {
        const double k = springs.stiffness(s);
        m_constraints[next[colour[s]]++] = Constraint{springs.a(s), springs.b(s), static_cast<std::uint32_t>(s),
                                                      springs.restLength(s), k > 0.0 ? 1.0 / k : -1.0,
                                                      k > 0.0 ? springs.damping(s) / k : 0.0};
    }
}

void Xpbd::step(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x, std::span<dvec3> v,
                double dt, int substeps, const External& external, const Room& room)
{
    const std::size_t n = x.size();
    const double h = dt / double(substeps);
    m_start.resize(n);
    m_accel.resize(n);
    // The projections depend on h and the masses alone: made again only when one changed.
    bool changed = m_inverseMass.size() != n || !(h == m_scaledFor);
    m_inverseMass.resize(n);
    for (std::size_t p = 0; p < n; ++p) {
        const double w = 1.0 / mass[p];
        changed = changed || !(w == m_inverseMass[p]);
        m_inverseMass[p] = w;
    }
    if (changed)
        scale(h);
    m_scaledFor = h;
    const bool inRoom = !room.planes.empty();
    if (inRoom || room.obstacles)
        m_bounces.assign(n, 0);
    else
        m_bounces.clear();
    for (int sub = 0; sub < substeps; ++sub) {
        if (room.obstacles)
            room.obstacles->advance(h);
        external(x, v, m_accel);
        forEachIndex(n, [&](std::size_t p) {
            v[p] += h * m_accel[p];
            m_start[p] = x[p];
            x[p] += h * v[p];
        });
        // The joints to the obstacles are held after each sweep: swept apart, the springs
        // converged on a member as light as itself and the joint then pulled it to a body thirty
        // times heavier, so a box hung on a stiff rope sank as on a soft one.
        if (m_stiffest > kStiff) {
            m_lambda.assign(m_constraints.size(), 0.0);
            for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
                const double error = project<true>(springs, x);
                if (room.obstacles)
                    room.obstacles->hold(x, m_start);
                if (!(error > kTolerance))
                    break;
            }
        } else {
            project<false>(springs, x);
            if (room.obstacles)
                room.obstacles->hold(x, m_start);
        }
        keepApart(room.touching, x);
        if (room.obstacles)
            forEachIndex(n, [&](std::size_t p) { room.obstacles->keepOut(p, m_start[p], x[p]); });
        if (!inRoom && !room.obstacles) {
            forEachIndex(n, [&](std::size_t p) { v[p] = (x[p] - m_start[p]) / h; });
            continue;
        }
        forEachIndex(n, [&](std::size_t p) {
            const dvec3 arriving = v[p];
            const int plane = inRoom ? keepInRoom(room, p, x[p]) : -1;
            v[p] = (x[p] - m_start[p]) / h;
            if (room.obstacles && room.obstacles->bounce(p, arriving, 2.0 * glm::length(m_accel[p]) * h, v[p]))
                ++m_bounces[p];
            if (plane < 0)
                return;
            // Put back on the surface, it moves along it only: a fast arrival bounces.
            const dvec3 normal = room.planes[std::size_t(plane)].normal;
            const double arrival = -glm::dot(normal, arriving);
            if (arrival > 2.0 * glm::length(m_accel[p]) * h) {
                v[p] += (room.restitution[p] * arrival - glm::dot(normal, v[p])) * normal;
                ++m_bounces[p];
            }
        });
        if (room.obstacles)
            room.obstacles->react();
    }
}

void Xpbd::keepApart(std::span<const Touching> touching, std::span<dvec3> x) const
{
    for (const Touching& t : touching) {
        const double wa = m_inverseMass[t.a], wb = m_inverseMass[t.b];
        const dvec3 d = x[t.b] - x[t.a];
        const double distance = glm::length(d), depth = t.reach - distance;
        if (!(depth > 0.0) || !(distance > 0.0))
            continue;
        const dvec3 n = d / distance;
        x[t.a] -= (depth * wa / (wa + wb)) * n;
        x[t.b] += (depth * wb / (wa + wb)) * n;
        // Their sliding over each other in the substep cut by up to mu times the depth.
        const dvec3 back = heldBack((x[t.b] - m_start[t.b]) - (x[t.a] - m_start[t.a]), n, t.friction, depth);
        x[t.a] += (wa / (wa + wb)) * back;
        x[t.b] -= (wb / (wa + wb)) * back;
    }
}

int Xpbd::keepInRoom(const Room& room, std::size_t p, dvec3& x) const
{
    int touched = -1;
    for (std::size_t k = 0; k < room.planes.size(); ++k) {
        const Plane plane = room.planes[k].inflatedBy(room.radius[p]);
        const double depth = -plane.distance(x);
        if (!(depth > 0.0) || plane.overHole(x) || plane.overHole(m_start[p]))
            continue; // inside, or where a hole leaves no surface: the rule after the step sees to it
        x += depth * plane.normal;
        x -= heldBack(x - m_start[p], plane.normal, room.friction[p], depth);
        touched = int(k);
    }
    return touched;
}

void Xpbd::scale(double h)
{
    m_projections.resize(m_constraints.size());
    m_multipliers.resize(m_constraints.size());
    forEachIndex(m_constraints.size(), [&](std::size_t k) {
        const Constraint& con = m_constraints[k];
        Projection& projection = m_projections[k];
        projection = Projection{con.a, con.b, con.restLength, 0.0, 0.0, 0.0};
        if (con.inverseStiffness < 0.0) {
            m_multipliers[k] = Multiplier{};
            return;
        }
        const double wa = m_inverseMass[con.a], wb = con.b == SpringSystem::kFixed ? 0.0 : m_inverseMass[con.b];
        const double gamma = con.dampingOverStiffness / h;
        const double denominator = (1.0 + gamma) * (wa + wb) + con.inverseStiffness / (h * h); // alpha~ = alpha / h^2
        projection.shareA = wa / denominator;
        projection.shareB = wb / denominator;
        projection.gamma = gamma;
        m_multipliers[k] = Multiplier{con.inverseStiffness / (h * h), 1.0 / denominator};
    });
    m_stiffest = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, m_constraints.size(), kIndexGrain), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double most) {
            for (std::size_t k = r.begin(); k < r.end(); ++k) {
                const Projection& p = m_projections[k];
                const Multiplier& m = m_multipliers[k];
                if (m.compliance > 0.0) // (w_a + w_b) / alpha~ = (w_a + w_b) k h^2
                    most = std::max(most, (p.shareA + p.shareB) / (m.inverseDenominator * m.compliance));
            }
            return most;
        },
        [](double p, double q) { return std::max(p, q); });
}

template <bool kSweeps>
double Xpbd::project(const SpringSystem& springs, std::span<dvec3> x)
{
    const Projection* projections = m_projections.data();
    const Multiplier* multipliers = m_multipliers.data();
    const Constraint* constraints = m_constraints.data();
    const dvec3* start = m_start.data();
    double* lambda = m_lambda.data();
    dvec3* positions = x.data();
    // Projects constraint k, and returns its error relative to its rest length.
    auto projectOne = [&](std::size_t k) {
        const Projection& con = projections[k];
        const bool fixed = con.b == SpringSystem::kFixed;
        const dvec3 xa = positions[con.a];
        const dvec3 xb = fixed ? springs.fixedPoint(constraints[k].spring) : positions[con.b];
        const dvec3 d = xb - xa;
        const double length = glm::length(d);
        if (!(length > 0.0))
            return 0.0; // no direction to pull along
        // The constraint's error C (less alpha~ lambda when sweeping again) and its damping term
        // gamma grad C . (x* - x), along u = d / |d|.
        double error = length - con.restLength;
        if (kSweeps)
            error -= multipliers[k].compliance * lambda[k];
        if (con.gamma != 0.0) {
            const dvec3 moved = (fixed ? dvec3(0.0) : xb - start[con.b]) - (xa - start[con.a]);
            error += con.gamma * glm::dot(d, moved) / length;
        }
        const dvec3 pull = d * (error / length);
        positions[con.a] = xa + con.shareA * pull;
        if (!fixed)
            positions[con.b] = xb - con.shareB * pull;
        if (!kSweeps || !(multipliers[k].inverseDenominator > 0.0))
            return 0.0; // not sweeping again, or no constraint
        lambda[k] += error * multipliers[k].inverseDenominator;
        return std::abs(error) / (con.restLength > 0.0 ? con.restLength : 1.0);
    };
    double largest = 0.0;
    for (std::size_t c = 0; c + 1 < m_colourStart.size(); ++c) {
        const tbb::blocked_range<std::size_t> colour(m_colourStart[c], m_colourStart[c + 1], kIndexGrain);
        if (!kSweeps) {
            tbb::parallel_for(colour, [&](const tbb::blocked_range<std::size_t>& r) {
                for (std::size_t k = r.begin(); k < r.end(); ++k)
                    projectOne(k);
            });
            continue;
        }
        // A sweep's largest error is a maximum, exact in any order: the same on any number of threads.
        largest = std::max(largest, tbb::parallel_reduce(
                                        colour, 0.0,
                                        [&](const tbb::blocked_range<std::size_t>& r, double worst) {
                                            for (std::size_t k = r.begin(); k < r.end(); ++k)
                                                worst = std::max(worst, projectOne(k));
                                            return worst;
                                        },
                                        [](double p, double q) { return std::max(p, q); }));
    }
    return largest;
}

} // namespace pba::detail
