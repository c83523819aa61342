// The scenes where particles, ropes and cloth touch rigid bodies or themselves, held to their
// one-line claims, each measured here from the bodies' states rather than from the engine's
// contacts: a sheet drapes over a fixed box with no particle inside it, a crate bounces on a
// trampoline cloth and comes to rest on it, a crate on a rope knocks a wall of boxes down with its
// joint holding, and a sheet falls in folds onto the floor without passing through itself.
#include <gtest/gtest.h>

#include <array>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "pba/scene/scene.hpp"
#include "pba/world.hpp"
#include "support/scene_claim.hpp"

using namespace pba;

namespace {

template <class OnStep>
void run(Scene& scene, const OnStep& onStep)
{
    const auto steps = static_cast<long>(std::lround(scene.duration / scene.dt));
    for (long n = 0; n < steps; ++n) {
        scene.world.step(scene.dt);
        onStep(n + 1);
    }
}

std::size_t bodyNamed(const World& world, const std::string& name)
{
    const auto i = world.findBody(name);
    EXPECT_TRUE(i.has_value()) << name;
    return i.value_or(0);
}

/// How far p lies inside an axis-aligned box (negative: outside, by at least that much).
double depthInside(const dvec3& p, const dvec3& centre, const dvec3& half)
{
    const dvec3 d = half - glm::abs(p - centre);
    return std::min({d.x, d.y, d.z});
}

double speedOf(const Body& b) { return glm::length(b.getVel()); }

} // namespace

SCENE_CLAIM(TouchSceneClaims, ClothOnBoxDrapesOverTheBoxWithNoParticleInsideIt, "cloth-on-box")
{
    Scene scene = loadScene("cloth-on-box");
    World& world = scene.world;
    const auto& box = world.body(bodyNamed(world, "box"));
    const dvec3 centre = box.getPos(), half(0.4);
    std::vector<std::size_t> sheet;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (world.body(i).getName().rfind("sheet[", 0) == 0)
            sheet.push_back(i);
    ASSERT_EQ(sheet.size(), 256u);
    // The edges the sheet is drawn with: each particle to its next in its row and its column, and
    // across its cell to the next of both.
    std::vector<std::pair<std::size_t, std::size_t>> edges;
    const auto at = [&](int i, int j) { return bodyNamed(world, fmt::format("sheet[{},{}]", i, j)); };
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
            if (i + 1 < 16)
                edges.emplace_back(at(i, j), at(i + 1, j));
            if (j + 1 < 16)
                edges.emplace_back(at(i, j), at(i, j + 1));
            if (i + 1 < 16 && j + 1 < 16)
                edges.emplace_back(at(i, j), at(i + 1, j + 1));
        }
    // The cells' halves it is drawn with, and the box's top corners, which come up under them.
    std::vector<std::array<std::size_t, 3>> triangles;
    for (int j = 0; j + 1 < 16; ++j)
        for (int i = 0; i + 1 < 16; ++i) {
            triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
        }
    double deepest = -INFINITY; // of the particles' surfaces (a radius, 2 cm, from their centres)
    double deepestBetween = -INFINITY; // of the sheet between them, as thick
    double deepestCorner = -INFINITY; // of a top corner into a cell's half, as thick, over its inside
    run(scene, [&](long) {
        for (const auto& t : triangles) {
            const dvec3 a = world.body(t[0]).getPos(), b = world.body(t[1]).getPos(), c = world.body(t[2]).getPos();
            const dvec3 n = glm::normalize(glm::cross(b - a, c - a));
            for (const double x : {-0.4, 0.4})
                for (const double z : {-0.4, 0.4}) {
                    const dvec3 corner = centre + dvec3(x, 0.4, z);
                    // Its foot's weights on b and c, by areas; inside the triangle if all three are positive.
                    const double area = glm::dot(glm::cross(b - a, c - a), n);
                    const double u = glm::dot(glm::cross(corner - a, c - a), n) / area;
                    const double v = glm::dot(glm::cross(b - a, corner - a), n) / area;
                    if (u > 0.0 && v > 0.0 && u + v < 1.0) // the sheet lies above the box: up is out
                        deepestCorner = std::max(deepestCorner, std::abs(glm::dot(corner - a, n)) < 0.02
                                                                    ? 0.02 - std::abs(glm::dot(corner - a, n))
                                                                    : -INFINITY);
                }
        }
        for (const std::size_t i : sheet)
            deepest = std::max(deepest, depthInside(world.body(i).getPos(), centre, half) + 0.02);
        for (const auto& [a, b] : edges) {
            const dvec3 pa = world.body(a).getPos(), pb = world.body(b).getPos();
            for (int k = 1; k < 20; ++k) {
                const dvec3 p = pa + (pb - pa) * (k / 20.0);
                const double inside = depthInside(p, centre, half);
                const double outside = glm::length(glm::max(glm::abs(p - centre) - half, dvec3(0.0)));
                deepestBetween = std::max(deepestBetween, (inside > 0.0 ? inside : -outside) + 0.02);
            }
        }
    });
    EXPECT_LE(deepest, 1e-3) << "a particle inside the box";
    EXPECT_LE(deepestBetween, 1e-3) << "the sheet between two particles inside the box";
    EXPECT_LE(deepestCorner, 1e-3) << "a corner of the box through the sheet's cell";
    const auto& middle = world.body(bodyNamed(world, "sheet[8,8]"));
    // On the top, a radius above it; the sheet's edges, held a radius off the box's edges, lift
    // the coarse sheet's middle by a few millimetres.
    EXPECT_NEAR(middle.getPos().y, 0.8 + 0.02, 1e-2);
    for (const char* corner : {"sheet[0,0]", "sheet[15,0]", "sheet[0,15]", "sheet[15,15]"})
        EXPECT_LT(world.body(bodyNamed(world, corner)).getPos().y, 0.8 - 0.2) << corner << " hangs down a side";
    double fastest = 0.0;
    for (const std::size_t i : sheet)
        fastest = std::max(fastest, speedOf(world.body(i)));
    EXPECT_LT(fastest, 0.01);
}

SCENE_CLAIM(TouchSceneClaims, TrampolineThrowsTheCrateBackUpAndHoldsItAtRest, "trampoline")
{
    Scene scene = loadScene("trampoline");
    World& world = scene.world;
    const auto& crate = world.body(bodyNamed(world, "crate"));
    const auto& middle = world.body(bodyNamed(world, "trampoline[7,7]"));
    double lowest = INFINITY, lowestCloth = INFINITY, rebound = -INFINITY;
    bool landed = false;
    run(scene, [&](long) {
        lowest = std::min(lowest, crate.getPos().y);
        lowestCloth = std::min(lowestCloth, middle.getPos().y);
        if (crate.getVel().y > 0.0)
            landed = true;
        if (landed && scene.world.time() < 1.5)
            rebound = std::max(rebound, crate.getPos().y);
    });
    // The cloth gave way under it (momentum both ways), and threw it back up nearly half a metre.
    EXPECT_LT(lowestCloth, 1.5 - 0.4);
    EXPECT_GT(rebound - lowest, 0.45);
    EXPECT_GT(lowest - 0.2, 0.9) << "the crate reached within 0.9 m of the floor";
    EXPECT_NEAR(crate.getPos().y - 0.2, 1.31, 0.01); // its bottom, at rest in the sag
    // Still as `pba sim` says it (the cloth's last sway dies out by about 14 s).
    EXPECT_LT(speedOf(crate), 1e-6);
    EXPECT_LT(glm::length(static_cast<const RigidBody&>(crate).getAngularVelocity()), 1e-6);
}

// Implicit Euler's promise holds with a heavy body on the sheet: at five times the scene's dt the
// crate's landing stores no energy that was not there (met only after the step, the contact
// stretched the springs to five times the start's energy for a moment at the scene's dt, and
// beyond dt 0.003 s the crate gained energy), and it rests where it rests at the scene's dt.
TEST(TouchScenes, TheTrampolineKeepsItsEnergyAndRestsAsHighAtFiveTimesItsStep)
{
    Scene scene = loadScene("trampoline");
    World& world = scene.world;
    const auto& crate = world.body(bodyNamed(world, "crate"));
    const double start = world.totalEnergy();
    double most = start;
    for (int step = 0; step < 1000; ++step) {
        world.step(0.01);
        most = std::max(most, world.totalEnergy());
    }
    EXPECT_LE(most, start * (1.0 + 1e-9));
    EXPECT_NEAR(crate.getPos().y - 0.2, 1.31, 0.01);
    EXPECT_LT(speedOf(crate), 1e-3);
}

SCENE_CLAIM(TouchSceneClaims, HangingCrateKnocksTheWallDownOnARopeWhoseJointHolds, "hanging-crate")
{
    Scene scene = loadScene("hanging-crate");
    World& world = scene.world;
    std::vector<std::pair<std::size_t, dvec3>> wall;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (world.isRigid(i) && world.body(i).getName() != "crate")
            wall.emplace_back(i, world.body(i).getPos());
    ASSERT_EQ(wall.size(), 20u);
    const dvec3 pin = world.body(bodyNamed(world, "rope[0]")).getPos();
    double worstJoint = 0.0;
    run(scene, [&](long) {
        const JointFrame f = world.jointFrame(0);
        worstJoint = std::max(worstJoint, glm::length(f.onA - f.onB));
    });
    EXPECT_LT(worstJoint, 1e-6);
    const auto moved = std::count_if(wall.begin(), wall.end(), [&](const auto& box) {
        return glm::length(world.body(box.first).getPos() - box.second) > 0.3;
    });
    EXPECT_EQ(moved, 6);
    EXPECT_EQ(world.body(bodyNamed(world, "rope[0]")).getPos(), pin);
}

// Twelve light boxes resting side by side on an implicit-Euler sheet at dt 0.005 s: each is solved
// with the sheet, and none gains energy or sinks through it (met only after the step, their
// energy grew to 4.5 times the start's, and at 0.01 s the world stopped on the energy's rise).
TEST(TouchScenes, BoxesRestingOnAnImplicitSheetGainNoEnergy)
{
    std::string boxes;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            boxes += fmt::format(R"({}{{"name": "box{}{}", "shape": {{"type": "box", "size": [0.15, 0.15, 0.15]}},
                                     "mass": 0.5, "position": [{}, 1.8, {}], "friction": 0.5}})",
                                 boxes.empty() ? "" : ",", i, j, -0.45 + 0.3 * i, -0.45 + 0.3 * j);
    Scene scene = parseScene(R"({"dt": 0.005, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
        "cloths": [{"name": "sheet", "origin": [-1, 1.5, -1], "across": [2, 0, 0], "down": [0, 0, 2], "columns": 15,
                    "rows": 15, "mass": 2, "stiffness": {"structural": 20000, "shear": 2000, "bending": 5}, "damping": 60,
                    "integrator": "implicit-euler", "pinned": ["top-left", "top-right", "bottom-left", "bottom-right"],
                    "restitution": 0.0, "radius": 0.07, "friction": 0.5}],
        "rigid_bodies": [)" + boxes + "]}",
                             "boxes-on-a-sheet.json");
    World& world = scene.world;
    const double start = world.totalEnergy();
    double most = start;
    for (int step = 0; step < 800; ++step) {
        world.step(scene.dt);
        most = std::max(most, world.totalEnergy());
    }
    EXPECT_LE(most, start * (1.0 + 1e-9));
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        if (!world.isRigid(i))
            continue;
        EXPECT_GT(world.body(i).getPos().y, 1.0) << world.body(i).getName() << " went through the sheet";
    }
}

// A box resting on the floor is held up by it, which a sheet's solve does not see: an
// implicit-Euler sheet dropped over it comes to rest as over a fixed box (held on the box within
// its solve, it still moved at 1 to 8 cm/s after 6 s, against 0.4 mm/s).
TEST(TouchScenes, AnImplicitSheetOverABoxOnTheFloorComesToRest)
{
    Scene scene = parseScene(R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "cloths": [{"name": "sheet", "origin": [-1, 1.6, -1], "across": [2, 0, 0], "down": [0, 0, 2], "columns": 16,
                    "rows": 16, "mass": 0.5, "stiffness": {"structural": 300, "shear": 30, "bending": 2}, "damping": 0.05,
                    "integrator": "implicit-euler", "restitution": 0.0, "radius": 0.02, "friction": 0.5}],
        "rigid_bodies": [{"name": "box", "shape": {"type": "box", "size": [0.8, 0.8, 0.8]}, "density": 500,
                          "position": [0, 0.4, 0], "friction": 0.5, "restitution": 0.0}],
        "forces": [{"type": "drag", "coefficient": 0.004}]})",
                             "sheet-over-a-box.json");
    World& world = scene.world;
    for (int step = 0; step < 4000; ++step)
        world.step(scene.dt);
    double fastest = 0.0;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        fastest = std::max(fastest, glm::length(world.body(i).getVel()));
    EXPECT_LT(fastest, 1e-3);
}

// Momentum passes both ways: a crate dropped on a rope pinned at both ends slows while the rope under it is
// pushed down, and the two end moving together.
TEST(TouchScenes, ACrateDroppedOnARopeSlowsAndTheRopeMoves)
{
    Scene scene = parseScene(R"({"dt": 0.001, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
        "ropes": [{"name": "rope", "from": [-1, 2, 0], "to": [1, 2, 0], "count": 21, "mass": 0.5, "stiffness": 2000,
                   "damping": 0.5, "pinned": ["start", "end"], "radius": 0.03}],
        "rigid_bodies": [{"name": "crate", "shape": {"type": "box", "size": [0.3, 0.3, 0.3]}, "mass": 2,
                          "position": [0, 2.6, 0.0]}]})",
                             "slack.json");
    World& world = scene.world;
    const auto& crate = world.body(bodyNamed(world, "crate"));
    const auto& middle = world.body(bodyNamed(world, "rope[10]"));
    double ropeFastestDown = 0.0;
    bool slowed = false;
    for (int n = 0; n < 600; ++n) {
        const double before = crate.getVel().y;
        world.step(scene.dt);
        // Free, it gains g dt of downward speed a step; on the rope, less, or it rises.
        if (crate.getPos().y < 2.3 && crate.getVel().y > before - 0.5 * 9.81 * scene.dt)
            slowed = true;
        ropeFastestDown = std::max(ropeFastestDown, -middle.getVel().y);
    }
    EXPECT_TRUE(slowed);
    EXPECT_GT(ropeFastestDown, 1.0); // pushed down at more than 1 m/s
    EXPECT_GT(crate.getPos().y, 1.0); // held by the rope, above the floor
}

SCENE_CLAIM(TouchSceneClaims, ClothFoldsFallsInFoldsNeverThroughItself, "cloth-folds")
{
    // Far apart in the flat sheet (at least four radii, whatever its springs are) and so never
    // held near each other by them: every such pair is checked, every 10 steps.
    Scene scene = loadScene("cloth-folds");
    World& world = scene.world;
    const double radius = 0.04;
    std::vector<std::pair<std::size_t, std::size_t>> far;
    for (std::size_t a = 0; a < world.bodyCount(); ++a)
        for (std::size_t b = a + 1; b < world.bodyCount(); ++b)
            if (glm::length(world.body(a).getPos() - world.body(b).getPos()) >= 4.0 * radius)
                far.emplace_back(a, b);
    ASSERT_EQ(world.bodyCount(), 400u);
    double closest = INFINITY;
    run(scene, [&](long n) {
        if (n % 10 == 0)
            for (const auto& pair : far)
                closest = std::min(closest,
                                   glm::length(world.body(pair.first).getPos() - world.body(pair.second).getPos()));
    });
    EXPECT_GE(closest, 0.9 * 2.0 * radius) << "two layers passed into each other";
    double highest = 0.0;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        highest = std::max(highest, world.body(i).getPos().y);
    EXPECT_GE(highest, 5.0 * radius) << "in folds, three layers deep somewhere";
    EXPECT_LT(highest, 0.5) << "on the floor";
}

// The rope scene with friction: its end, lying on the floor, rests there. Mirrored back with its
// rebound, an end pulled down by its springs at three times gravity hopped every third step for
// as long as it lay (5,301 bounces in 40 s), and crept along the floor at 2.5 mm/s with zero
// velocity (the step's slide was left where friction had stopped the velocity); under velocity
// Verlet it hopped on, the mirror's lift giving back what the rebound lost.
TEST(TouchScenes, ARopesEndLyingOnTheFloorRests)
{
    for (const char* integrator : {"semi-implicit-euler", "velocity-verlet", "rk4", "implicit-euler", "xpbd"})
        for (const char* radius : {"", R"(, "radius": 0.02)"}) {
            Scene scene = parseScene(
                fmt::format(R"({{"dt": 0.002, "gravity": [0, -9.81, 0], "room": {{"min": [-3, 0, -2], "max": [3, 4, 2]}},
                    "ropes": [{{"name": "rope", "from": [-2.5, 3.5, 0], "to": [1.5, 3.5, 0], "count": 25, "mass": 0.5,
                                "stiffness": 500, "bending_stiffness": 2, "damping": 0.05, "pinned": ["start"],
                                "restitution": 0.5, "friction": 0.5, "integrator": "{}"{}}}],
                    "forces": [{{"type": "drag", "coefficient": 0.002}}]}})",
                            integrator, radius),
                "rope-with-friction.json");
            World& world = scene.world;
            const std::size_t end = world.bodyCount() - 1;
            for (int step = 0; step < 5000; ++step) // 10 s: the rope has come down and settled
                world.step(scene.dt);
            const dvec3 lying = world.body(end).getPos();
            for (int step = 0; step < 5000; ++step)
                world.step(scene.dt);
            const std::string what = std::string(integrator) + (*radius ? " with a radius" : "");
            EXPECT_LT(lying.y, 0.021) << what << ": on the floor";
            // Still, but for velocity Verlet's and RK4's 0.01-0.05 mm/s (the start velocity drives
            // half their step's slide): the creep was 2.5 mm/s.
            EXPECT_LT(glm::length(world.body(end).getPos() - lying), 1e-3) << what;
            EXPECT_LT(world.bounceCount(end), 50u) << what << ": its landing's bounces, not one every few steps";
        }
}
