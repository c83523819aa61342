#include "pba/vec3_array.hpp"

namespace pba {

Vec3Array& Vec3Array::operator+=(const Vec3Array& other)
{
    for (std::size_t i = 0; i < m_items.size(); ++i)
        m_items[i] += other.m_items[i];
    return *this;
}

Vec3Array operator*(Vec3Array a, double s)
{
    for (dvec3& u : a.m_items)
        u *= s;
    return a;
}

} // namespace pba
