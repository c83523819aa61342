// Where a particle's ball is drawn: resting on the surface the particle touches, never half
// sunk into it; where it is, away from surfaces and over the floor's hole. What the legend says of
// collisions, and where the camera stands.
#include <gtest/gtest.h>

#include "pba/scene/scene.hpp"
#include "render/collision_note.hpp"
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

// The legend's collision line names the rule each kind of body in the scene meets the surfaces
// with, and semi-implicit Euler only where a particle the rule applies to uses it.
TEST(CollisionNote, SaysWhatAppliesToThisScenesBodies)
{
    const std::string integrators = collisionNote(loadScene("integrators").world);
    EXPECT_NE(integrators.find("particles: reflect"), std::string::npos) << integrators;
    EXPECT_NE(integrators.find("semi-implicit Euler keeps its bounce height"), std::string::npos) << integrators;
    EXPECT_EQ(integrators.find("rigid"), std::string::npos) << integrators;

    const std::string dice = collisionNote(loadScene("dice").world); // rigid bodies only
    EXPECT_EQ(dice, "collisions: rigid bodies: contact impulses with their restitution and friction");

    // A rope's particles are joined by springs: exact acts as reflect for them, and no particle
    // bounces on its own, so nothing is said of semi-implicit Euler's bounce.
    const std::string rope = collisionNote(loadScene("rope").world);
    EXPECT_NE(rope.find("particles joined by springs: reflect"), std::string::npos) << rope;
    EXPECT_EQ(rope.find("semi-implicit"), std::string::npos) << rope;
    EXPECT_EQ(rope.find("particles: exact"), std::string::npos) << rope;

    // The grains bounce at a tenth of their speed: semi-implicit Euler's bounce height is the
    // practical's comparison of elastic bounces, and is not said of them.
    const std::string granular = collisionNote(loadScene("granular").world);
    EXPECT_NE(granular.find("particles: reflect"), std::string::npos) << granular;
    EXPECT_EQ(granular.find("bounce height"), std::string::npos) << granular;

    Scene rk4 = loadScene("integrators");
    for (std::size_t i = 0; i < rk4.world.bodyCount(); ++i)
        rk4.world.body(i).setIntegrator(Integrator::RK4);
    const std::string text = collisionNote(rk4.world);
    EXPECT_EQ(text.find("semi-implicit"), std::string::npos) << text;
    EXPECT_EQ(collisionNote(parseScene(R"({"particles": [{"name": "a", "position": [0, 1, 0]}]})", "free.json").world),
              "") << "no surfaces, nothing to collide with";
}

// A camera given by its position and target is there and looks there; a named view keeps the
// framing's target and distance.
TEST(Camera, LookingFromAPositionAtATargetAndNamedViews)
{
    const OrbitCamera camera = OrbitCamera::lookingFrom(glm::vec3(1, 2, 3), glm::vec3(0, 1, 0));
    EXPECT_NEAR(glm::length(camera.eye() - glm::vec3(1, 2, 3)), 0.0f, 1e-5f);
    EXPECT_EQ(camera.target, glm::vec3(0, 1, 0));
    const glm::vec3 centre = camera.project(glm::vec3(0, 1, 0), 640, 360);
    EXPECT_NEAR(centre.x, 320.0f, 0.01f);
    EXPECT_NEAR(centre.y, 180.0f, 0.01f);
    const OrbitCamera framing = frameWorld(loadScene("dice").world);
    const OrbitCamera front = namedView(NamedView::Front, framing);
    EXPECT_EQ(front.target, framing.target);
    EXPECT_EQ(front.distance, framing.distance);
    EXPECT_NEAR(front.eye().x, framing.target.x, 1e-4f) << "straight in front: on the z axis through the target";
    EXPECT_GT(front.eye().z, framing.target.z);
    const OrbitCamera side = namedView(NamedView::Side, framing);
    EXPECT_NEAR(side.eye().z, framing.target.z, 1e-4f);
    EXPECT_GT(side.eye().x, framing.target.x);
    EXPECT_GT(namedView(NamedView::Top, framing).eye().y, framing.target.y + 0.99f * framing.distance);
}

// A framing camera keeps the room's picture out of the legend's corner and inside the picture:
// every point of every segment between two of the room's corners (the picture's outline and all
// inside it) lies outside the corner, at a large and a small picture size and from the named views.
// A thumbnail, whose legend is taller than 0.4 of it, keeps its framing.
TEST(Camera, TheFramingKeepsTheRoomOutOfTheLegendsCorner)
{
    const World world = loadScene("incline").world;
    const FramedBox box = framedBox(world);
    const OrbitCamera thumbnail = clearOfCorner(frameWorld(world), box.lo, box.hi, 96, 64, {560, 80});
    EXPECT_EQ(thumbnail.target, frameWorld(world).target);
    EXPECT_EQ(thumbnail.distance, frameWorld(world).distance);
    struct Case {
        int width, height;
        glm::vec2 corner;
    };
    for (const Case& c : {Case{1280, 720, {572, 122}}, Case{640, 360, {572, 105}}, Case{640, 360, {300, 140}}})
        for (const OrbitCamera& start : {frameWorld(world), namedView(NamedView::Front, frameWorld(world)),
                                         namedView(NamedView::Top, frameWorld(world))}) {
            const OrbitCamera camera = clearOfCorner(start, box.lo, box.hi, c.width, c.height, c.corner);
            glm::vec3 corners[8];
            for (int k = 0; k < 8; ++k)
                corners[k] = glm::vec3((k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y,
                                       (k & 4) ? box.hi.z : box.lo.z);
            const float w = float(c.width), h = float(c.height);
            for (int a = 0; a < 8; ++a) {
                const glm::vec3 p = camera.project(corners[a], c.width, c.height);
                EXPECT_TRUE(p.x >= 0 && p.x <= w && p.y >= 0 && p.y <= h) << "corner " << a;
                for (int b = a + 1; b < 8; ++b)
                    for (int k = 0; k <= 100; ++k) {
                        const glm::vec3 q =
                            camera.project(glm::mix(corners[a], corners[b], float(k) / 100.0f), c.width, c.height);
                        EXPECT_FALSE(q.x < c.corner.x && q.y > h - c.corner.y)
                            << c.width << "x" << c.height << ": " << q.x << ", " << q.y;
                    }
            }
        }
}

TEST(WorldView, AParticleWithARadiusIsDrawnAtThatSize)
{
    Scene scene = parseScene(R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
        "particles": [{"name": "ping-pong", "position": [0, 0.02, 0], "mass": 0.0027, "radius": 0.02}],
        "swarms": [{"name": "s", "count": 4, "region": {"min": [0, 1, 0], "max": [1, 2, 1]}, "seed": 1, "radius": 0.03}]})",
                             "balls.json");
    ViewSettings settings;
    EXPECT_FLOAT_EQ(drawnRadius(scene.world.body(0), settings), 0.02f);
    // Its centre is a radius above the floor already: drawn where it is, not lifted further.
    EXPECT_FLOAT_EQ(drawnCentre(scene.world, 0, 1.0, settings).y, 0.02f);
    DrawList list;
    buildDrawList(scene.world, scene.world, 1.0, settings, nullptr, list);
    ASSERT_FALSE(list.sprites.empty());
    EXPECT_FLOAT_EQ(list.sprites.back().radius, 0.03f) << "the swarm's grains at their radius";
}

// A rope or cloth is "rope NAME" in the legend and the panel, but a rope named "rope" is not
// "rope rope".
TEST(BodyGroupsLabel, KindAndNameOnceEach)
{
    const Scene crate = loadScene("hanging-crate");
    const BodyGroups groups(crate.world, crate.fabric);
    ASSERT_GT(groups.size(), 0u);
    EXPECT_EQ(groups[0].label, "rope: 14 particles");
    const Scene cloth = loadScene("cloth");
    EXPECT_EQ(BodyGroups(cloth.world, cloth.fabric)[0].label.rfind("cloth ", 0), 0u);
}
