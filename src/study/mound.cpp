#include "study/mound.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <vector>

namespace pba::study {

double angleOfRepose(const Swarm& grains)
{
    const std::size_t n = grains.size();
    if (n < 2)
        return 0.0;
    double cx = 0.0, cz = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        cx += grains.position(i).x;
        cz += grains.position(i).z;
    }
    cx /= double(n), cz /= double(n);
    std::vector<double> rho(n);
    for (std::size_t i = 0; i < n; ++i)
        rho[i] = std::hypot(grains.position(i).x - cx, grains.position(i).z - cz);
    std::vector<double> sorted = rho;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(n * 95 / 100), sorted.end());
    const double edge = sorted[n * 95 / 100], ring = 2.0 * grains.radius();
    std::vector<double> top(std::size_t(std::ceil(edge / ring)), -1.0);
    for (std::size_t i = 0; i < n; ++i)
        if (rho[i] < edge)
            top[std::size_t(rho[i] / ring)] = std::max(top[std::size_t(rho[i] / ring)], double(grains.position(i).y));
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, m = 0.0;
    for (std::size_t b = 0; b < top.size(); ++b) {
        if (top[b] < 0.0)
            continue; // an empty ring
        const double x = (double(b) + 0.5) * ring;
        sx += x, sy += top[b], sxx += x * x, sxy += x * top[b], m += 1.0;
    }
    const double denominator = m * sxx - sx * sx;
    if (!(denominator > 0.0))
        return 0.0;
    return std::atan(-(m * sxy - sx * sy) / denominator) * 180.0 / std::numbers::pi;
}

double deepestGrainOverlap(const Swarm& grains)
{
    // Cells a diameter wide: two grains that overlap lie in the same or neighbouring cells.
    const double r = grains.radius(), cell = 2.0 * r;
    if (!(r > 0.0))
        return 0.0;
    const auto key = [&](const dvec3& x, int dx, int dy, int dz) {
        const auto c = [&](double v, int d) { return std::uint64_t(std::int64_t(std::floor(v / cell)) + d + (1 << 20)); };
        return (c(x.x, dx) << 42) | (c(x.y, dy) << 21) | c(x.z, dz);
    };
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
    for (std::size_t i = 0; i < grains.size(); ++i)
        cells[key(dvec3(grains.position(i)), 0, 0, 0)].push_back(i);
    double deepest = 0.0;
    for (std::size_t i = 0; i < grains.size(); ++i) {
        const dvec3 x(grains.position(i));
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz)
                    if (const auto it = cells.find(key(x, dx, dy, dz)); it != cells.end())
                        for (const std::size_t j : it->second)
                            if (j > i)
                                deepest = std::max(deepest, 2.0 * r - glm::length(dvec3(grains.position(j)) - x));
    }
    return deepest / r;
}

} // namespace pba::study
