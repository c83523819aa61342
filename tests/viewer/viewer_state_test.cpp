// The viewer's logic without a window: reset keeps the panel's settings and reload restores
// the scene's, key commands each count, and synthetic frames reach exactly a simulated time,
// the same state `pba render` draws there, and a blow-up pauses the run with its message.
#include <gtest/gtest.h>

#include <string>
#include <vector>
#include <algorithm>

#include "frame_steps.hpp"
#include "viewer_state.hpp"

using namespace pba;
using namespace pba::app;

namespace {

ViewerState loaded(const char* scene)
{
    ViewerState state;
    state.load(loadScene(scene));
    return state;
}

/// The force index of the scene's blow dryer.
std::size_t dryerIndex(const World& world)
{
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        if (dynamic_cast<const BlowDryer*>(&world.force(i)))
            return i;
    throw std::logic_error("no blow dryer");
}

const BlowDryerField& dryerField(const World& world)
{
    return dynamic_cast<const BlowDryer&>(world.force(dryerIndex(world))).field();
}

} // namespace

TEST(ViewerState, ResetRestartsWithTheIntegratorAndRestitutionChosenInThePanel)
{
    ViewerState state = loaded("integrators");
    const dvec3 start = state.scene.world.body(1).getPos();
    state.advanceTo(0.5);
    state.setIntegrator(1, Integrator::RK4);
    state.setRestitution(1, 0.5);
    state.setCollisionResponse(CollisionResponse::Exact);
    state.setDt(0.002);
    EXPECT_EQ(state.scene.world.body(1).getIntegrator(), Integrator::RK4) << "applied live too";

    state.reset();
    const World& world = state.scene.world;
    EXPECT_EQ(world.time(), 0.0);
    EXPECT_EQ(world.body(1).getPos(), start);
    EXPECT_EQ(world.body(1).getIntegrator(), Integrator::RK4);
    EXPECT_EQ(world.body(1).getCor(), 0.5);
    EXPECT_EQ(world.collisionResponse(), CollisionResponse::Exact);
    EXPECT_EQ(state.clock.dt(), 0.002);
    EXPECT_EQ(world.body(2).getIntegrator(), Integrator::SemiImplicitEuler) << "the others untouched";
}

// The panel edits a rigid body's restitution, friction and integrator (the fifth among them)
// live, and a reset keeps them; a particle has no friction to set.
TEST(ViewerState, PanelEditsARigidBodysRestitutionFrictionAndIntegrator)
{
    ViewerState state = loaded("dice");
    state.advanceTo(0.5);
    state.setIntegrator(0, Integrator::ImplicitGyroscopic);
    state.setRestitution(0, 0.1);
    state.setFriction(0, 0.9);
    const auto& live = static_cast<const RigidBody&>(state.scene.world.body(0));
    EXPECT_EQ(live.getFriction(), 0.9) << "applied live";
    state.reset();
    const auto& die = static_cast<const RigidBody&>(state.scene.world.body(0));
    EXPECT_EQ(state.scene.world.time(), 0.0);
    EXPECT_EQ(die.getIntegrator(), Integrator::ImplicitGyroscopic);
    EXPECT_EQ(die.getCor(), 0.1);
    EXPECT_EQ(die.getFriction(), 0.9);
    ViewerState particles = loaded("integrators");
    particles.setFriction(1, 0.9); // nothing to set, and no error
    EXPECT_FALSE(particles.scene.world.isRigid(1));
}

TEST(ViewerState, ReloadRestoresTheScenesOwnSettings)
{
    ViewerState state = loaded("integrators");
    state.setIntegrator(1, Integrator::RK4);
    state.setRestitution(1, 0.5);
    state.setCollisionResponse(CollisionResponse::Exact);
    state.setDt(0.002);
    state.advanceTo(0.3);
    state.apply(ViewerCommand::ReloadScene);
    const World& world = state.scene.world;
    EXPECT_EQ(world.time(), 0.0);
    EXPECT_EQ(world.body(1).getIntegrator(), Integrator::ForwardEuler);
    EXPECT_EQ(world.body(1).getCor(), 1.0);
    EXPECT_EQ(world.collisionResponse(), CollisionResponse::Reflect);
    EXPECT_EQ(state.clock.dt(), 0.01);
    // And reset after a reload restarts with the scene's settings too.
    state.reset();
    EXPECT_EQ(state.scene.world.body(1).getIntegrator(), Integrator::ForwardEuler);
}

TEST(ViewerState, ResetKeepsTheBlowDryersSettingsAndItsHoleFollowsTheNozzle)
{
    ViewerState state = loaded("blow-dryer");
    BlowDryerField f = dryerField(state.scene.world);
    const double sceneStrength = f.strength;
    f.strength = 20.0;
    f.nozzle.x = 0.5;
    state.setDryerField(dryerIndex(state.scene.world), f);
    state.advanceTo(0.2);
    state.reset();
    EXPECT_EQ(dryerField(state.scene.world).strength, 20.0);
    EXPECT_EQ(dryerField(state.scene.world).nozzle.x, 0.5);
    ASSERT_TRUE(state.scene.world.floorHole());
    EXPECT_EQ(state.scene.world.floorHole()->centre.x, 0.5);
    state.reload();
    EXPECT_EQ(dryerField(state.scene.world).strength, sceneStrength);
    EXPECT_EQ(state.scene.world.floorHole()->centre.x, 0.0);
}

// `pba view --time T` and `pba render --time T` step with the same function: the same steps,
// the same state, and the state drawn at exactly T, however the frames were cut.
TEST(ViewerState, SyntheticFramesReachExactlyTheTimeAsRenderDoes)
{
    for (const double t : {0.0, 0.005, 1.2, 2.0, 2.0051}) {
        ViewerState state = loaded("blow-dryer");
        for (int frame = 0; double(frame) / 60 < t; ++frame)
            state.advanceTo(double(frame) / 60);
        state.advanceTo(t);
        Scene rendered = loadScene("blow-dryer");
        BlowUpWatch watch(rendered.world);
        const double alpha = stepToFrame(rendered, t, watch);
        EXPECT_EQ(state.scene.world.stepCount(), rendered.world.stepCount()) << t;
        EXPECT_EQ(state.scene.world.body(0).getPos(), rendered.world.body(0).getPos()) << t;
        EXPECT_EQ(state.alpha(), alpha) << t;
        EXPECT_NEAR(render::drawnTime(state.scene.world, state.alpha(), true), t, 1e-12) << t;
    }
    ViewerState state = loaded("blow-dryer");
    state.advanceTo(2.0);
    EXPECT_EQ(state.scene.world.stepCount(), 400u) << "2 s of 0.005 s steps, not one more";
}

TEST(ViewerState, DurationPausesTheRunAtExactlyThatTime)
{
    ViewerState state = loaded("integrators");
    state.pauseAt = 0.5;
    for (int frame = 0; frame < 100 && !state.paused; ++frame)
        state.advance(0.07); // frames that do not divide 0.5 s nor the 0.01 s step
    ASSERT_TRUE(state.paused);
    EXPECT_EQ(state.scene.world.stepCount(), 50u);
    EXPECT_NEAR(render::drawnTime(state.scene.world, state.alpha(), true), 0.5, 1e-12);
    state.advance(0.07);
    EXPECT_EQ(state.scene.world.stepCount(), 50u) << "paused";
    state.apply(ViewerCommand::TogglePause); // play goes on past it
    state.advance(0.07);
    EXPECT_GT(state.scene.world.stepCount(), 50u);
    state.reset(); // and a restart pauses there again
    state.paused = false;
    for (int frame = 0; frame < 100 && !state.paused; ++frame)
        state.advance(0.07);
    EXPECT_EQ(state.scene.world.stepCount(), 50u);
}

TEST(ViewerState, EveryStepCommandOfAFrameIsTaken)
{
    ViewerState state = loaded("integrators");
    KeyInput keys;
    for (int n = 0; n < 3; ++n) {
        keys.onKey(46 /* GLFW_KEY_PERIOD */, 1 /* GLFW_PRESS */, 0);
        keys.onKey(46, 0 /* GLFW_RELEASE */, 0);
    }
    for (const ViewerCommand command : keys.take())
        state.apply(command);
    state.advance(1.0 / 60);
    EXPECT_TRUE(state.paused);
    EXPECT_EQ(state.scene.world.stepCount(), 3u);
    EXPECT_EQ(state.alpha(), 1.0) << "a single step shows the state it made";
    state.apply(ViewerCommand::Quit);
    EXPECT_TRUE(state.quit);
}

TEST(ViewerState, ChoosingAnIntegratorChangesTheWholeCoupledGroup)
{
    // Particles joined by springs share one integrator: the panel's choice for one of them
    // moves the group with it (and the reset state too), so the next step cannot refuse it.
    ViewerState state;
    state.load(parseScene(R"({ "particles": [
        { "name": "a", "position": [0, 1, 0] }, { "name": "b", "position": [1, 1, 0] },
        { "name": "c", "position": [2, 1, 0] }, { "name": "alone", "position": [3, 1, 0] } ],
      "forces": [ { "type": "spring", "particles": ["a", "b"], "stiffness": 10, "rest_length": 1 },
                  { "type": "spring", "particles": ["c", "b"], "stiffness": 10, "rest_length": 1 } ] })",
                          "group.json"));
    state.setIntegrator(2, Integrator::RK4);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(state.scene.world.body(i).getIntegrator(), Integrator::RK4) << i;
        EXPECT_EQ(state.initial.body(i).getIntegrator(), Integrator::RK4) << i;
    }
    EXPECT_EQ(state.scene.world.body(3).getIntegrator(), Integrator::SemiImplicitEuler);
    EXPECT_NO_THROW(state.stepWorld(10));
}

// Every blow-up pauses the viewer with its message instead of quitting it: a picogram box in the
// dryer (which used to escape as std::invalid_argument, "an orientation must be a non-zero finite
// quaternion", and quit the viewer) and a rope whose energy explodes inside the room (stiffness
// 1e300). A reset starts the run again.
TEST(ViewerState, EveryBlowUpPausesTheViewerWithItsMessage)
{
    const auto edited = [](const char* scene, const std::string& from, const std::string& to) {
        std::string json(builtinSceneText(scene));
        const std::size_t at = json.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        json.replace(at, from.size(), to);
        return parseScene(json, std::string(scene) + ".json");
    };
    struct Case {
        Scene scene;
        const char* says;
    };
    std::vector<Case> cases;
    cases.push_back({edited("blow-dryer-boxes", "\"mass\": 0.5", "\"mass\": 1e-12"), "body 'light'"});
    cases.push_back({edited("rope", "\"stiffness\": 500", "\"stiffness\": 1e300"), "no energy source"});
    for (Case& c : cases) {
        ViewerState state;
        state.load(std::move(c.scene));
        state.advanceTo(2.0);
        ASSERT_TRUE(state.error.has_value()) << c.says;
        EXPECT_NE(state.error->find(c.says), std::string::npos) << *state.error;
        EXPECT_TRUE(state.paused);
        EXPECT_LT(state.scene.world.time(), 2.0);
        const double stoppedAt = state.scene.world.time();
        state.advance(0.1); // paused: nothing moves
        EXPECT_EQ(state.scene.world.time(), stoppedAt);
        state.reset();
        EXPECT_FALSE(state.error.has_value());
        EXPECT_EQ(state.scene.world.time(), 0.0);
    }
}

// A 10 x 10 cloth is one row of the panel, not 100: one group with its name and count, one
// integrator for the whole system (applied live and kept by reset), its pins left fixed.
TEST(ViewerState, AClothIsOneRowWithOneIntegratorForTheWholeSystem)
{
    ViewerState state = loaded("cloth-in-the-dryer");
    ASSERT_EQ(state.groups.size(), 1u);
    const render::BodyGroup& sheet = state.groups[0];
    EXPECT_EQ(sheet.kind, render::BodyGroup::Kind::Cloth);
    EXPECT_EQ(sheet.label, "cloth sheet: 10 x 10 particles");
    EXPECT_EQ(sheet.members.size(), state.scene.world.bodyCount());
    state.setGroupIntegrator(0, Integrator::RK4);
    state.setGroupRestitution(0, 0.2);
    state.reset();
    for (const std::size_t i : sheet.members) {
        const Body& body = state.scene.world.body(i);
        if (!body.isFixed()) {
            EXPECT_EQ(body.getIntegrator(), Integrator::RK4) << i;
        }
        EXPECT_EQ(body.getCor(), 0.2) << i;
    }
    EXPECT_NO_THROW(state.stepWorld(5));
}

// The plots: a particle's height and energy, a rope's total energy over its start, and for a
// rigid body the components of omega in its own frame; in zero gravity no height (it is flat).
TEST(ViewerState, EachGroupGetsThePlotsThatShowWhatItDoes)
{
    const ViewerState integrators = loaded("integrators");
    EXPECT_EQ(plotKinds(integrators.scene.world, integrators.groups[1]),
              (std::vector<PlotKind>{PlotKind::Height, PlotKind::EnergyRatio}));
    const ViewerState dice = loaded("dice");
    EXPECT_EQ(plotKinds(dice.scene.world, dice.groups[0]),
              (std::vector<PlotKind>{PlotKind::Height, PlotKind::BodySpin, PlotKind::EnergyRatio}));
    const ViewerState racket = loaded("tennis-racket");
    EXPECT_EQ(plotKinds(racket.scene.world, racket.groups[0]),
              (std::vector<PlotKind>{PlotKind::BodySpin, PlotKind::EnergyRatio}));

    // The rope's energy plot is its particles' total over their total at the start.
    ViewerState rope = loaded("rope");
    EXPECT_EQ(plotKinds(rope.scene.world, rope.groups[0]), std::vector<PlotKind>{PlotKind::EnergyRatio});
    rope.advanceTo(0.5);
    const std::vector<double> now = rope.scene.world.energies(), start = rope.initial.energies();
    const double ratio = render::groupEnergy(rope.groups[0], now) / render::groupEnergy(rope.groups[0], start);
    EXPECT_NEAR(rope.plots[0].energyRatio.values().back(), ratio, 1e-6);
    EXPECT_LT(ratio, 1.0) << "damping, drag and bounces take energy";
}

// The tennis racket spins about its middle (z) axis: omega_z in its own frame starts at +6 rad/s
// and the flip turns it to about -6 within 4 s, while the world-frame omega keeps pointing near L.
// The plots sample every 1/60 s of simulated time, whatever dt (0.002 s here).
TEST(ViewerState, TheTennisRacketsSpinPlotShowsItsFlip)
{
    ViewerState state = loaded("tennis-racket");
    state.advanceTo(4.0);
    const std::vector<float>& z = state.plots[0].spin[2].values();
    EXPECT_EQ(z.size(), 241u) << "t = 0 and every 1/60 s to 4 s";
    EXPECT_NEAR(z.front(), 6.0f, 0.01f);
    EXPECT_LT(*std::min_element(z.begin(), z.end()), -5.5f);
    const std::vector<float>& e = state.plots[0].energyRatio.values();
    EXPECT_NEAR(*std::min_element(e.begin(), e.end()), 1.0f, 1e-6f) << "free of torques: energy kept";
}

// n, j and a toggle the contacts, joint frames and axes; c puts the camera back where --camera
// put it at the start.
TEST(ViewerState, KeysToggleTheMarksAndCReturnsToTheStartsCamera)
{
    ViewerState state;
    state.cameraChoice = parseCamera("0,2,6,0,1,0");
    state.load(loadScene("dice"));
    EXPECT_NEAR(glm::length(state.camera.eye() - glm::vec3(0, 2, 6)), 0.0f, 1e-5f);
    KeyInput keys;
    for (const int key : {78 /* N */, 74 /* J */, 65 /* A */, 67 /* C */})
        keys.onKey(key, 1 /* GLFW_PRESS */, 0);
    state.camera.orbit(1.0f, 0.2f);
    for (const ViewerCommand command : keys.take())
        state.apply(command);
    EXPECT_TRUE(state.settings.contacts);
    EXPECT_TRUE(state.settings.joints);
    EXPECT_TRUE(state.settings.axes);
    EXPECT_NEAR(glm::length(state.camera.eye() - glm::vec3(0, 2, 6)), 0.0f, 1e-5f);
    state.apply(ViewerCommand::ToggleContacts);
    EXPECT_FALSE(state.settings.contacts);
}

// --clock: a frame of 0.055 s at dt 0.01 s is five steps of dt with the fixed clock (the rest
// kept for the next frame and drawn by interpolation), five of dt and one of 0.005 s with the
// semi-fixed clock, one step of 0.055 s with the variable clock; the last two do not interpolate.
TEST(ViewerState, EachClockStepsAFrameItsWay)
{
    struct Expected {
        ClockKind clock;
        int steps;
        double time, lastStep;
    };
    for (const Expected& e : {Expected{ClockKind::Fixed, 5, 0.05, 0.01}, Expected{ClockKind::SemiFixed, 6, 0.055, 0.005},
                              Expected{ClockKind::Variable, 1, 0.055, 0.055}}) {
        ViewerState state = loaded("integrators");
        state.clockKind = e.clock;
        state.advance(0.055);
        EXPECT_EQ(state.stepsThisFrame, e.steps) << clockName(e.clock);
        EXPECT_NEAR(state.scene.world.time(), e.time, 1e-12) << clockName(e.clock);
        EXPECT_NEAR(state.scene.world.time() - state.scene.world.previousTime(), e.lastStep, 1e-12);
        if (e.clock == ClockKind::Fixed) {
            EXPECT_NEAR(state.alpha(), 0.5, 1e-9);
        } else {
            EXPECT_EQ(state.alpha(), 1.0) << clockName(e.clock);
        }
    }
}

TEST(ViewerState, TheVariableClockPausesOnTheFrameThatReachesTheDurationAndPlaysOn)
{
    ViewerState state = loaded("integrators");
    state.clockKind = ClockKind::Variable;
    state.pauseAt = 0.5;
    for (int frame = 0; frame < 100 && !state.paused; ++frame)
        state.advance(0.07);
    ASSERT_TRUE(state.paused);
    EXPECT_NEAR(state.scene.world.time(), 0.56, 1e-9); // eight frames of 0.07 s
    state.apply(ViewerCommand::TogglePause);
    state.advance(0.07);
    EXPECT_FALSE(state.paused);
    EXPECT_NEAR(state.scene.world.time(), 0.63, 1e-9);
}
