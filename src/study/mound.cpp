#include "study/mound.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pba/overlap.hpp"

namespace pba::study {

double angleOfRepose(const Swarm& grains, const dvec3& up)
{
    const std::size_t n = grains.size();
    if (n < 2)
        return 0.0;
    dvec3 centre(0.0);
    for (std::size_t i = 0; i < n; ++i)
        centre += dvec3(grains.position(i));
    centre /= double(n);
    std::vector<double> rho(n), height(n);
    for (std::size_t i = 0; i < n; ++i) {
        const dvec3 d = dvec3(grains.position(i)) - centre;
        height[i] = glm::dot(d, up);
        rho[i] = glm::length(d - height[i] * up);
    }
    std::vector<double> sorted = rho;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(n * 95 / 100), sorted.end());
    const double edge = sorted[n * 95 / 100];
    // Rings a grain wide, but no more than kRings of them (grains far smaller than their heap).
    constexpr double kRings = 10000.0;
    const double ring = std::max(2.0 * grains.radius(), edge / kRings);
    if (!(ring > 0.0))
        return 0.0;
    std::vector<double> top(std::size_t(std::ceil(edge / ring)), -INFINITY);
    for (std::size_t i = 0; i < n; ++i)
        if (rho[i] < edge) {
            const std::size_t b = std::min(std::size_t(rho[i] / ring), top.size() - 1);
            top[b] = std::max(top[b], height[i]);
        }
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, m = 0.0;
    for (std::size_t b = 0; b < top.size(); ++b) {
        if (top[b] == -INFINITY)
            continue; // an empty ring
        const double x = (double(b) + 0.5) * ring;
        sx += x, sy += top[b], sxx += x * x, sxy += x * top[b], m += 1.0;
    }
    const double denominator = m * sxx - sx * sx;
    if (!(denominator > 0.0))
        return 0.0;
    return std::atan(-(m * sxy - sx * sy) / denominator) * 180.0 / std::numbers::pi + 0.0; // (-0 reads 0)
}

double deepestGrainOverlap(const Swarm& grains)
{
    const double r = grains.radius();
    if (!(r > 0.0))
        return 0.0;
    std::vector<dvec3> centres(grains.size());
    for (std::size_t i = 0; i < grains.size(); ++i)
        centres[i] = dvec3(grains.position(i));
    double deepest = 0.0;
    for (const auto& [i, j] : nearBallPairs(centres, std::vector<double>(grains.size(), r), 0.0))
        deepest = std::max(deepest, 2.0 * r - glm::length(centres[j] - centres[i]));
    return deepest / r;
}

} // namespace pba::study
