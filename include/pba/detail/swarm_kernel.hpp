#pragma once
// A swarm's fields as its inner loop holds them: an implementation detail, not pba's API. In a
// header because the swarm's loops (src/core), the scene reader's check that a swarm's fields fit
// in floats and the tests use them.
#include <cstddef>
#include <vector>

#include "pba/detail/blow_dryer_kernel.hpp"
#include "pba/forces.hpp"
#include "pba/math.hpp"
#include "pba/swarm.hpp"

namespace pba {

/// The same fields laid out for the inner loop, as the accelerations they give a particle of
/// one swarm's mass (1 / m folded into the drag and the dryers' strengths once a step, not
/// multiplied in for every particle): the first dryer held by value (with a zero strength when
/// there is none), so the common case is one straight-line expression.
struct SwarmKernelFields {
    Vec3<float> gravity{0.0f};
    float dragPerMass = 0.0f; ///< the drag coefficient over m
    BlowDryerKernelT<float> dryer{};
    std::vector<BlowDryerKernelT<float>> more; ///< dryers after the first
    std::size_t moreCount = 0;
    bool dryerUp = false; ///< the first dryer points exactly along +y (see DryerAxis)
    bool noDryer = false; ///< no dryer at all: `dryer` is one of zero strength, which pushes nothing
    bool air = false;     ///< some dryer has air terms (drag toward the air, axis pull)
    float radius = 0.0f;  ///< the grains' radius: in air with a density the dryers push them by their size

    SwarmKernelFields(const SwarmFields& f, float inverseMass, float grainRadius = 0.0f)
        : gravity(f.gravity), dragPerMass(f.drag * inverseMass), radius(grainRadius)
    {
        BlowDryerFieldT<float> off;
        off.strength = 0.0f;
        dryer = BlowDryerKernelT<float>(f.dryers.empty() ? off : f.dryers.front(), inverseMass);
        for (std::size_t k = 1; k < f.dryers.size(); ++k)
            more.emplace_back(f.dryers[k], inverseMass);
        moreCount = more.size();
        noDryer = f.dryers.empty();
        dryerUp = dryer.axis == Vec3<float>(0.0f, 1.0f, 0.0f);
        air = dryer.hasAirTerms();
        for (const auto& k : more)
            air = air || k.hasAirTerms();
    }
};

/// The acceleration a swarm particle feels at (x, v): one inline expression of the same
/// kernels the Force classes wrap (the first dryer only: see swarmAccelerationAll), the dryer's
/// air terms included.
inline Vec3<float> swarmAcceleration(const SwarmKernelFields& f, const Vec3<float>& x, const Vec3<float>& v)
{
    return f.gravity + dragForce(f.dragPerMass, v) + blowDryerForce<DryerAxis::Any, true>(f.dryer, x, v, f.radius);
}

/// With every dryer: the loop over dryers keeps the particle loop from vectorising, so it is
/// used only when a scene has more than one, or air terms.
inline Vec3<float> swarmAccelerationAll(const SwarmKernelFields& f, const Vec3<float>& x, const Vec3<float>& v)
{
    Vec3<float> a = swarmAcceleration(f, x, v);
    for (std::size_t k = 0; k < f.moreCount; ++k)
        a += blowDryerForce<DryerAxis::Any, true>(f.more[k], x, v, f.radius);
    return a;
}

} // namespace pba
