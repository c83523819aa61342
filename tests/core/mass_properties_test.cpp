// Mass properties against their closed forms: the box, the ball and the cylinder, a mesh of a
// box against the box shape, and the unit right tetrahedron.
#include "pba/mass_properties.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

using namespace pba;

namespace {

void expectNear(const dmat3& actual, const dmat3& expected, double tolerance)
{
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            EXPECT_NEAR(actual[c][r], expected[c][r], tolerance) << "[" << c << "][" << r << "]";
}

dmat3 diagonal(double x, double y, double z) { return dmat3(dvec3(x, 0.0, 0.0), dvec3(0.0, y, 0.0), dvec3(0.0, 0.0, z)); }

/// A box's eight corners around `centre` and its twelve triangles, counter-clockwise from outside.
struct BoxMesh {
    std::vector<dvec3> vertices;
    std::vector<std::uint32_t> triangles{0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                         2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};

    BoxMesh(const dvec3& size, const dvec3& centre)
    {
        const dvec3 h = 0.5 * size;
        for (const dvec3 corner : {dvec3(-1, -1, -1), dvec3(1, -1, -1), dvec3(1, 1, -1), dvec3(-1, 1, -1),
                                   dvec3(-1, -1, 1), dvec3(1, -1, 1), dvec3(1, 1, 1), dvec3(-1, 1, 1)})
            vertices.push_back(centre + corner * h);
    }
};

} // namespace

TEST(MassProperties, BoxClosedForm)
{
    const MassProperties box = boxMassProperties(dvec3(1.0, 2.0, 3.0), 500.0);
    const double m = 500.0 * 6.0;
    EXPECT_DOUBLE_EQ(box.mass, m);
    EXPECT_EQ(box.centre, dvec3(0.0));
    expectNear(box.inertia, diagonal(m * 13.0 / 12.0, m * 10.0 / 12.0, m * 5.0 / 12.0), 1e-9);
}

TEST(MassProperties, SphereAndCylinderClosedForms)
{
    const MassProperties ball = sphereMassProperties(0.5, 1000.0);
    const double mb = 1000.0 * 4.0 / 3.0 * std::numbers::pi * 0.125;
    EXPECT_DOUBLE_EQ(ball.mass, mb);
    expectNear(ball.inertia, diagonal(0.1 * mb, 0.1 * mb, 0.1 * mb), 1e-12);

    const MassProperties can = cylinderMassProperties(0.5, 2.0, 1000.0);
    const double mc = 1000.0 * std::numbers::pi * 0.25 * 2.0;
    EXPECT_DOUBLE_EQ(can.mass, mc);
    const double across = mc * (3.0 * 0.25 + 4.0) / 12.0;
    expectNear(can.inertia, diagonal(across, 0.5 * mc * 0.25, across), 1e-9); // y is the axis
}

TEST(MassProperties, MeshOfABoxEqualsTheBoxAndFindsItsCentre)
{
    const dvec3 size(0.4, 1.0, 2.5);
    const dvec3 centre(3.0, -1.0, 0.5);
    const BoxMesh mesh(size, centre);
    const MassProperties fromMesh = meshMassProperties(mesh.vertices, mesh.triangles, 700.0);
    const MassProperties box = boxMassProperties(size, 700.0);
    EXPECT_NEAR(fromMesh.mass, box.mass, 1e-9 * box.mass);
    EXPECT_NEAR(fromMesh.centre.x, centre.x, 1e-12);
    EXPECT_NEAR(fromMesh.centre.y, centre.y, 1e-12);
    EXPECT_NEAR(fromMesh.centre.z, centre.z, 1e-12);
    expectNear(fromMesh.inertia, box.inertia, 1e-9 * box.mass);
}

TEST(MassProperties, UnitTetrahedronClosedForm)
{
    // The corners (0,0,0), (1,0,0), (0,1,0), (0,0,1) at density 1: volume 1/6, centre (1/4,1/4,1/4);
    // over the volume x^2 integrates to 1/60 and xy to 1/120, so about the centre the moments
    // are 1/60 - 1/96 = 1/160 and the products 1/120 - 1/96 = -1/480: I = [1/80, 1/480; ...].
    const std::array<dvec3, 4> corners{dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0, 0, 1)};
    const std::array<std::uint32_t, 12> triangles{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    const MassProperties tetra = meshMassProperties(corners, triangles, 1.0);
    EXPECT_NEAR(tetra.mass, 1.0 / 6.0, 1e-15);
    EXPECT_NEAR(tetra.centre.x, 0.25, 1e-15);
    EXPECT_NEAR(tetra.centre.y, 0.25, 1e-15);
    EXPECT_NEAR(tetra.centre.z, 0.25, 1e-15);
    dmat3 expected(0.0);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            expected[c][r] = c == r ? 1.0 / 80.0 : 1.0 / 480.0;
    expectNear(tetra.inertia, expected, 1e-15);
}

TEST(MassProperties, WithMassScalesTheInertiaAndKeepsTheCentre)
{
    const MassProperties box = boxMassProperties(dvec3(1.0, 2.0, 3.0), 1.0).withMass(12.0);
    EXPECT_DOUBLE_EQ(box.mass, 12.0);
    expectNear(box.inertia, diagonal(13.0, 10.0, 5.0), 1e-12);
    EXPECT_THROW(box.withMass(0.0), std::invalid_argument);
}

TEST(MassProperties, BadShapesAreRefusedSayingWhy)
{
    EXPECT_THROW(boxMassProperties(dvec3(1.0, 0.0, 1.0), 1.0), std::invalid_argument);
    EXPECT_THROW(sphereMassProperties(1.0, -2.0), std::invalid_argument);
    EXPECT_THROW(cylinderMassProperties(INFINITY, 1.0, 1.0), std::invalid_argument);
    BoxMesh mesh(dvec3(1.0), dvec3(0.0));
    // Inside out: every triangle turned the other way.
    std::vector<std::uint32_t> inverted = mesh.triangles;
    for (std::size_t t = 0; t < inverted.size(); t += 3)
        std::swap(inverted[t + 1], inverted[t + 2]);
    EXPECT_THROW(meshMassProperties(mesh.vertices, inverted, 1.0), std::invalid_argument);
    // Open: a face missing.
    const std::vector<std::uint32_t> open(mesh.triangles.begin(), mesh.triangles.end() - 6);
    EXPECT_THROW(meshMassProperties(mesh.vertices, open, 1.0), std::invalid_argument);
    // An index past the vertices.
    std::vector<std::uint32_t> bad = mesh.triangles;
    bad[4] = 8;
    EXPECT_THROW(meshMassProperties(mesh.vertices, bad, 1.0), std::invalid_argument);
}
