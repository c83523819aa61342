#include "contact/convex_polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace pba::contact {

namespace {

constexpr std::uint32_t kNoFace = ~0u;

/// Appends one face's edges: an edge seen first is new (this face on its left, as its loop runs
/// tail -> head); seen again it must run the other way, and this face is its right.
void addFaceEdges(ConvexPolyhedron& p, std::uint32_t face, std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t>& byEnds)
{
    const ConvexPolyhedron::Face& f = p.faces[face];
    for (std::uint32_t k = 0; k < f.count; ++k) {
        const std::uint32_t tail = p.faceVertices[f.first + k], head = p.faceVertices[f.first + (k + 1) % f.count];
        const auto key = std::minmax(tail, head);
        const auto [it, added] = byEnds.try_emplace(key, static_cast<std::uint32_t>(p.edges.size()));
        if (added) {
            p.edges.push_back({tail, head, face, kNoFace});
        } else {
            ConvexPolyhedron::Edge& e = p.edges[it->second];
            if (e.rightFace != kNoFace || e.tail != head || e.head != tail)
                throw std::invalid_argument("convex polyhedron: edge " + std::to_string(tail) + "-" + std::to_string(head) +
                                            " is not shared by exactly two faces in opposite directions");
            e.rightFace = face;
        }
        p.faceEdges[f.first + k] = it->second;
    }
}

} // namespace

ConvexPolyhedron ConvexPolyhedron::fromFaces(std::vector<dvec3> vertices, std::span<const std::vector<std::uint32_t>> loops,
                                             std::span<const dvec3> normals)
{
    if (loops.size() != normals.size())
        throw std::invalid_argument("convex polyhedron: one normal per face");
    ConvexPolyhedron p;
    p.vertices = std::move(vertices);
    for (std::size_t i = 0; i < loops.size(); ++i) {
        if (loops[i].size() < 3)
            throw std::invalid_argument("convex polyhedron: face " + std::to_string(i) + " has fewer than three vertices");
        Face f;
        f.normal = normals[i];
        f.first = static_cast<std::uint32_t>(p.faceVertices.size());
        f.count = static_cast<std::uint32_t>(loops[i].size());
        f.offset = -INFINITY;
        for (const std::uint32_t v : loops[i]) {
            if (v >= p.vertices.size())
                throw std::invalid_argument("convex polyhedron: face " + std::to_string(i) + " names no vertex " + std::to_string(v));
            f.offset = std::max(f.offset, glm::dot(f.normal, p.vertices[v]));
            p.faceVertices.push_back(v);
        }
        // Newell: the loop's cross products add up to twice its area along the normal.
        dvec3 twiceArea(0.0);
        for (std::size_t k = 0; k < loops[i].size(); ++k)
            twiceArea += glm::cross(p.vertices[loops[i][k]], p.vertices[loops[i][(k + 1) % loops[i].size()]]);
        f.area = 0.5 * glm::dot(twiceArea, f.normal);
        p.faces.push_back(f);
    }
    p.faceEdges.assign(p.faceVertices.size(), 0);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> byEnds;
    for (std::uint32_t face = 0; face < p.faces.size(); ++face)
        addFaceEdges(p, face, byEnds);
    for (const Edge& e : p.edges)
        if (e.rightFace == kNoFace)
            throw std::invalid_argument("convex polyhedron: edge " + std::to_string(e.tail) + "-" + std::to_string(e.head) +
                                        " borders only one face");
    for (const dvec3& v : p.vertices)
        p.boundingRadius = std::max(p.boundingRadius, glm::length(v));
    return p;
}

ConvexPolyhedron ConvexPolyhedron::box(const dvec3& halfExtents)
{
    // Vertex i has the sign of bit 0 in x, bit 1 in y, bit 2 in z (as contactPointsOf). The face
    // of +axis runs (u-, w-) (u+, w-) (u+, w+) (u-, w+) with u, w the next two axes: u x w = axis
    // makes that counter-clockwise seen from outside; the face of -axis runs the other way.
    std::vector<dvec3> vertices;
    for (int i = 0; i < 8; ++i)
        vertices.push_back(halfExtents * dvec3(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0));
    std::vector<std::vector<std::uint32_t>> loops;
    std::vector<dvec3> normals;
    for (int axis = 0; axis < 3; ++axis) {
        const std::uint32_t a = 1u << axis, u = 1u << (axis + 1) % 3, w = 1u << (axis + 2) % 3;
        normals.push_back(dvec3(0.0));
        normals.back()[axis] = 1.0;
        loops.push_back({a, a | u, a | u | w, a | w});
        normals.push_back(-normals.back());
        loops.push_back({0, w, u | w, u});
    }
    ConvexPolyhedron p = fromFaces(std::move(vertices), loops, normals);
    if (halfExtents.x > 0.0 && halfExtents.y > 0.0 && halfExtents.z > 0.0)
        p.boxHalfExtents = halfExtents;
    return p;
}

ConvexPolyhedron ConvexPolyhedron::prism(double radius, double height, int sides)
{
    if (sides < 3)
        throw std::invalid_argument("prism: at least three sides");
    const auto n = static_cast<std::uint32_t>(sides);
    std::vector<dvec3> vertices;
    for (const double y : {-0.5 * height, 0.5 * height})
        for (std::uint32_t k = 0; k < n; ++k) {
            const double angle = 2.0 * std::numbers::pi * k / n;
            vertices.push_back({radius * std::cos(angle), y, radius * std::sin(angle)});
        }
    // The rims run from +x towards +z, clockwise seen from +y: the bottom cap (seen from -y)
    // takes them in order, the top cap in reverse. Side k (between rim vertices k and k + 1)
    // runs up, across and down, so that its first two edges cross to the outward normal.
    std::vector<std::vector<std::uint32_t>> loops(2);
    std::vector<dvec3> normals{{0.0, -1.0, 0.0}, {0.0, 1.0, 0.0}};
    for (std::uint32_t k = 0; k < n; ++k) {
        loops[0].push_back(k);
        loops[1].push_back(2 * n - 1 - k);
    }
    for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t next = (k + 1) % n;
        loops.push_back({k, n + k, n + next, next});
        const double angle = 2.0 * std::numbers::pi * (k + 0.5) / n;
        normals.push_back({std::cos(angle), 0.0, std::sin(angle)});
    }
    return fromFaces(std::move(vertices), loops, normals);
}

std::uint32_t ConvexPolyhedron::support(const dvec3& direction) const
{
    // A box's corner is the signs of the direction; a zero component ties two corners, and the
    // first of them (the bit clear) is the one the search below would find.
    if (isBox())
        return (direction.x > 0.0 ? 1u : 0u) | (direction.y > 0.0 ? 2u : 0u) | (direction.z > 0.0 ? 4u : 0u);
    std::uint32_t best = 0;
    double bestDot = -INFINITY;
    for (std::uint32_t i = 0; i < vertices.size(); ++i) {
        const double d = glm::dot(vertices[i], direction);
        if (d > bestDot) {
            bestDot = d;
            best = i;
        }
    }
    return best;
}

std::uint32_t ConvexPolyhedron::edgeBetween(std::uint32_t tail, std::uint32_t head) const
{
    for (std::uint32_t i = 0; i < edges.size(); ++i)
        if ((edges[i].tail == tail && edges[i].head == head) || (edges[i].tail == head && edges[i].head == tail))
            return i;
    return static_cast<std::uint32_t>(edges.size());
}

} // namespace pba::contact
