// The rotations' own steps: the implicit gyroscopic step and the splitting's free flow (the
// templates that use them are in pba/detail/rigid_step.hpp).
#include "pba/rotation.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace pba {

void implicitGyroscopicStep(Rotation& s, const dmat3& inertiaBody, const dmat3& inverseInertiaBody,
                            const dvec3& torqueWorld, double dt)
{
    const dmat3 r = glm::mat3_cast(s.orientation);
    const dmat3 rt = glm::transpose(r);
    const dvec3 l = s.momentum + torqueWorld * dt;
    const dvec3 w0 = inverseInertiaBody * (rt * l); // body frame
    const dvec3 iw = inertiaBody * w0;
    const dvec3 f = dt * glm::cross(w0, iw);
    // J = I + dt (skew(w) I - skew(I w)), with skew(a) b = a x b.
    auto skew = [](const dvec3& a) { return dmat3(0.0, a.z, -a.y, -a.z, 0.0, a.x, a.y, -a.x, 0.0); };
    const dmat3 j = inertiaBody + dt * (skew(w0) * inertiaBody - skew(iw));
    const dvec3 w1 = w0 - glm::inverse(j) * f;
    // The step's result is the angular velocity (world frame), as Bullet and Box2D keep it: the
    // orientation moves with it, and L is what that velocity is at the new orientation.
    const dvec3 omega = r * w1;
    s.orientation = glm::normalize(s.orientation + orientationRate(s.orientation, omega) * dt);
    const dmat3 r1 = glm::mat3_cast(s.orientation);
    s.momentum = r1 * (inertiaBody * (glm::transpose(r1) * omega));
}

namespace {

/// The principal axes (unit, body frame) and moments of a symmetric inertia tensor.
struct Principal {
    std::array<dvec3, 3> axes;
    std::array<double, 3> moments;
};

/// Cyclic Jacobi rotations until the off-diagonal part is gone to rounding: a few sweeps for a
/// 3 x 3 matrix. A tensor diagonal already (every built-in shape's) is taken as it is.
Principal principalAxes(const dmat3& inertia)
{
    dmat3 a = inertia;
    dmat3 v(1.0);
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        const double scale = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (!(off > 1e-32 * scale))
            break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (a[p][q] == 0.0)
                    continue;
                const double theta = 0.5 * std::atan2(2.0 * a[p][q], a[q][q] - a[p][p]);
                const double c = std::cos(theta), s = std::sin(theta);
                dmat3 rot(1.0); // columns p and q turned by theta
                rot[p][p] = c;
                rot[q][q] = c;
                rot[q][p] = s;
                rot[p][q] = -s;
                a = glm::transpose(rot) * a * rot;
                v = v * rot;
            }
    }
    return {{v[0], v[1], v[2]}, {a[0][0], a[1][1], a[2][2]}};
}

/// The exact flow of T_i = L_i^2 / (2 I_i) over h: a turn about principal axis `axis` (body frame)
/// by h L_i / I_i, with L_i = L . (that axis in the world), which the turn leaves as it is.
dquat turnAbout(const dquat& q, const dvec3& momentum, const dvec3& axis, double moment, double h)
{
    const double angle = h * glm::dot(q * axis, momentum) / moment;
    return q * dquat(std::cos(0.5 * angle), axis * std::sin(0.5 * angle));
}

} // namespace

dquat freeRotation(const dquat& q, const dvec3& momentum, const dmat3& inertiaBody, double dt)
{
    const Principal p = principalAxes(inertiaBody);
    // Any order of the three flows gives a symmetric, symplectic second-order method; the order
    // sets the error's constant. The smallest moment's flow (the fastest turn) outermost and the
    // largest moment's whole in the middle keeps the energy best of the six orders on the tennis
    // racket (docs/compare.md gives the numbers).
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return p.moments[a] < p.moments[b]; });
    const auto [a, b, c] = order;
    dquat turned = turnAbout(q, momentum, p.axes[a], p.moments[a], 0.5 * dt);
    turned = turnAbout(turned, momentum, p.axes[b], p.moments[b], 0.5 * dt);
    turned = turnAbout(turned, momentum, p.axes[c], p.moments[c], dt);
    turned = turnAbout(turned, momentum, p.axes[b], p.moments[b], 0.5 * dt);
    turned = turnAbout(turned, momentum, p.axes[a], p.moments[a], 0.5 * dt);
    return glm::normalize(turned);
}

} // namespace pba
