// The narrow phase's polyhedra: boxes, prisms and convex hulls as vertices, faces and edges. The
// oracles are the solids' own counts (a cube's 8 vertices, 12 edges and 6 faces; Euler's
// V - E + F = 2) and the conventions the header states (loops counter-clockwise seen from
// outside, each edge's left face running tail -> head).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/contact/convex_polyhedron.hpp"
#include "core/contact/narrow_phase.hpp"

namespace {

using pba::dvec3;
using pba::contact::ConvexPolyhedron;

/// Everything a well-formed polyhedron promises: unit outward normals with every vertex on or
/// below every face's plane, each loop on its plane and counter-clockwise about its normal
/// (every corner turns left), each edge once with its left face running tail -> head and its
/// right face head -> tail, faceEdges naming each loop edge, and Euler's formula.
void expectWellFormed(const ConvexPolyhedron& p)
{
    for (const ConvexPolyhedron::Face& f : p.faces) {
        EXPECT_NEAR(glm::length(f.normal), 1.0, 1e-12);
        for (const dvec3& v : p.vertices)
            EXPECT_LE(glm::dot(f.normal, v), f.offset + 1e-12);
        const auto loop = p.loop(f);
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const dvec3 &a = p.vertices[loop[k]], &b = p.vertices[loop[(k + 1) % loop.size()]],
                        &c = p.vertices[loop[(k + 2) % loop.size()]];
            EXPECT_NEAR(glm::dot(f.normal, a), f.offset, 1e-12);
            EXPECT_GT(glm::dot(glm::cross(b - a, c - b), f.normal), 0.0);
            const ConvexPolyhedron::Edge& e = p.edges[p.faceEdges[f.first + k]];
            const bool forward = e.tail == loop[k] && e.head == loop[(k + 1) % loop.size()];
            const bool backward = e.head == loop[k] && e.tail == loop[(k + 1) % loop.size()];
            const auto face = static_cast<std::uint32_t>(&f - p.faces.data());
            EXPECT_TRUE((forward && e.leftFace == face) || (backward && e.rightFace == face));
        }
    }
    EXPECT_EQ(static_cast<long>(p.vertices.size()) - static_cast<long>(p.edges.size()) + static_cast<long>(p.faces.size()),
              2);
}

TEST(ConvexPolyhedron, BoxHasACubesCountsAndAxisNormals)
{
    const ConvexPolyhedron box = ConvexPolyhedron::box({0.5, 1.0, 1.5});
    EXPECT_EQ(box.vertices.size(), 8u);
    EXPECT_EQ(box.edges.size(), 12u);
    EXPECT_EQ(box.faces.size(), 6u);
    expectWellFormed(box);
    // Face 2 is +y, at the half height.
    EXPECT_EQ(box.faces[2].normal, dvec3(0, 1, 0));
    EXPECT_DOUBLE_EQ(box.faces[2].offset, 1.0);
    EXPECT_DOUBLE_EQ(box.boundingRadius, std::sqrt(0.25 + 1.0 + 2.25));
    EXPECT_EQ(box.vertices[box.support({1, 1, -1})], dvec3(0.5, 1.0, -1.5));
}

TEST(ConvexPolyhedron, PrismHasTwoCapsAndASideFacePerRimEdge)
{
    const int n = pba::kCylinderRimPoints;
    const ConvexPolyhedron prism = ConvexPolyhedron::prism(0.5, 2.0, n);
    EXPECT_EQ(prism.vertices.size(), 2u * n);
    EXPECT_EQ(prism.faces.size(), n + 2u);
    EXPECT_EQ(prism.edges.size(), 3u * n);
    expectWellFormed(prism);
    // The rims are contactPointsOf's: vertex k at angle 2 pi k / n, bottom first.
    const auto points = pba::contactPointsOf(pba::Shape::cylinder(0.5, 2.0));
    ASSERT_EQ(points.size(), prism.vertices.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        EXPECT_LT(glm::length(points[i] - prism.vertices[i]), 1e-15);
    // A side face lies at the polygon's inradius, r cos(pi / n).
    EXPECT_NEAR(prism.faces[2].offset, 0.5 * std::cos(std::numbers::pi / n), 1e-15);
}

TEST(ConvexPolyhedron, CubeMeshHullMergesItsTrianglesIntoSixQuads)
{
    // The cube as Shape::mesh takes it: twelve triangles, two a face.
    const pba::Shape cube = pba::Shape::mesh(
        {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
        {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5});
    const pba::contact::CollisionShape shape = pba::contact::CollisionShape::of(cube);
    ASSERT_EQ(shape.kind, pba::contact::CollisionShape::Kind::Polyhedron);
    const ConvexPolyhedron& hull = *shape.polyhedron;
    EXPECT_EQ(hull.vertices.size(), 8u);
    EXPECT_EQ(hull.edges.size(), 12u);
    ASSERT_EQ(hull.faces.size(), 6u);
    for (const ConvexPolyhedron::Face& f : hull.faces) {
        EXPECT_EQ(f.count, 4u);
        EXPECT_NEAR(std::abs(f.normal.x) + std::abs(f.normal.y) + std::abs(f.normal.z), 1.0, 1e-12); // an axis
        EXPECT_NEAR(f.offset, 1.0, 1e-12);
    }
    expectWellFormed(hull);
}

TEST(ConvexPolyhedron, TetrahedronHullDropsAnInteriorPoint)
{
    // A corner tetrahedron and a point inside it (its centroid): the hull keeps the four corners.
    const std::vector<dvec3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.25, 0.25, 0.25}};
    const ConvexPolyhedron hull = ConvexPolyhedron::hull(points);
    EXPECT_EQ(hull.vertices.size(), 4u);
    EXPECT_EQ(hull.edges.size(), 6u);
    ASSERT_EQ(hull.faces.size(), 4u);
    for (const dvec3& v : hull.vertices)
        EXPECT_NE(v, points[4]);
    // The slanted face: normal (1, 1, 1) / sqrt 3 at distance 1 / sqrt 3 from the origin.
    int slanted = 0;
    for (const ConvexPolyhedron::Face& f : hull.faces)
        if (glm::length(f.normal - dvec3(1.0) / std::sqrt(3.0)) < 1e-12) {
            ++slanted;
            EXPECT_NEAR(f.offset, 1.0 / std::sqrt(3.0), 1e-12);
        }
    EXPECT_EQ(slanted, 1);
    expectWellFormed(hull);
}

TEST(ConvexPolyhedron, HullOfFlatOrTooFewPointsIsRefused)
{
    const std::vector<dvec3> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.5, 0}};
    EXPECT_THROW(ConvexPolyhedron::hull(flat), std::invalid_argument);
    const std::vector<dvec3> three{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    EXPECT_THROW(ConvexPolyhedron::hull(three), std::invalid_argument);
}

TEST(ConvexPolyhedron, FacesThatDoNotCloseAreRefused)
{
    // A lone triangle: each of its edges borders one face only.
    const std::vector<std::vector<std::uint32_t>> loops{{0, 1, 2}};
    const std::vector<dvec3> normals{{0, 0, 1}};
    EXPECT_THROW(ConvexPolyhedron::fromFaces({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, loops, normals), std::invalid_argument);
}

TEST(ConvexPolyhedron, CollisionShapeOfEachShapeType)
{
    using pba::contact::CollisionShape;
    const CollisionShape sphere = CollisionShape::of(pba::Shape::sphere(0.3));
    EXPECT_EQ(sphere.kind, CollisionShape::Kind::Sphere);
    EXPECT_DOUBLE_EQ(sphere.boundingRadius(), 0.3);
    const CollisionShape box = CollisionShape::of(pba::Shape::box({1, 2, 3}));
    ASSERT_EQ(box.kind, CollisionShape::Kind::Polyhedron);
    EXPECT_EQ(box.polyhedron->vertices[7], dvec3(0.5, 1.0, 1.5)); // half the size
    const CollisionShape cylinder = CollisionShape::of(pba::Shape::cylinder(0.5, 1.0));
    ASSERT_EQ(cylinder.kind, CollisionShape::Kind::Polyhedron);
    EXPECT_EQ(cylinder.polyhedron->faces.size(), pba::kCylinderRimPoints + 2u);
    EXPECT_DOUBLE_EQ(cylinder.boundingRadius(), std::sqrt(0.25 + 0.25));
}

} // namespace
