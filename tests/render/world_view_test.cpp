// Where a particle's ball is drawn: resting on the surface the particle touches, never half
// sunk into it; where it is, away from surfaces and over the floor's hole.
#include <gtest/gtest.h>

#include "pba/scene/scene.hpp"
#include "render/world_view.hpp"

using namespace pba;
using namespace pba::render;

TEST(WorldView, ABallOnTheGroundIsDrawnRestingOnIt)
{
    Scene scene = loadScene("integrators"); // ground at y = 0
    ViewSettings settings;
    Body& ball = scene.world.body(1);
    ball.setPos(dvec3(0.0, 0.0, 0.0)); // at impact: the particle is a point on the ground
    const float r = drawnRadius(ball, settings);
    const glm::vec3 centre = drawnCentre(scene.world, 1, 1.0, settings);
    EXPECT_FLOAT_EQ(centre.y, r) << "its lowest point on the ground";
    EXPECT_FLOAT_EQ(centre.x, 0.0f);
    // Within a radius of the ground: lifted to rest on it; higher: drawn where it is.
    EXPECT_FLOAT_EQ(restingCentre(scene.world, glm::vec3(0, 0.5f * r, 0), r).y, r);
    EXPECT_FLOAT_EQ(restingCentre(scene.world, glm::vec3(0, 1.5f * r, 0), r).y, 1.5f * r);
    EXPECT_FLOAT_EQ(restingCentre(scene.world, glm::vec3(0, 1.0f, 0), r).y, 1.0f);
}

TEST(WorldView, ABallInACornerRestsOnBothWallsButNotOverTheHole)
{
    Scene scene = loadScene("blow-dryer"); // room [-2, 2] x [0, 4] x [-2, 2], a hole at the origin
    const float r = 0.1f;
    const glm::vec3 corner = restingCentre(scene.world, glm::vec3(-2.0f, 0.0f, 1.0f), r);
    EXPECT_NEAR(corner.x, -2.0f + r, 1e-6f);
    EXPECT_NEAR(corner.y, r, 1e-6f);
    EXPECT_NEAR(corner.z, 1.0f, 1e-6f);
    // Over the hole, a ball as near the floor is drawn where it is: it is falling into the hole
    // (the dryer's grille, further down, is not within its radius).
    const glm::vec3 overHole(0.0f, 0.3f * r, 0.0f);
    EXPECT_EQ(restingCentre(scene.world, overHole, 0.5f * r), overHole);
    EXPECT_NEAR(restingCentre(scene.world, glm::vec3(1.0f, 0.3f * r, 0.0f), 0.5f * r).y, 0.5f * r, 1e-6f);
}

// A cloth is two lit triangles a cell, each vertex with the normal of the faces around it (a flat sheet's
// is its plane's), its own springs drawn as no coils and its particles as no balls but
// its pins; without the layout the same world is drawn particle by particle.
TEST(WorldView, AClothIsASurfaceAndARopeALineOfBeads)
{
    Scene scene = loadScene("cloth");
    ViewSettings settings;
    settings.trails = false;
    settings.referenceLines = false;
    settings.fabric = scene.fabric;
    DrawList list;
    buildDrawList(scene.world, scene.world, 1.0, settings, nullptr, list);
    const ClothLayout& sheet = scene.fabric.cloths.at(0);
    EXPECT_EQ(list.surfaces.size(), 6 * (sheet.width - 1) * (sheet.height - 1));
    for (const LitVertex& v : list.surfaces) { // flat and horizontal at the start: the normal is vertical
        EXPECT_NEAR(std::abs(glm::normalize(v.normal).y), 1.0f, 1e-5f);
    }
    EXPECT_EQ(list.sprites.size(), 2u); // the two pinned corners
    const std::size_t roomEdges = 2 * 12;
    EXPECT_EQ(list.lines.size(), roomEdges); // no coils

    settings.fabric = {};
    buildDrawList(scene.world, scene.world, 1.0, settings, nullptr, list);
    EXPECT_TRUE(list.surfaces.empty());
    EXPECT_EQ(list.sprites.size(), scene.world.bodyCount());

    Scene rope = loadScene("rope");
    settings.fabric = rope.fabric;
    buildDrawList(rope.world, rope.world, 1.0, settings, nullptr, list);
    const std::size_t beads = rope.fabric.ropes.at(0).particles.size();
    EXPECT_EQ(list.sprites.size(), beads);
    EXPECT_EQ(list.lines.size(), roomEdges + 2 * (beads - 1));
}
