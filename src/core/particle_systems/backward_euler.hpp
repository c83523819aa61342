#pragma once
// Backward (implicit) Euler for a system of particles joined by springs (Baraff and Witkin,
// "Large steps in cloth simulation", 1998): with the springs' Jacobians K = df/dx and D = df/dv
// at the start of the step, the velocity change first solves
//     (M - dt D - dt^2 K) dv = dt (f0 + dt K v0),     v1 = v0 + dv,  x1 = x0 + dt v1,
// f0 every force at the start. The springs are implicit, every other force (gravity, drag, the
// blow dryer) explicit: a particle with no spring moves as by semi-implicit Euler. The system is
// solved by conjugate gradients, preconditioned by its 3 x 3 diagonal blocks, from the last
// step's dv, matrix-free: each product runs as the spring network's forces do, a pass over the
// springs and a pass over the bodies that sums each body's springs in their order, on all cores.
// Its dot products are reduced over a fixed tree of blocks, so the result is the same on any
// number of threads.
//
// That once-linearised step holds only while the springs turn little in a step: a rope swinging
// through a large angle in one step moves along its springs' tangents, stretches them, and its
// energy grows (to 131 times the start's on the rope at 100 times semi-implicit Euler's limit).
// So Newton's corrections follow, each linearised at the last one's end, until the nonlinear
// equations M (v1 - v0) = dt f(x0 + dt v1, v1) hold to kNewtonTolerance; at a frame's dt on a
// cloth the first step already does, and no correction is solved. Each correction is a descent
// direction of the step's incremental potential Phi (whose gradient is minus the equations'
// residual; the springs' damping acts along their start directions so that it has a potential),
// and a backtracking line search on Phi keeps each one downhill where a full Newton step is not.
//
// A spring's stiffness block is k (u u^T + g (I - u u^T)) with g = 1 - L / |d|, its geometric
// term, clamped at zero: a compressed spring's would make the matrix indefinite, where conjugate
// gradients fail (Choi and Ko 2002 drop it for the same reason). The matrix is then symmetric
// positive definite for any dt, which is what makes the step stable at any dt: for one undamped
// spring it multiplies the energy by exactly 1 / (1 + omega^2 dt^2) a step.
//
// A member resting on a surface is held on it for the step (Baraff and Witkin's constraints,
// section 5.3): its velocity along the surface's normal ends at zero, and conjugate gradients
// search only along the surface for it (each residual and direction filtered by I - n n^T), so
// the springs pull the rest of the system knowing it cannot sink. Otherwise the solve would pull
// it into the floor every step, and the floor rule after it push it back: a sheet lying on the
// floor chattered, counted as thousands of bounces. A member the surface would have to pull
// (its springs lift it off) is let go, and the step solved again without it.
//
// A surface may be a moving body's that the members' pushes move in turn (a crate resting on a
// cloth: Bearers). A member held on it moves along the normal with the body's point, and the
// body's velocity and spin are solved with the sheet's: the held members' pushes depend linearly
// on the body's six velocities, so the body's six velocities U are unknowns of the same conjugate gradients beside the
// members' (the step's incremental potential gains 1/2 (U - U_alone)^T M (U - U_alone), whose
// least is the body's momentum equation, M (U - U_alone) = -(what the pushes give it)). Met only after the
// step, the body saw each member as a lone ball and the stiff springs a step later: a crate on an
// implicit cloth stretched it to five times the scene's energy for a moment at dt 0.002 s, and
// gained energy beyond 0.003 s.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pba/math.hpp"

#include "particle_systems/spring_system.hpp"

namespace pba::detail {

/// A rigid body's six velocities, linear then angular (or the impulse and moment that pair with them).
struct Twist {
    dvec3 linear{0.0}, angular{0.0};
    Twist operator+(const Twist& o) const { return {linear + o.linear, angular + o.angular}; }
    Twist operator-(const Twist& o) const { return {linear - o.linear, angular - o.angular}; }
    Twist operator*(double k) const { return {linear * k, angular * k}; }
    Twist& operator+=(const Twist& o) { return *this = *this + o; }
};
inline double dot(const Twist& a, const Twist& b) { return glm::dot(a.linear, b.linear) + glm::dot(a.angular, b.angular); }

/// A rigid body's mass and (world) inertia, as the 6 x 6 matrix they make.
struct BodyMass {
    double mass = 0.0;
    dmat3 inertia{0.0};
    Twist times(const Twist& t) const { return {mass * t.linear, inertia * t.angular}; }
};

/// A symmetric 6 x 6 matrix, row-major.
struct Mat6 {
    std::array<double, 36> m{};
    Mat6() = default;
    explicit Mat6(const BodyMass& b)
    {
        for (int i = 0; i < 3; ++i) {
            m[std::size_t(i * 7)] = b.mass;
            for (int j = 0; j < 3; ++j)
                m[std::size_t((3 + i) * 6 + 3 + j)] = b.inertia[j][i];
        }
    }
    /// Adds w s s^T.
    void addOuter(const Twist& s, double w)
    {
        const double v[6] = {s.linear.x, s.linear.y, s.linear.z, s.angular.x, s.angular.y, s.angular.z};
        for (std::size_t i = 0; i < 6; ++i)
            for (std::size_t j = 0; j < 6; ++j)
                m[i * 6 + j] += w * v[i] * v[j];
    }
    Twist times(const Twist& t) const
    {
        const double v[6] = {t.linear.x, t.linear.y, t.linear.z, t.angular.x, t.angular.y, t.angular.z};
        double r[6] = {};
        for (std::size_t i = 0; i < 6; ++i)
            for (std::size_t j = 0; j < 6; ++j)
                r[i] += m[i * 6 + j] * v[j];
        return {{r[0], r[1], r[2]}, {r[3], r[4], r[5]}};
    }
    Mat6 inverse() const;
};

class BackwardEuler {
public:
    /// Conjugate gradients stop when the residual's preconditioned norm falls below this fraction
    /// of the right-hand side's, or after kMaxIterations.
    static constexpr double kTolerance = 1e-5;
    static constexpr int kMaxIterations = 500;
    /// Newton's corrections stop when the nonlinear equations' residual, in the same norm, is
    /// below this fraction of the first right-hand side's, or after kMaxNewtonIterations solves.
    /// Loose on purpose: a crumpled cloth's compressed springs, whose geometric term the matrix
    /// drops, leave the first step a residual of up to 0.48 of it at a frame's dt (the bench's
    /// cloth in the dryer), which Newton would take three more solves to remove; on the rope at
    /// 100 times semi-implicit Euler's limit, where the once-linearised step gains energy, the
    /// first steps' residuals are 17 to 1,900 times it.
    static constexpr double kNewtonTolerance = 0.5;
    static constexpr int kMaxNewtonIterations = 10;
    /// The shortest fraction of a Newton correction the line search tries.
    static constexpr double kSmallestStep = 1.0 / 1024.0;

    /// A moving body that held members rest on (see above), in the world's frame.
    struct Bearer {
        double mass = 0.0;
        dmat3 inertia{0.0};
        /// The body's velocity and spin over the step without the members.
        dvec3 aloneVelocity{0.0}, aloneSpin{0.0};
        /// In: a guess of them with the members (the solve starts from it: its start's); out: them.
        dvec3 velocity{0.0}, spin{0.0};
        bool moves = true; ///< false: the members do not move it within the step (it is a moving surface)
    };
    static constexpr std::uint32_t kNoBearer = 0xffffffffu;
    struct Bearers {
        std::span<const std::uint32_t> of; ///< per member, the bearer it is held on, or kNoBearer
        std::span<const dvec3> arm;        ///< per member held on a bearer: its contact point from the bearer's centre
        std::span<Bearer> bodies;
    };

    /// One step of the system: x and v (one per member, in the springs' member order) from the
    /// start to the end of the step; `force[k]`, the net force on member k at the start (every
    /// force, springs included); `mass[k]` its mass; `heldOn[k]` the unit normal of the surface
    /// member k rests on, which stops it along the normal for the step, or zero (`heldOn`
    /// empty: none rests), or, for a member held on one of `bearers`, moves it along the normal
    /// with that body. `along[k]`, if given, adds a mass that member k carries in some directions
    /// only (a body it is joined to by a rod: along the rod). The springs' fixed ends must be placed.
    void step(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x, std::span<dvec3> v,
              std::span<const dvec3> force, double dt, std::span<const dvec3> heldOn = {},
              const Bearers& bearers = {}, std::span<const dmat3> along = {});

    /// After a step with members held: how much member k's surface pushed it (the change of its
    /// velocity along the normal, m/s, not negative; zero where it was not held or was let go),
    /// for the surface's friction.
    double push(std::size_t k) const { return m_held ? m_push[k] : 0.0; }

    /// The last step's conjugate-gradient iterations (over all its solves), its solves (one, and
    /// one a Newton correction), and the last solve's relative residual.
    int iterations() const { return m_iterations; }
    int newtonIterations() const { return m_newtonIterations; }
    double residual() const { return m_residual; }

private:
    /// A spring's block B = dt^2 K + dt D = alpha I + beta u u^T, applied to w as alpha w + beta (u . w) u.
    struct Block {
        dvec3 u{0.0};
        double alpha = 0.0, beta = 0.0;
        dvec3 apply(const dvec3& w) const { return alpha * w + (beta * glm::dot(u, w)) * u; }
    };
    /// A symmetric 3 x 3 matrix: xx, yy, zz, xy, xz, yz.
    struct Sym3 {
        double xx = 0.0, yy = 0.0, zz = 0.0, xy = 0.0, xz = 0.0, yz = 0.0;
        dvec3 apply(const dvec3& w) const
        {
            return {xx * w.x + xy * w.y + xz * w.z, xy * w.x + yy * w.y + yz * w.z, xz * w.x + yz * w.y + zz * w.z};
        }
    };

    /// One Newton correction of v, unless the equations hold already (then false).
    bool correct(const SpringSystem& springs, std::span<const double> mass, std::span<dvec3> x, std::span<dvec3> v,
                 double dt, double scale);
    /// The step's incremental potential, whose gradient is minus the equations' residual, at v + step m_dv.
    double phi(const SpringSystem& springs, std::span<const double> mass, std::span<const dvec3> v, double dt,
               double step);
    /// Each spring's force on its first end at (x, v), into m_perSpring.
    void springForces(const SpringSystem& springs, std::span<const dvec3> x, std::span<const dvec3> v);
    /// The springs' blocks and the preconditioner, linearised at x. At the start of the step (v0
    /// and f0 given) also Baraff and Witkin's right-hand side dt (f0 + dt K v0) into m_rhs, the
    /// springs' start directions, and the forces other than the springs.
    void linearise(const SpringSystem& springs, std::span<const double> mass, std::span<const dvec3> x, double dt,
                   std::span<const dvec3> v0 = {}, std::span<const dvec3> f0 = {});
    /// Each spring's B (w_a - w_b), into m_perSpring.
    void springPass(const SpringSystem& springs, const std::vector<dvec3>& w);
    /// Solves for m_dv (and the bearers' velocities) from its value; returns the right-hand
    /// side's squared preconditioned norm.
    double solve(const SpringSystem& springs, std::span<const double> mass);
    /// w without its part along member p's held normal (w itself where p is free).
    dvec3 filtered(std::size_t p, const dvec3& w) const
    {
        return m_held ? w - glm::dot(m_normal[p], w) * m_normal[p] : w;
    }
    /// Each held member's push from the solved m_dv; lets go of those their surface pulls.
    /// Returns whether it let any go.
    bool releasePulled(const SpringSystem& springs, std::span<const double> mass);
    /// What each held member's surface gives it along its normal (an impulse, N s) for m_dv.
    void heldImpulses(const SpringSystem& springs, std::span<const double> mass, std::vector<double>& out);
    // The bearers' part of the solve (m_bearers set): their velocities m_u as unknowns beside m_dv.
    /// Held member p's velocity along its normal at the end of the step: its bearer's point's, or zero.
    double heldSpeed(std::size_t p) const;
    /// s = (n, arm x n) of held member p: its speed along n is s . U of its bearer's U.
    Twist along(std::size_t p) const;
    /// Whether member p of m_bearerMembers is still held (not let go of since startBearers).
    bool stillHeld(std::uint32_t p) const;
    void startBearers();
    void finishBearers();
    /// The bearers' residual from the members' whole residual, and their preconditioners.
    void bearerResidual(const std::vector<dvec3>& residual);
    double bearerScale() const;
    /// z_U from r_U; returns r_U . z_U.
    double preconditionBearers();
    /// Member p's preconditioned residual (z), with its bearer's part along its normal.
    dvec3 preconditioned(std::size_t p) const;
    /// The bearers' part of the direction and of H times it; returns its part of p^T H p.
    double bearerDirection(double beta);
    /// Moves the bearers' velocities by alpha along the direction; returns their part of r . z.
    double stepBearers(double alpha);

    std::vector<Block> m_blocks;     ///< one per spring
    std::vector<dvec3> m_perSpring;  ///< a pass's result per spring
    std::vector<Sym3> m_inverseDiagonal;
    std::vector<dvec3> m_rhs, m_dv, m_r, m_z, m_p, m_ap;
    std::vector<dvec3> m_x0, m_v0, m_otherForce, m_correction, m_trial;
    std::vector<dvec3> m_u0;               ///< each spring's direction at the start
    std::vector<dvec3> m_startSpringForce; ///< each spring's force on its first end at the start
    bool m_held = false;           ///< whether any member is held on a surface this step
    std::vector<dvec3> m_normal;   ///< per member, the normal it is held along (or zero)
    std::vector<double> m_push;    ///< per member, its surface's push (m/s)
    std::vector<double> m_impulse; ///< per member, heldImpulses' scratch
    /// The bearers of the step's first solves (null in Newton's corrections and without any):
    /// their velocities, those alone, masses, the members held on them, and the conjugate
    /// gradients' vectors and preconditioners for them.
    const Bearers* m_bearers = nullptr;
    std::span<const dmat3> m_along; ///< the step's directional masses (step's `along`), or none
    /// Member p's mass times w, its directional mass included.
    dvec3 massTimes(std::span<const double> mass, std::size_t p, const dvec3& w) const
    {
        return m_along.empty() ? mass[p] * w : mass[p] * w + m_along[p] * w;
    }
    std::vector<Twist> m_u, m_uAlone, m_ru, m_zu, m_pu, m_apu;
    std::vector<BodyMass> m_uMass;
    std::vector<Mat6> m_uDiagonal, m_uInverse;
    std::vector<std::uint32_t> m_bearerMembers;
    int m_iterations = 0, m_newtonIterations = 0;
    double m_residual = 0.0;
};

} // namespace pba::detail
