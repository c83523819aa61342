// A cloth (and a rope) against itself. Oracles: two particles with a radius are spheres, so a
// pair that the springs do not hold (far apart along the sheet) is never closer than the sum of
// their radii once the contacts are solved, less a tenth for what the few sweeps leave (checked
// over every pair, independently of the core's grid and of its neighbour rule: here a pair is far
// apart when the flat sheet held it at least twice its touching distance apart); a sheet lying on
// itself rests its upper balls on its lower ones, touching; neighbours along the springs get no
// contact at all, so a sheet whose neighbours overlap lies as each of its particles would alone;
// the pairs are solved in index order, so the thread count changes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "pba/scene/scene.hpp"
#include "pba/spring_network.hpp"
#include "pba/world.hpp"
#include "particle_systems/spring_neighbours.hpp"

using namespace pba;

namespace {

constexpr double kRadius = 0.04;

/// A 12 x 12 sheet held on its lower edge, leaning a little, let go: it buckles and falls in
/// folds onto the floor. `radius` on its particles.
Scene foldingSheet(double radius)
{
    const std::string text = R"({"dt": 0.002, "gravity": [0, -9.81, 0], "collision_response": "reflect",
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "cloths": [{"name": "sheet", "origin": [-0.44, 0.98, -0.1], "across": [0.88, 0, 0], "down": [0, -0.88, 0.15],
                    "columns": 12, "rows": 12, "mass": 0.2, "stiffness": {"structural": 300, "shear": 30, "bending": 1},
                    "damping": 0.05, "restitution": 0, "friction": 0.5, "integrator": "implicit-euler",
                    "radius": )" + std::to_string(radius) + "}]}";
    return parseScene(text, "folds.json");
}

/// The closest any two particles far apart in the rest sheet (at least 4 radii) come, over the
/// sum of their radii (2 kRadius).
double closestFarPair(const std::vector<dvec3>& rest, const World& world)
{
    double closest = INFINITY;
    for (std::size_t a = 0; a < rest.size(); ++a)
        for (std::size_t b = a + 1; b < rest.size(); ++b)
            if (glm::length(rest[a] - rest[b]) >= 4.0 * kRadius)
                closest = std::min(closest, glm::length(world.body(a).getPos() - world.body(b).getPos()));
    return closest / (2.0 * kRadius);
}

std::vector<dvec3> positions(const World& world)
{
    std::vector<dvec3> x;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        x.push_back(world.body(i).getPos());
    return x;
}

/// closestFarPair of a scene's particles after `steps` steps from where they start.
double closestFarPairAfter(Scene scene, int steps)
{
    const std::vector<dvec3> rest = positions(scene.world);
    for (int step = 0; step < steps; ++step)
        scene.world.step(scene.dt);
    return closestFarPair(rest, scene.world);
}

} // namespace

TEST(ClothSelf, ASheetFallingInFoldsKeepsItsFarParticlesApart)
{
    auto dropped = [](double radius) { return closestFarPairAfter(foldingSheet(radius), 600); };
    EXPECT_GE(dropped(kRadius), 0.9);
    // Without a radius the same drop passes through itself: the check above has something to find.
    EXPECT_LT(dropped(0.0), 0.75);
}

TEST(ClothSelf, ASheetFoldedOntoItselfLiesInTwoLayersOneDiameterApart)
{
    // A 12 x 16 sheet of 8 cm spacing lies on the floor (rows 0 to 8), its last 7 rows standing
    // up from row 8 and leaning back over it: they fall onto the lying rows and stay on them.
    const std::string text = R"({"dt": 0.002, "gravity": [0, -9.81, 0], "collision_response": "reflect",
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "cloths": [{"name": "sheet", "origin": [-0.44, 0.04, 0], "across": [0.88, 0, 0], "down": [0, 0, 1.2],
                    "columns": 12, "rows": 16, "mass": 0.2, "stiffness": {"structural": 300, "shear": 30, "bending": 0.2},
                    "damping": 0.05, "restitution": 0, "friction": 0.5, "integrator": "implicit-euler",
                    "radius": 0.04}]})";
    Scene scene = parseScene(text, "fold.json");
    const ClothLayout& sheet = scene.fabric.cloths.at(0);
    const double spacing = 0.08, lean = 0.2; // rad
    for (std::size_t j = 9; j < sheet.height; ++j)
        for (std::size_t i = 0; i < sheet.width; ++i) {
            const double up = double(j - 8) * spacing;
            dvec3 x = scene.world.body(sheet.at(i, j)).getPos();
            x.y = kRadius + up * std::cos(lean);
            x.z = 8 * spacing - up * std::sin(lean);
            scene.world.body(sheet.at(i, j)).setPos(x);
        }
    for (int step = 0; step < 1000; ++step)
        scene.world.step(scene.dt);
    // Away from the fold (rows 0 to 6 below, 12 to 15 above), the lower layer lies on the floor,
    // one radius up, and each ball of the upper one rests on the lower balls, touching them: its
    // centre 2 r from the nearest, and from sqrt(3) r (nestled between two) to 2 r (on top of
    // one) above their layer.
    const World& world = scene.world;
    for (std::size_t i = 0; i < sheet.width; ++i) {
        for (std::size_t j = 0; j <= 6; ++j)
            EXPECT_NEAR(world.body(sheet.at(i, j)).getPos().y, kRadius, 1e-3 * kRadius) << i << "," << j;
        for (std::size_t j = 12; j < sheet.height; ++j) {
            const dvec3 x = world.body(sheet.at(i, j)).getPos();
            double nearest = INFINITY;
            for (std::size_t k = 0; k < sheet.width; ++k)
                for (std::size_t l = 0; l <= 8; ++l)
                    nearest = std::min(nearest, glm::length(world.body(sheet.at(k, l)).getPos() - x));
            EXPECT_NEAR(nearest, 2.0 * kRadius, 0.05 * kRadius) << i << "," << j;
            EXPECT_GE(x.y, kRadius + std::sqrt(3.0) * kRadius - 0.05 * kRadius) << i << "," << j;
            EXPECT_LE(x.y, 3.0 * kRadius + 0.05 * kRadius) << i << "," << j;
        }
    }
}

TEST(ClothSelf, NeighboursThatOverlapAtRestGetNoContact)
{
    // Radius 0.6 of the spacing: each particle overlaps its four nearest by a fifth of the
    // spacing. A contact between them would push them apart; the springs hold them, at rest
    // length, so the sheet lying flat on the floor must move as each of its particles would
    // alone: as the lone particle beside it, of the same mass and radius, on the same floor.
    Scene scene = parseScene(R"({"dt": 0.002, "gravity": [0, -9.81, 0], "collision_response": "reflect",
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "cloths": [{"name": "sheet", "origin": [-0.5, 0.06, -0.5], "across": [1, 0, 0], "down": [0, 0, 1],
                    "columns": 11, "rows": 11, "mass": 1.21, "stiffness": {"structural": 300, "shear": 30, "bending": 1},
                    "damping": 0.05, "restitution": 0, "friction": 0.5, "integrator": "implicit-euler",
                    "radius": 0.06}],
        "particles": [{"name": "alone", "position": [1.5, 0.06, 1.5], "mass": 0.01, "restitution": 0, "friction": 0.5,
                       "radius": 0.06, "integrator": "implicit-euler"}]})",
                             "flat.json");
    const std::vector<dvec3> start = positions(scene.world);
    const std::size_t alone = start.size() - 1;
    for (int step = 0; step < 200; ++step)
        scene.world.step(scene.dt);
    const State lone = scene.world.body(alone).getState();
    for (std::size_t i = 0; i < alone; ++i) {
        const State s = scene.world.body(i).getState();
        EXPECT_NEAR(s.pos.x, start[i].x, 1e-12) << i;
        EXPECT_NEAR(s.pos.z, start[i].z, 1e-12) << i;
        EXPECT_NEAR(s.pos.y, lone.pos.y, 1e-12) << i;
        EXPECT_LT(glm::length(s.vel - lone.vel), 1e-9) << i;
    }
}

TEST(ClothSelf, NeighboursAreTheSpringsEndsAndWhatLiesWithinTwiceTouchingAlongThem)
{
    // A rope of 6 particles 1 m apart (rest lengths), and a seventh joined to the first by a
    // spring of 10 m: the rest-length path from particle 0 to particle k is k m.
    auto neighboursAt = [](double radius) {
        std::vector<SpringNetwork::Link> links;
        for (std::size_t k = 0; k + 1 < 6; ++k)
            links.push_back({k, k + 1, 100.0, 1.0, 0.0});
        links.push_back({0, 6, 100.0, 10.0, 0.0});
        std::vector<ClonePtr<Force>> forces;
        forces.emplace_back(std::make_unique<SpringNetwork>(links));
        std::vector<double> radii(8, radius);
        radii[5] = 0.0; // no radius: never a neighbour, never collides
        detail::SpringNeighbours neighbours;
        neighbours.update(forces, radii);
        std::vector<std::size_t> near;
        for (std::size_t k = 1; k < 8; ++k)
            if (neighbours.near(0, k)) {
                EXPECT_TRUE(neighbours.near(k, 0)) << "symmetric";
                near.push_back(k);
            }
        return near;
    };
    // Twice the touching distance 2 (r + r): 1.2 m takes the spring's ends only, 2.4 m one more
    // particle along the rope, 4.4 m the next two (particle 5 has no radius); particle 7 has no spring.
    EXPECT_EQ(neighboursAt(0.3), (std::vector<std::size_t>{1, 6}));
    EXPECT_EQ(neighboursAt(0.6), (std::vector<std::size_t>{1, 2, 6}));
    EXPECT_EQ(neighboursAt(1.1), (std::vector<std::size_t>{1, 2, 3, 4, 6}));
}

TEST(ClothSelf, AFoldingSheetIsTheSameOnOneAndTwoThreads)
{
    auto run = [](int threads) {
        Scene scene = foldingSheet(kRadius);
        scene.world.setThreads(threads);
        for (int step = 0; step < 300; ++step)
            scene.world.step(scene.dt);
        return positions(scene.world);
    };
    EXPECT_EQ(run(1), run(2));
}

TEST(ClothSelf, ARadiusOfZeroIsTheSameRunToTheBitAsNoRadius)
{
    auto run = [](const std::string& radius) {
        Scene scene = parseScene(R"({"dt": 0.002, "gravity": [0, -9.81, 0], "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
            "cloths": [{"name": "sheet", "origin": [-0.44, 0.98, -0.1], "across": [0.88, 0, 0], "down": [0, -0.88, 0.15],
                        "columns": 8, "rows": 8, "mass": 0.2, "stiffness": {"structural": 300, "shear": 30, "bending": 1},
                        "integrator": "implicit-euler")" + radius + "}]}",
                                 "sheet.json");
        for (int step = 0; step < 300; ++step)
            scene.world.step(scene.dt);
        return positions(scene.world);
    };
    EXPECT_EQ(run(""), run(R"(, "radius": 0)"));
}

TEST(ClothSelf, ARopeFallingOnItselfInCoilsDoesNotPassThroughItself)
{
    // A rope of 40 balls standing almost upright on the floor, let go: it collapses onto itself
    // in coils. The same check as the sheet's: balls far apart along it (at least 4 radii in the
    // straight rope) never come within 90% of a diameter, and without a radius they would.
    auto dropped = [](double radius) {
        return closestFarPairAfter(parseScene(R"({"dt": 0.002, "gravity": [0, -9.81, 0], "collision_response": "reflect",
            "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
            "ropes": [{"name": "rope", "from": [0, 0.04, 0], "to": [0.1, 2.04, 0.05], "count": 40, "mass": 0.2,
                       "stiffness": 2000, "bending_stiffness": 0.5, "damping": 0.05, "restitution": 0, "friction": 0.5,
                       "integrator": "implicit-euler", "radius": )" + std::to_string(radius) + "}]}",
                                              "coils.json"),
                                   750);
    };
    EXPECT_GE(dropped(kRadius), 0.9);
    EXPECT_LT(dropped(0.0), 0.75);
}

TEST(ClothSelf, ASheetDroppedOnAnotherRestsOnItsBalls)
{
    // Two cloths are two systems of springs: the upper, dropped flat from 30 cm, lands on the
    // lower, lying on the floor, and its balls rest on the lower balls, touching them (2 r from
    // the nearest), between sqrt(2) r (in the hollow of four, the lower balls' spacing being 2 r)
    // and 2 r (on top of one) above them.
    Scene scene = parseScene(R"({"dt": 0.002, "gravity": [0, -9.81, 0], "collision_response": "reflect",
        "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "cloths": [{"name": "lower", "origin": [-0.4, 0.04, -0.4], "across": [0.8, 0, 0], "down": [0, 0, 0.8],
                    "columns": 11, "rows": 11, "mass": 0.2, "stiffness": {"structural": 300, "shear": 30, "bending": 1},
                    "damping": 0.05, "restitution": 0, "friction": 0.5, "integrator": "implicit-euler", "radius": 0.04},
                   {"name": "upper", "origin": [-0.2, 0.34, -0.2], "across": [0.4, 0, 0], "down": [0, 0, 0.4],
                    "columns": 6, "rows": 6, "mass": 0.1, "stiffness": {"structural": 300, "shear": 30, "bending": 1},
                    "damping": 0.05, "restitution": 0, "friction": 0.5, "integrator": "implicit-euler", "radius": 0.04}]})",
                             "two.json");
    for (int step = 0; step < 500; ++step)
        scene.world.step(scene.dt);
    const ClothLayout& lower = scene.fabric.cloths.at(0);
    const ClothLayout& upper = scene.fabric.cloths.at(1);
    const World& world = scene.world;
    for (std::size_t u = upper.first; u < upper.first + upper.width * upper.height; ++u) {
        const dvec3 x = world.body(u).getPos();
        double nearest = INFINITY;
        for (std::size_t l = lower.first; l < lower.first + lower.width * lower.height; ++l)
            nearest = std::min(nearest, glm::length(world.body(l).getPos() - x));
        EXPECT_NEAR(nearest, 2.0 * kRadius, 0.05 * kRadius) << u;
        EXPECT_GE(x.y, kRadius + std::sqrt(2.0) * kRadius - 0.05 * kRadius) << u;
        EXPECT_LE(x.y, 3.0 * kRadius + 0.05 * kRadius) << u;
    }
}
