#pragma once
// Four floats that one instruction adds, multiplies or compares at once (Box2D v3's b2FloatW):
// the wide contact rows' arithmetic, four contacts a lane each. SSE2, which every x86-64 has;
// elsewhere four plain floats, the same results. Private to the core.
#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace pba::rigid {

#if defined(__SSE2__)

struct Float4 {
    __m128 v;
    static Float4 all(float x) { return {_mm_set1_ps(x)}; }
    static Float4 zero() { return {_mm_setzero_ps()}; }
    /// From and to four floats aligned to 16 bytes.
    static Float4 load(const float* p) { return {_mm_load_ps(p)}; }
    void store(float* p) const { _mm_store_ps(p, v); }
};
inline Float4 operator+(Float4 a, Float4 b) { return {_mm_add_ps(a.v, b.v)}; }
inline Float4 operator-(Float4 a, Float4 b) { return {_mm_sub_ps(a.v, b.v)}; }
inline Float4 operator*(Float4 a, Float4 b) { return {_mm_mul_ps(a.v, b.v)}; }
inline Float4 operator/(Float4 a, Float4 b) { return {_mm_div_ps(a.v, b.v)}; }
inline Float4 max(Float4 a, Float4 b) { return {_mm_max_ps(a.v, b.v)}; }
inline Float4 abs(Float4 a) { return {_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)}; }
inline Float4 sqrt(Float4 a) { return {_mm_sqrt_ps(a.v)}; }
/// Where a > b, x; elsewhere y.
inline Float4 selectGreater(Float4 a, Float4 b, Float4 x, Float4 y)
{
    const __m128 m = _mm_cmpgt_ps(a.v, b.v);
    return {_mm_or_ps(_mm_and_ps(m, x.v), _mm_andnot_ps(m, y.v))};
}

#else

struct Float4 {
    float v[4];
    static Float4 all(float x) { return {{x, x, x, x}}; }
    static Float4 zero() { return all(0.0f); }
    static Float4 load(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
    void store(float* p) const { std::copy(v, v + 4, p); }
};
template <class F>
Float4 eachLane(Float4 a, Float4 b, F f)
{
    return {{f(a.v[0], b.v[0]), f(a.v[1], b.v[1]), f(a.v[2], b.v[2]), f(a.v[3], b.v[3])}};
}
inline Float4 operator+(Float4 a, Float4 b) { return eachLane(a, b, [](float x, float y) { return x + y; }); }
inline Float4 operator-(Float4 a, Float4 b) { return eachLane(a, b, [](float x, float y) { return x - y; }); }
inline Float4 operator*(Float4 a, Float4 b) { return eachLane(a, b, [](float x, float y) { return x * y; }); }
inline Float4 operator/(Float4 a, Float4 b) { return eachLane(a, b, [](float x, float y) { return x / y; }); }
inline Float4 max(Float4 a, Float4 b) { return eachLane(a, b, [](float x, float y) { return x > y ? x : y; }); }
inline Float4 abs(Float4 a) { return eachLane(a, a, [](float x, float) { return std::fabs(x); }); }
inline Float4 sqrt(Float4 a) { return eachLane(a, a, [](float x, float) { return std::sqrt(x); }); }
inline Float4 selectGreater(Float4 a, Float4 b, Float4 x, Float4 y)
{
    Float4 r;
    for (int k = 0; k < 4; ++k)
        r.v[k] = a.v[k] > b.v[k] ? x.v[k] : y.v[k];
    return r;
}

#endif

/// Three lanes of vectors: the x, y and z of four vectors.
struct Vec4x3 {
    Float4 x, y, z;
};
inline Float4 dot(const Vec4x3& a, const Vec4x3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec4x3 operator*(Float4 s, const Vec4x3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline Vec4x3 operator+(const Vec4x3& a, const Vec4x3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec4x3 operator-(const Vec4x3& a, const Vec4x3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

} // namespace pba::rigid
