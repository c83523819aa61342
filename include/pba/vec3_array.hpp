#pragma once
// The state of a group of coupled bodies as one vector: a position (or velocity, or
// acceleration) per body, with the vector-space operations the integrators use. The same
// integrator templates then step one body (Vec3) or a whole coupled group (Vec3Array): RK4
// of a coupled system is RK4 of the whole system, not of each body in turn.
#include <cstddef>
#include <utility>
#include <vector>

#include "pba/math.hpp"

namespace pba {

class Vec3Array {
public:
    Vec3Array() = default;
    explicit Vec3Array(std::size_t n) : m_items(n, dvec3(0.0)) {}

    std::size_t size() const { return m_items.size(); }
    /// Keeps the storage: a buffer reused every step allocates once.
    void resize(std::size_t n) { m_items.resize(n); }
    dvec3& operator[](std::size_t i) { return m_items[i]; }
    const dvec3& operator[](std::size_t i) const { return m_items[i]; }
    auto begin() { return m_items.begin(); }
    auto end() { return m_items.end(); }
    auto begin() const { return m_items.begin(); }
    auto end() const { return m_items.end(); }

    /// Body by body, out of line (src/core/swarms/vec3_array.cpp): each is a loop over the whole group,
    /// beside which a call costs nothing.
    Vec3Array& operator+=(const Vec3Array& other);
    friend Vec3Array operator+(Vec3Array a, const Vec3Array& b) { return a += b; }
    friend Vec3Array operator*(Vec3Array a, double s);
    friend Vec3Array operator*(double s, Vec3Array a) { return std::move(a) * s; }

private:
    std::vector<dvec3> m_items;
};

} // namespace pba
