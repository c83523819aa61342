// ConvexPolyhedron::hull: Qhull's reentrant library finds the hull's facets (merging coplanar
// triangles, its default "C-0"), and each facet becomes a face whose loop is its vertices sorted
// by angle about its normal.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

extern "C" {
#include <libqhull_r/libqhull_r.h>
}

#include "contact/convex_polyhedron.hpp"

namespace pba::contact {

namespace {

/// A facet as Qhull leaves it: its outward normal and its vertices (indices into the input), in
/// no particular order.
struct Facet {
    dvec3 normal;
    std::vector<std::uint32_t> points;
};

/// Orders a facet's vertices counter-clockwise about its normal (seen from outside) by their
/// angle about the facet's centre, which lies inside the convex facet.
void orderByAngle(std::span<const dvec3> points, Facet& facet)
{
    dvec3 centre(0.0);
    for (const std::uint32_t i : facet.points)
        centre += points[i];
    centre /= static_cast<double>(facet.points.size());
    const dvec3& n = facet.normal;
    // Any direction across the facet will do as the angle's zero: the axis least along n.
    const dvec3 axis = std::abs(n.x) < 0.57 ? dvec3(1, 0, 0) : std::abs(n.y) < 0.57 ? dvec3(0, 1, 0) : dvec3(0, 0, 1);
    const dvec3 u = glm::normalize(glm::cross(n, axis)), w = glm::cross(n, u);
    std::vector<std::pair<double, std::uint32_t>> byAngle;
    for (const std::uint32_t i : facet.points) {
        const dvec3 d = points[i] - centre;
        byAngle.emplace_back(std::atan2(glm::dot(d, w), glm::dot(d, u)), i);
    }
    std::sort(byAngle.begin(), byAngle.end());
    for (std::size_t k = 0; k < byAngle.size(); ++k)
        facet.points[k] = byAngle[k].second;
}

/// Qhull's first line of complaint, for the exception.
std::string firstLine(const char* text, std::size_t size)
{
    std::string s(text ? text : "", size);
    const auto end = s.find('\n');
    return end == std::string::npos ? s : s.substr(0, end);
}

/// Runs Qhull over `points` and returns its facets; std::invalid_argument with Qhull's message
/// when it finds no hull (too few points, all of them in a plane).
std::vector<Facet> qhullFacets(std::span<const dvec3> points)
{
    std::vector<coordT> coordinates;
    for (const dvec3& p : points)
        coordinates.insert(coordinates.end(), {p.x, p.y, p.z});
    // Qhull reports to a stream: keep its messages for the exception instead of printing them.
    char* errorText = nullptr;
    std::size_t errorSize = 0;
    std::FILE* errors = open_memstream(&errorText, &errorSize);
    qhT state;
    qhT* qh = &state;
    qh_zero(qh, errors);
    char options[] = "qhull";
    const int status = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False, options,
                                    nullptr, errors);
    std::vector<Facet> facets;
    if (status == 0)
        for (facetT* facet = qh->facet_list; facet && facet->next; facet = facet->next) {
            Facet f{{facet->normal[0], facet->normal[1], facet->normal[2]}, {}};
            for (int i = 0; facet->vertices->e[i].p; ++i)
                f.points.push_back(static_cast<std::uint32_t>(
                    qh_pointid(qh, static_cast<vertexT*>(facet->vertices->e[i].p)->point)));
            facets.push_back(std::move(f));
        }
    qh_freeqhull(qh, !qh_ALL);
    int longRemaining = 0, bytesRemaining = 0;
    qh_memfreeshort(qh, &longRemaining, &bytesRemaining);
    std::fclose(errors);
    const std::string message = firstLine(errorText, errorSize);
    std::free(errorText);
    if (status != 0)
        throw std::invalid_argument("convex hull: the points span no volume (" + message + ")");
    return facets;
}

} // namespace

ConvexPolyhedron ConvexPolyhedron::hull(std::span<const dvec3> points)
{
    if (points.size() < 4)
        throw std::invalid_argument("convex hull: " + std::to_string(points.size()) + " points span no volume");
    std::vector<Facet> facets = qhullFacets(points);
    // Only the hull's vertices are kept, numbered in the order of the input.
    std::map<std::uint32_t, std::uint32_t> renumbered;
    for (const Facet& f : facets)
        for (const std::uint32_t i : f.points)
            renumbered.emplace(i, 0);
    std::vector<dvec3> vertices;
    for (auto& [input, index] : renumbered) {
        index = static_cast<std::uint32_t>(vertices.size());
        vertices.push_back(points[input]);
    }
    std::vector<std::vector<std::uint32_t>> loops;
    std::vector<dvec3> normals;
    for (Facet& f : facets) {
        orderByAngle(points, f);
        for (std::uint32_t& i : f.points)
            i = renumbered.at(i);
        loops.push_back(std::move(f.points));
        normals.push_back(f.normal);
    }
    return fromFaces(std::move(vertices), loops, normals);
}

} // namespace pba::contact
