// RigidWatch, what `pba sim` prints about rigid bodies, against the closed forms the rigid scenes'
// descriptions quote and against cases whose answer is known by construction.
#include <cmath>

#include <gtest/gtest.h>

#include "pba/rigid_body.hpp"
#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "study/rigid_watch.hpp"

namespace pba::study {
namespace {

std::vector<RigidFigures> watched(Scene& scene)
{
    RigidWatch watch(scene.world);
    for (long n = 0; n < std::lround(scene.duration / scene.dt); ++n) {
        scene.world.step(scene.dt);
        watch.record(scene.world);
    }
    return watch.bodies(scene.world);
}

/// A ball sliding at v0 without spin rolls from t = 2 v0 / (7 mu g) (within `share` of it) at 5/7 v0.
void expectRollsAsTheClosedFormSays(const RigidFigures& ball, double v0, double mu, double share)
{
    const double tRoll = 2.0 * v0 / (7.0 * mu * 9.81);
    ASSERT_TRUE(ball.rollingFrom.has_value());
    EXPECT_NEAR(*ball.rollingFrom, tRoll, share * tRoll);
    EXPECT_NEAR(ball.rollingSpeed, 5.0 / 7.0 * v0, 0.005);
}

// A ball sliding at v0 without spin rolls from t = 2 v0 / (7 mu g) at 5/7 v0.
TEST(RigidWatch, TheRollingBallRollsWhenTheClosedFormSays)
{
    Scene scene = loadScene("rolling");
    const std::vector<RigidFigures> figures = watched(scene);
    ASSERT_EQ(figures.size(), 1u);
    expectRollsAsTheClosedFormSays(figures[0], 3.0, 0.3, 0.01);
    EXPECT_FALSE(figures[0].stillFrom.has_value());
    EXPECT_FALSE(figures[0].free()); // it started without a spin: nothing to keep
}

// The same on a fixed table rather than the floor: it rolls from t = 2 v0 / (7 mu g) at 5/7 v0
// (the watch looked at the room's surfaces alone, and saw the roll only once the ball was down).
TEST(RigidWatch, ABallRollsOnAFixedTableWhenTheClosedFormSays)
{
    Scene scene = parseScene(R"({"dt": 0.001, "duration": 0.6, "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "rigid_bodies": [
        {"name": "table", "shape": {"type": "box", "size": [3.0, 0.1, 1.0]}, "position": [0, 0.95, 0], "fixed": true,
         "friction": 0.3},
        {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "position": [-1, 1.1, 0], "velocity": [1, 0, 0],
         "friction": 0.3}]})",
                             "table.json");
    const std::vector<RigidFigures> figures = watched(scene);
    ASSERT_EQ(figures.size(), 1u);
    expectRollsAsTheClosedFormSays(figures[0], 1.0, 0.3, 0.02);
}

// The incline's lesson as `pba sim` measures it: the box on the 35-degree ramp slides down it
// without turning, its speed growing at g (sin 35 - mu cos 35) with mu = 0.5; the one on the
// 20-degree ramp, below the friction angle, does not slide.
TEST(RigidWatch, TheSteepRampsBoxSlidesAtTheTextbookAcceleration)
{
    Scene scene = loadScene("incline");
    const std::vector<RigidFigures> figures = watched(scene);
    const double pi = std::acos(-1.0), a = 35.0 * pi / 180.0;
    const double expected = 9.81 * (std::sin(a) - 0.5 * std::cos(a));
    for (const RigidFigures& f : figures) {
        if (f.name != "steep-box") {
            EXPECT_FALSE(f.slide.has_value()) << f.name;
            continue;
        }
        ASSERT_TRUE(f.slide.has_value());
        EXPECT_EQ(f.slide->on, "steep-ramp");
        EXPECT_NEAR(f.slide->acceleration, expected, 0.01 * expected);
        EXPECT_GT(f.slide->to - f.slide->from, 1.0);
    }
}

// A box on a ramp at the friction angle itself (tan 26.57 degrees = 0.5 = mu) creeps a few
// hundredths of a millimetre before it stops: no slide to report, where one of 0.000 m/s^2 was.
TEST(RigidWatch, ACreepIsNoSlide)
{
    Scene scene = parseScene(R"({"dt": 0.005, "duration": 2, "room": {"min": [-2, 0, -2], "max": [2, 3, 2]},
        "rigid_bodies": [
        {"name": "ramp", "shape": {"type": "box", "size": [2.0, 0.1, 0.6]}, "position": [0, 1.0, 0.0],
         "orientation": [0.9732489894677302, 0, 0, 0.22975292054736118], "fixed": true, "friction": 0.5, "restitution": 0},
        {"name": "box", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 2, "position": [0.201246, 1.268328, 0.0],
         "orientation": [0.9732489894677302, 0, 0, 0.22975292054736118], "friction": 0.5, "restitution": 0}]})",
                             "creep.json");
    const dvec3 start = scene.world.body(1).getPos();
    const std::vector<RigidFigures> figures = watched(scene);
    ASSERT_EQ(figures.size(), 1u); // the ramp is fixed: nothing to say of it
    EXPECT_LT(glm::length(scene.world.body(1).getPos() - start), RigidFigures::kLeastSlideDistance);
    EXPECT_FALSE(figures[0].slide.has_value());
    EXPECT_TRUE(figures[0].stillFrom.has_value());
}

// The scene's "By t = 2 s every die is still".
TEST(RigidWatch, EveryDieIsStillByTheDescriptionsTime)
{
    Scene scene = loadScene("dice");
    for (const RigidFigures& die : watched(scene)) {
        ASSERT_TRUE(die.stillFrom.has_value()) << die.name;
        EXPECT_LT(*die.stillFrom, 2.0) << die.name;
        EXPECT_TRUE(die.flips.empty()) << die.name; // a cube has no middle axis
    }
}

// The Dzhanibekov box turns over every half period of the elliptic integral's T = 5.86 s,
// free of torques.
TEST(RigidWatch, TheTennisRacketTurnsOverEveryHalfPeriod)
{
    Scene scene = loadScene("tennis-racket");
    const std::vector<RigidFigures> figures = watched(scene);
    ASSERT_EQ(figures.size(), 1u);
    const RigidFigures& racket = figures[0];
    EXPECT_TRUE(racket.free());
    EXPECT_LT(racket.energyDrift, 1e-9);
    EXPECT_LT(racket.momentumDrift, 1e-9);
    ASSERT_GE(racket.flips.size(), 6u);
    const double every = (racket.flips.back() - racket.flips.front()) / double(racket.flips.size() - 1);
    EXPECT_NEAR(every, 5.86 / 2.0, 0.01);
    EXPECT_NEAR(racket.meanSpin, 6.0, 0.5);
}

// A flip's time is where the angular velocity about the middle axis crosses zero between two
// looks, not the look after it: a watch that looks at every 10th step of the same run times the
// flips within a tenth of its 10 dt of the every-step watch's, where the look after the
// crossing would be up to 10 dt late.
TEST(RigidWatch, FlipsAreTimedBetweenSteps)
{
    Scene scene = loadScene("tennis-racket");
    RigidWatch everyStep(scene.world), everyTenth(scene.world);
    for (long n = 1; n <= std::lround(scene.duration / scene.dt); ++n) {
        scene.world.step(scene.dt);
        everyStep.record(scene.world);
        if (n % 10 == 0)
            everyTenth.record(scene.world);
    }
    const std::vector<double> expected = everyStep.bodies(scene.world)[0].flips;
    const std::vector<double> flips = everyTenth.bodies(scene.world)[0].flips;
    ASSERT_GE(flips.size(), 6u);
    ASSERT_EQ(flips.size(), expected.size());
    for (std::size_t k = 0; k < flips.size(); ++k)
        EXPECT_NEAR(flips[k], expected[k], scene.dt) << "flip " << k;
}

// Boxes the dryer pushes are turned by it: spinning, and not free.
TEST(RigidWatch, TheDryersBoxesTumbleUnderItsTorque)
{
    Scene scene = loadScene("blow-dryer-boxes");
    scene.duration = 4.0;
    for (const RigidFigures& box : watched(scene)) {
        EXPECT_FALSE(box.free()) << box.name;
        EXPECT_GT(box.meanSpin, 0.1) << box.name;
        EXPECT_FALSE(box.stillFrom.has_value()) << box.name;
    }
}

/// What the watch makes of one body on a floor at y = 0 under gravity, over `steps` of dt.
RigidFigures watchedAlone(std::unique_ptr<RigidBody> body, int steps, double dt)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0.0, -9.81, 0.0)));
    world.setGround(0.0);
    world.setCollisionResponse(CollisionResponse::Exact);
    world.addBody(std::move(body));
    RigidWatch watch(world);
    for (int n = 0; n < steps; ++n) {
        world.step(dt);
        watch.record(world);
    }
    return watch.bodies(world).at(0);
}

// A box set down on its -y face is still from the start; turned a quarter about x (its +z
// axis now pointing down), it lies on its +z face, still within a few steps.
TEST(RigidWatch, ABoxSetDownIsStillFromTheStartOnTheFaceBelow)
{
    for (const bool turned : {false, true}) {
        auto box = std::make_unique<RigidBody>(Shape::box(dvec3(0.4, 0.2, 0.6)), 500.0);
        box->setName("box");
        const double pi = std::acos(-1.0);
        if (turned)
            box->setOrientation(glm::angleAxis(pi / 2.0, dvec3(1.0, 0.0, 0.0)));
        box->setPos(dvec3(0.0, turned ? 0.3 : 0.1, 0.0));
        const RigidFigures f = watchedAlone(std::move(box), 200, 0.005);
        ASSERT_TRUE(f.stillFrom.has_value()) << turned;
        // Turned, its corners start a rounding of cos(pi/4) off level, and settle within a few steps.
        EXPECT_LE(*f.stillFrom, turned ? 0.05 : 0.0) << turned;
        EXPECT_EQ(f.restingFace, turned ? "+z" : "-y");
        EXPECT_LT(f.tilt, turned ? 1e-4 : 0.0 + 1e-12);
        EXPECT_FALSE(f.rollingFrom.has_value());
    }
}

// A ball set rolling (v = -w x r at the contact) rolls from the first step; a ball spun in
// place on the floor never rolls; one in the air never touches.
TEST(RigidWatch, ABallRollsOnlyWhereItsContactDoesNotSlip)
{
    struct Case {
        dvec3 position, velocity, spin;
        bool rolls;
    };
    const double r = 0.1;
    for (const Case& c : {Case{dvec3(0.0, r, 0.0), dvec3(1.0, 0.0, 0.0), dvec3(0.0, 0.0, -1.0 / r), true},
                          Case{dvec3(0.0, r, 0.0), dvec3(0.0), dvec3(0.0, 0.0, 5.0), false},
                          Case{dvec3(0.0, 2.0, 0.0), dvec3(1.0, 0.0, 0.0), dvec3(0.0, 0.0, -1.0 / r), false}}) {
        auto ball = std::make_unique<RigidBody>(Shape::sphere(r), 1000.0);
        ball->setName("ball");
        ball->setFriction(0.5);
        ball->setCor(0.0);
        ball->setPos(c.position);
        ball->setVel(c.velocity);
        ball->setAngularVelocity(c.spin);
        const RigidFigures f = watchedAlone(std::move(ball), 20, 0.001);
        EXPECT_EQ(f.rollingFrom.has_value(), c.rolls) << c.position.y << " " << c.spin.z;
        if (c.rolls) {
            EXPECT_EQ(*f.rollingFrom, 0.0);
            EXPECT_NEAR(f.rollingSpeed, 1.0, 1e-9);
        }
    }
}

} // namespace
} // namespace pba::study

namespace pba::study {
namespace {

// The pendulum's bob is at its highest twice a period: every 2 sqrt(I / (m g l)) K(sin 30 degrees)
// for its 60-degree swing (I about the pivot), as its description says.
TEST(RigidWatch, APendulumIsAtItsHighestEveryHalfPeriod)
{
    Scene scene = loadScene("pendulum");
    const std::vector<RigidFigures> figures = watched(scene);
    ASSERT_EQ(figures.size(), 1u);
    const RigidFigures& bob = figures[0];
    ASSERT_GE(bob.highs.size(), 10u);
    const double r = 0.1, l = 1.0, g = 9.81, inertia = 0.4 * r * r + l * l; // per kilogram
    const double half = 2.0 * std::sqrt(inertia / (g * l)) * std::comp_ellint_1(0.5);
    EXPECT_NEAR((bob.highs.back() - bob.highs.front()) / double(bob.highs.size() - 1), half, 1e-3 * half);
    EXPECT_FALSE(bob.largestTilt.has_value()) << "a sphere has no up of its own";
}

// A cube turning about z at a steady w while it falls freely: its start's up tilts by w t until it
// passes a half turn, the largest angle being the last step's; it passes 45 degrees at
// t = pi / (4 w), and its centre ends g dt^2 n (n + 1) / 2 below its start after n steps (the
// splitting moves the centre by semi-implicit Euler). In zero g nothing is up: no tilt.
TEST(RigidWatch, ABodysLargestTiltIsHowFarItsStartsUpTurned)
{
    for (const bool weighed : {true, false}) {
        World world;
        if (weighed)
            world.addForce(std::make_unique<Gravity>(dvec3(0.0, -9.81, 0.0)));
        auto cube = std::make_unique<RigidBody>(Shape::box(dvec3(0.2)), 500.0);
        cube->setName("cube");
        cube->setPos(dvec3(0.0, 1.0, 0.0));
        const double w = 0.5;
        cube->setAngularVelocity(dvec3(0.0, 0.0, w));
        world.addBody(std::move(cube));
        RigidWatch watch(world);
        for (int n = 0; n < 1000; ++n) {
            world.step(0.002);
            watch.record(world);
        }
        const RigidFigures f = watch.bodies(world).at(0);
        EXPECT_TRUE(f.highs.empty()) << "no joint: no swing";
        if (!weighed) {
            EXPECT_FALSE(f.largestTilt.has_value());
            continue;
        }
        ASSERT_TRUE(f.largestTilt.has_value());
        EXPECT_NEAR(*f.largestTilt, w * 2.0 * 180.0 / std::acos(-1.0), 1e-4); // the rotation's own rounding
        ASSERT_TRUE(f.tippedAt.has_value());
        EXPECT_NEAR(*f.tippedAt, std::acos(-1.0) / 4.0 / w, 0.002) << "past 45 degrees at the step after pi/4 / w";
        EXPECT_GE(*f.tippedAt, std::acos(-1.0) / 4.0 / w);
        EXPECT_NEAR(f.fromStart, 0.5 * 9.81 * 0.002 * 0.002 * 1000.0 * 1001.0, 1e-9);
    }
}

// What is no figure: a box hung still from two joints, whose upward speed's rounding changes
// sign, has no turning points; a ball dropped straight onto the floor, whose contact does not
// slip because it does not move along the floor, does not roll.
TEST(RigidWatch, RoundingIsNoSwingAndABounceIsNoRoll)
{
    Scene hung = parseScene(R"({"dt": 0.01, "duration": 3, "room": {"min": [-3, 0, -3], "max": [3, 4, 3]},
        "rigid_bodies": [{"name": "bob", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "position": [1, 2, 0]}],
        "joints": [{"type": "ball", "bodies": ["bob"], "anchor": [0, 3, 0]},
                   {"type": "ball", "bodies": ["bob"], "anchor": [1, 3, 0]}]})",
                            "hung.json");
    const RigidFigures bob = watched(hung).at(0);
    EXPECT_TRUE(bob.stillFrom.has_value());
    EXPECT_TRUE(bob.highs.empty()) << bob.highs.size() << " turning points of a body at rest";
    Scene drop = parseScene(R"({"dt": 0.01, "duration": 3, "room": {"min": [-3, 0, -3], "max": [3, 4, 3]},
        "rigid_bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.2}, "position": [0, 2, 0],
                          "restitution": 0.5}]})",
                            "drop.json");
    EXPECT_FALSE(watched(drop).at(0).rollingFrom.has_value());
}

} // namespace
} // namespace pba::study
