#pragma once
#include "pba/body.hpp"

namespace pba {

/// A point mass. Drawn with a small quad (scaled to 0.1, rotated by pi/2 about x so it
/// lies in the xz plane) because a dimensionless thing cannot be seen.
class Particle : public Body {
public:
    Particle();
    std::unique_ptr<Body> clone() const override { return std::make_unique<Particle>(*this); }
};

} // namespace pba
