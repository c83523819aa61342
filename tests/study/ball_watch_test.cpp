// BallWatch, what `pba sim` prints about particles with a radius, against cases whose answer is
// known by construction: fixed balls and a fixed box, which no contact moves.
#include <gtest/gtest.h>

#include "pba/scene/scene.hpp"
#include "study/ball_watch.hpp"

namespace pba::study {
namespace {

BallFigures watched(Scene& scene, int steps)
{
    BallWatch watch(scene.world, std::vector<bool>(scene.world.bodyCount(), false));
    for (int n = 0; n < steps; ++n) {
        scene.world.step(scene.dt);
        watch.record(scene.world);
    }
    watch.finish(scene.world);
    return watch.figures();
}

// Two fixed balls of 10 and 20 cm overlapping by 1 cm (5% of the smaller's diameter), a third
// 5 cm into a fixed box: the watch reads both depths where they stand.
TEST(BallWatch, ItReadsHowFarBallsAreInEachOtherAndInABody)
{
    Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "particles": [
          {"name": "a", "position": [0, 1, 0], "radius": 0.1, "fixed": true},
          {"name": "b", "position": [0.29, 1, 0], "radius": 0.2, "fixed": true},
          {"name": "c", "position": [1.25, 1, 0], "radius": 0.1, "fixed": true}],
        "rigid_bodies": [{"name": "block", "shape": {"type": "box", "size": [0.6, 0.6, 0.6]}, "position": [1.6, 1, 0],
                          "fixed": true}]})",
                             "balls.json");
    const BallFigures f = watched(scene, 25);
    EXPECT_EQ(f.balls, 3u);
    EXPECT_NEAR(f.deepestPair, 0.01 / 0.2, 1e-12);
    EXPECT_NEAR(f.deepestInBody, 0.05, 1e-12);
    EXPECT_EQ(f.deepestBody, "block");
    EXPECT_EQ(f.freeBalls, 0u) << "fixed balls are no group's";
}

// Three balls at rest in zero g, their surfaces 0.5 mm apart in a row, touch as one group from
// the first look; a fourth 1 m away keeps them from being one.
TEST(BallWatch, BallsTouchingInARowAreOneGroupFromTheFirstLook)
{
    for (const bool fourth : {false, true}) {
        std::string particles = R"({"name": "a", "position": [0, 1, 0], "radius": 0.1},
            {"name": "b", "position": [0.2005, 1, 0], "radius": 0.1},
            {"name": "c", "position": [0.401, 1, 0], "radius": 0.1})";
        if (fourth)
            particles += R"(, {"name": "d", "position": [1.4, 1, 0], "radius": 0.1})";
        Scene scene = parseScene(R"({"dt": 0.01, "duration": 1, "gravity": [0, 0, 0],
            "room": {"min": [-2, 0, -2], "max": [2, 3, 2]}, "particles": [)" + particles + "]}",
                                 "row.json");
        const BallFigures f = watched(scene, 25);
        EXPECT_EQ(f.freeBalls, fourth ? 4u : 3u);
        EXPECT_EQ(f.deepestPair, 0.0);
        if (fourth) {
            EXPECT_FALSE(f.oneGroupFrom.has_value());
        } else {
            ASSERT_TRUE(f.oneGroupFrom.has_value());
            EXPECT_NEAR(*f.oneGroupFrom, 0.1, 1e-9);
        }
    }
}

} // namespace
} // namespace pba::study
