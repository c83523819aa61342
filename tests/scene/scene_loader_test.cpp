// Scenes: the built-ins load, and every kind of bad input is a SceneError naming the
// file, the field (as a JSON path) and the reason.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pba/blow_dryer.hpp"
#include "pba/rigid_body.hpp"
#include "pba/scene/scene.hpp"

using namespace pba;

TEST(SceneLoader, BuiltinScenesLoadByName)
{
    const auto names = builtinSceneNames();
    for (const char* expected : {"bouncing-cube", "integrators", "spring"})
        EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
    for (const auto& name : names) {
        const Scene scene = loadScene(name);
        EXPECT_EQ(scene.name, name);
        EXPECT_GT(scene.world.bodyCount() + scene.world.swarmCount(), 0u);
    }
}

TEST(SceneLoader, IntegratorsSceneIsTask3)
{
    const Scene scene = loadScene("integrators");
    ASSERT_EQ(scene.world.bodyCount(), 3u);
    EXPECT_TRUE(scene.world.body(0).isFixed());
    EXPECT_EQ(scene.world.body(1).getIntegrator(), Integrator::ForwardEuler);
    EXPECT_EQ(scene.world.body(2).getIntegrator(), Integrator::SemiImplicitEuler);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(scene.world.body(i).getPos().y, 2.0);
        EXPECT_EQ(scene.world.body(i).getVel(), dvec3(0.0));
        EXPECT_EQ(scene.world.body(i).getCor(), 1.0);
    }
    EXPECT_EQ(scene.world.ground(), 0.0);
}

TEST(SceneLoader, LoadsAFileByPath)
{
    const std::string path = testing::TempDir() + "/pba_scene_test.json";
    std::ofstream(path) << R"({"name": "mine", "dt": 0.02, "room": {"min": [0,0,0], "max": [1,1,1]},
        "particles": [{"name": "p", "position": [0.5, 0.5, 0.5]}]})";
    const Scene scene = loadScene(path);
    EXPECT_EQ(scene.name, "mine");
    EXPECT_EQ(scene.dt, 0.02);
    ASSERT_TRUE(scene.world.room().has_value());
    EXPECT_EQ(scene.world.planes().size(), 6u);
}

TEST(SceneLoader, ContactsSetHowTheRigidBodiesContactsAreSolved)
{
    const Scene fixed = parseScene(R"({"contacts": {"velocity_iterations": 10, "max_velocity_iterations": 10,
        "position_iterations": 3, "sleeping": false}})", "s.json");
    const ContactSettings& s = fixed.world.contactSettings();
    EXPECT_EQ(s.velocityIterations, 10);
    EXPECT_EQ(s.maxVelocityIterations, 10);
    EXPECT_EQ(s.positionIterations, 3);
    EXPECT_FALSE(s.sleeping);
    // More sweeps than the default's most: the most follows them.
    const Scene many = parseScene(R"({"contacts": {"velocity_iterations": 100}})", "s.json");
    EXPECT_EQ(many.world.contactSettings().velocityIterations, 100);
    EXPECT_EQ(many.world.contactSettings().maxVelocityIterations, 100);
    const ContactSettings defaults;
    const Scene none = parseScene("{}", "s.json");
    EXPECT_EQ(none.world.contactSettings().maxVelocityIterations, defaults.maxVelocityIterations);
}

struct BadScene {
    const char* json;
    const char* field;
    const char* reason;
};

// Shown in test names and failures instead of the struct's bytes.
void PrintTo(const BadScene& bad, std::ostream* os) { *os << bad.field << " " << bad.reason; }

class BadSceneTest : public testing::TestWithParam<BadScene> {};

/// The D and S cases below are a base object with some keys changed: "@forces{...}" or
/// "@swarms{...}" merges the braces' keys into the base's first force or swarm (a scene may not
/// repeat a key, so the change replaces it rather than following it).
std::string expand(const std::string& text)
{
    if (text.rfind("@", 0) != 0)
        return text;
    const std::size_t brace = text.find('{');
    const std::string list = text.substr(1, brace - 1);
    nlohmann::json base = nlohmann::json::parse(
        list == "forces"
            ? R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "forces": [{"type": "blow-dryer", "nozzle": [0, 0, 0],
                  "height": 3, "nozzle_radius": 0.2, "top_radius": 1, "strength": 30}]})"
            : R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "swarms": [{"name": "s", "count": 10,
                  "region": {"min": [0, 1, 0], "max": [1, 2, 1]}, "seed": 1}]})");
    const nlohmann::json changes = nlohmann::json::parse(text.substr(brace));
    for (const auto& [key, value] : changes.items())
        base[list][0][key] = value;
    return base.dump();
}

TEST_P(BadSceneTest, IsReportedWithFieldAndReason)
{
    const BadScene& bad = GetParam();
    try {
        parseScene(expand(bad.json), "bad.json");
        FAIL() << "accepted: " << bad.json;
    } catch (const SceneError& e) {
        EXPECT_EQ(e.file(), "bad.json");
        EXPECT_EQ(e.field(), bad.field) << e.what();
        EXPECT_NE(e.reason().find(bad.reason), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
    }
}

// A blow dryer, or a swarm, with keys changed (see expand).
#define D(change) "@forces{" change "}"
#define S(change) "@swarms{" change "}"
#define P(extra) R"({"particles": [{"name": "a", "position": [0, 1, 0])" extra "}]}"
#define R(extra) R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "rigid_bodies": [{"name": "r", "position": [0, 1, 0])" extra "}]}"
// A rope and a rigid body, and one joint between them.
#define J(joint) R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "ropes": [{"name": "rope", "from": [-1, 3, 0], "to": [1, 3, 0], "count": 5, "mass": 1, "stiffness": 100}], "rigid_bodies": [{"name": "r", "position": [0, 1, 0], "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}}], "joints": [)" joint "]}"
INSTANTIATE_TEST_SUITE_P(
    SceneLoader, BadSceneTest,
    testing::Values(BadScene{"{", "(document)", "malformed JSON"},
                    BadScene{"[1, 2]", "(scene)", "expected an object"},
                    BadScene{R"({"dt": "fast"})", "dt", "expected a number, got a string"},
                    BadScene{R"({"dt": 0})", "dt", "must be positive"},
                    BadScene{R"({"dt": -0.1})", "dt", "must be positive"},
                    BadScene{R"({"dt": 1e999})", "dt", "number overflow"},
                    BadScene{P(R"(, "mass": 1e999)"), "particles[0].mass", "number overflow"},
                    BadScene{P(R"(, "radius": -0.1)"), "particles[0].radius", "must not be negative"},
                    BadScene{P(R"(, "friction": -1)"), "particles[0].friction", "must not be negative"},
                    BadScene{R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "particles": [{"name": "a",
                                "position": [0, 0.05, 0], "radius": 0.1}]})",
                             "particles[0].radius", "a ball of radius 0.1 m at (0, 0.05, 0) reaches beyond"},
                    BadScene{R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "ropes": [{"name": "r",
                                "from": [0, 1, 0], "to": [1.95, 1, 0], "count": 3, "stiffness": 100, "radius": 0.1}]})",
                             "ropes[0].radius", "particle 'r[2]': a ball of radius 0.1 m"},
                    BadScene{R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "cloths": [{"name": "c",
                                "origin": [0, 1, 0], "across": [1, 0, 0], "down": [0, 0, 1], "columns": 2,
                                "rows": 2, "friction": -0.2}]})",
                             "cloths[0].friction", "must not be negative"},
                    BadScene{S(R"("radius": -1)"), "swarms[0].radius", "must not be negative"},
                    BadScene{S(R"("collide": true)"), "swarms[0].collide", "need a \"radius\" to collide"},
                    BadScene{S(R"("collide": true, "radius": 0.01, "region": {"min": [0, 1, 0], "max": [0, 1, 0]})"),
                             "swarms[0].region", "would all start at one point, with no direction to part along"},
                    BadScene{S(R"("radius": 1.5)"), "swarms[0].radius", "its region's corner: a ball of radius 1.5"},
                    BadScene{R"({"duration": 0})", "duration", "must be positive"},
                    BadScene{R"({"gravity": [0, -9.81]})", "gravity", "array of 3 numbers"},
                    BadScene{R"({"gravty": [0, -9.81, 0]})", "gravty", "unknown key"},
                    BadScene{R"({"collision_response": "bounce"})", "collision_response", "unknown collision response"},
                    BadScene{R"({"contacts": {"velocity_iterations": 0}})", "contacts.velocity_iterations",
                             "a whole number of sweeps from 1 to 1000, got 0"},
                    BadScene{R"({"contacts": {"position_iterations": 2.5}})", "contacts.position_iterations",
                             "a whole number of sweeps from 0 to 1000, got 2.5"},
                    BadScene{R"({"contacts": {"velocity_iterations": 12, "max_velocity_iterations": 8}})",
                             "contacts.max_velocity_iterations", "fewer than velocity_iterations (12)"},
                    BadScene{R"({"contacts": {"sweeps": 8}})", "contacts.sweeps", "unknown key"},
                    BadScene{R"({"room": {"min": [0, 0, 0], "max": [1, 0, 1]}})", "room.min", "must be below max"},
                    BadScene{R"({"ground": {"height": 0}, "room": {"min": [0,0,0], "max": [1,1,1]}})", "room", "not both"},
                    BadScene{R"({"ground": {"hieght": 0}})", "ground.hieght", "unknown key"},
                    BadScene{P(R"(, "mass": 0)"), "particles[0].mass", "must be positive"},
                    BadScene{P(R"(, "mass": -2)"), "particles[0].mass", "must be positive"},
                    BadScene{P(R"(, "restitution": 1.5)"), "particles[0].restitution", "must be in [0, 1]"},
                    BadScene{P(R"(, "restitution": -0.5)"), "particles[0].restitution", "must be in [0, 1]"},
                    BadScene{P(R"(, "integrator": "leapfrog")"), "particles[0].integrator", "unknown integrator"},
                    BadScene{P(R"(, "fixed": "yes")"), "particles[0].fixed", "expected a boolean"},
                    BadScene{P(R"(, "colour": "red")"), "particles[0].colour", "unknown key"},
                    BadScene{R"({"particles": [{"position": [0, 1, 0]}]})", "particles[0].name", "missing"},
                    BadScene{R"({"particles": [{"name": "a", "position": [0, 1, 0]}, {"name": "a", "position": [0, 1, 0]}]})",
                             "particles[1].name", "already named"},
                    BadScene{R"({"particles": [{"name": "a", "position": [0, 1, 0]}, {"name": "b", "position": [0, 1, 0], "mass": 0}]})",
                             "particles[1].mass", "must be positive"},
                    BadScene{R"({"ground": {"height": 0}, "particles": [{"name": "a", "position": [0, -1, 0]}]})",
                             "particles[0].position", "outside"},
                    BadScene{R"({"forces": [{"type": "magnet"}]})", "forces[0].type", "unknown force type"},
                    BadScene{R"({"particles": [{"name": "a", "position": [0, 1, 0]}], "forces": [{"type": "spring", "particle": "zz", "anchor": [0,0,0], "stiffness": 1}]})",
                             "forces[0].particle", "no particle or rigid body named"},
                    BadScene{R"({"particles": [{"name": "a", "position": [0, 1, 0]}], "forces": [{"type": "spring", "particle": "a", "anchor": [0,0,0], "stiffness": -1}]})",
                             "forces[0].stiffness", "must be positive"},
                    BadScene{R"({"forces": [{"type": "drag", "coefficient": -1}]})", "forces[0].coefficient",
                             "must not be negative"},
                    BadScene{D(R"("height": 0)"), "forces[0].height", "must be positive"},
                    BadScene{D(R"("height": -1)"), "forces[0].height", "must be positive"},
                    BadScene{D(R"("nozzle_radius": -0.1)"), "forces[0].nozzle_radius", "must not be negative"},
                    BadScene{D(R"("top_radius": -1)"), "forces[0].top_radius", "must not be negative"},
                    BadScene{D(R"("nozzle_radius": 0.5, "top_radius": 0.2)"), "forces[0].top_radius",
                             "must not be smaller than nozzle_radius"},
                    BadScene{D(R"("axis": [0, 0, 0])"), "forces[0].axis", "zero vector"},
                    BadScene{D(R"("air_density": 1.2)"), "forces[0].air_density", "needs air_speed"},
                    BadScene{D(R"("air_speed": 10, "air_density": -1)"), "forces[0].air_density",
                             "must not be negative"},
                    BadScene{D(R"("air_speed": 10, "air_density": 1.2, "drag_coefficient": 0)"),
                             "forces[0].drag_coefficient", "must be positive"},
                    BadScene{D(R"("strength": "strong")"), "forces[0].strength", "expected a number"},
                    BadScene{D(R"("axial_falloff": "cubic")"), "forces[0].axial_falloff", "unknown value 'cubic'"},
                    BadScene{D(R"("radial_falloff": 2)"), "forces[0].radial_falloff", "expected a string"},
                    BadScene{D(R"("direction": "sideways")"), "forces[0].direction", "unknown value 'sideways'"},
                    BadScene{D(R"("grille_depth": 0)"), "forces[0].grille_depth", "must be positive"},
                    BadScene{D(R"("nozzel": [0, 0, 0])"), "forces[0].nozzel", "unknown key"},
                    BadScene{S(R"("count": -1)"), "swarms[0].count", "whole number"},
                    BadScene{S(R"("count": 2.5)"), "swarms[0].count", "whole number"},
                    BadScene{S(R"("count": 1e9)"), "swarms[0].count", "whole number"},
                    BadScene{S(R"("mass": 0)"), "swarms[0].mass", "must be positive"},
                    BadScene{S(R"("restitution": 2)"), "swarms[0].restitution", "must be in [0, 1]"},
                    BadScene{S(R"("velocity_jitter": -1)"), "swarms[0].velocity_jitter", "must not be negative"},
                    BadScene{S(R"("integrator": "euler")"), "swarms[0].integrator", "unknown integrator"},
                    BadScene{S(R"("seed": -3)"), "swarms[0].seed", "whole number"},
                    BadScene{S(R"("seed": 9007199254740993)"), "swarms[0].seed",
                             "must be a whole number from 0 to 9007199254740992, got 9007199254740993"},
                    BadScene{S(R"("region": {"min": [0, 0.5, 0], "max": [0, 9, 0]})"), "swarms[0].region", "outside"},
                    BadScene{S(R"("region": {"min": [1, 1, 1], "max": [0, 1, 1]})"), "swarms[0].region.min",
                             "must not be above max"},
                    BadScene{S(R"("colour": 1)"), "swarms[0].colour", "unknown key"},
                    BadScene{R"({"dt": 0.01, "dt": 0.02})", "dt", "duplicate key"},
                    BadScene{P(R"(, "mass": 1, "mass": 2)"), "particles[0].mass", "duplicate key"},
                    BadScene{R"({"particles": [{"name": "a", "position": [0, 1, 0]}, {"name": "b", "position": [0, 2, 0], "mass": 1, "mass": 2}]})",
                             "particles[1].mass", "duplicate key"},
                    BadScene{P(R"(, "velocity": [1e300, 0, 0])"), "particles[0].velocity", "kinetic energy"},
                    BadScene{R"({"particles": [{"name": "a\tb", "position": [0, 1, 0]}]})", "particles[0].name",
                             "control character"},
                    BadScene{R(R"(, "shape": {"type": "cone"})"), "rigid_bodies[0].shape.type", "unknown shape 'cone'"},
                    BadScene{R(""), "rigid_bodies[0].shape", "missing"},
                    BadScene{R(R"(, "shape": {"type": "box", "size": [1, 0, 1]})"), "rigid_bodies[0].shape.size",
                             "every side must be positive"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": -1})"), "rigid_bodies[0].shape.radius",
                             "must be positive"},
                    BadScene{R(R"(, "shape": {"type": "cylinder", "radius": 1})"), "rigid_bodies[0].shape.height", "missing"},
                    BadScene{R(R"(, "shape": {"type": "box", "size": [1, 1, 1], "radius": 2})"),
                             "rigid_bodies[0].shape.radius", "unknown key"},
                    BadScene{R(R"(, "shape": {"type": "mesh", "path": "die.obj"})"), "rigid_bodies[0].shape.path",
                             "cannot name a mesh file"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": 0.1}, "orientation": [0, 0, 0, 0])"),
                             "rigid_bodies[0].orientation", "must not be zero"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": 0.1}, "orientation": [1, 0, 0])"),
                             "rigid_bodies[0].orientation", "four finite numbers"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "density": 2)"),
                             "rigid_bodies[0].mass", "not both"},
                    BadScene{R(R"(, "shape": {"type": "box", "size": [1e200, 1e200, 1e200]})"), "rigid_bodies[0].shape.size",
                             "too large"},
                    BadScene{R(R"(, "shape": {"type": "box", "size": [0.2, 0.2, 0.3]}, "die": true)"),
                             "rigid_bodies[0].die", "a die is a cube: its shape must be a box of three equal sides"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": 0.1}, "die": true)"), "rigid_bodies[0].die",
                             "a die is a cube"},
                    BadScene{R(R"(, "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "die": 1)"), "rigid_bodies[0].die",
                             "expected a boolean"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": 0.1}, "friction": -1)"),
                             "rigid_bodies[0].friction", "must not be negative"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": 0.1}, "restitution": 2)"),
                             "rigid_bodies[0].restitution", "must be in [0, 1]"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": 0.1}, "angular_velocity": [1e300, 0, 0])"),
                             "rigid_bodies[0].angular_velocity", "not finite"},
                    BadScene{R(R"(, "shape": {"type": "sphere", "radius": 0.1}, "position": [9, 1, 0])"),
                             "rigid_bodies[0].position", "duplicate key"},
                    BadScene{R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "rigid_bodies": [{"name": "r", "position": [0, 0, 0], "shape": {"type": "sphere", "radius": 0.1}}]})",
                             "rigid_bodies[0].position", "reaches 0.1 m through the floor"},
                    BadScene{J(R"({"type": "hindge", "bodies": ["r"], "anchor": [0, 1, 0]})"), "joints[0].type",
                             "did you mean 'hinge'?"},
                    BadScene{J(R"({"type": "ball", "bodies": ["rr"], "anchor": [0, 1, 0]})"), "joints[0].bodies[0]",
                             "no body is named 'rr': did you mean 'r'?"},
                    BadScene{J(R"({"type": "hinge", "bodies": ["r", "rope[2]"], "anchor": [0, 1, 0], "axis": [0, 0, 1]})"),
                             "joints[0]", "a hinge joint needs two rigid bodies, and 'rope[2]' is a particle"},
                    BadScene{J(R"({"type": "ball", "bodies": ["rope[2]"], "anchor": [0, 1, 0]})"), "joints[0]",
                             "a joint joins a particle to a rigid body, and 'rope[2]' is joined to the world"},
                    BadScene{J(R"({"type": "distance", "bodies": ["rope[1]", "rope[2]"], "anchors": [[0, 1, 0], [0, 2, 0]]})"),
                             "joints[0]", "and 'rope[1]' is joined to a particle"},
                    BadScene{R"({"rigid_bodies": [{"name": "table", "fixed": true, "position": [0, 1, 0], "shape": {"type": "box", "size": [1, 0.1, 1]}}, {"name": "b", "position": [0, 1.07, 0], "shape": {"type": "box", "size": [0.1, 0.1, 0.1]}}]})",
                             "rigid_bodies[1].position", "the box at its orientation starts 0.03 m inside the fixed body 'table'"},
                    BadScene{R"({"rigid_bodies": [{"name": "s", "position": [0, 1, 0], "shape": {"type": "sphere", "radius": 0.1}}, {"name": "t", "fixed": true, "position": [0, 1, 0], "shape": {"type": "box", "size": [1, 1, 1]}}]})",
                             "rigid_bodies[0].position", "the sphere starts 0.6 m inside the fixed body 't'"},
                    BadScene{R"({"rigid_bodies": [{"name": "a", "position": [0, 0.15, 0], "shape": {"type": "box", "size": [0.3, 0.3, 0.3]}}, {"name": "b", "position": [0.1, 0.3, 0], "shape": {"type": "box", "size": [0.3, 0.3, 0.3]}}]})",
                             "rigid_bodies[1].position", "the box at its orientation starts 0.15 m inside the body 'a': bodies that collide must start apart"},
                    BadScene{R"({"rigid_bodies": [{"name": "a", "position": [0, 1, 0], "shape": {"type": "sphere", "radius": 0.2}}, {"name": "b", "position": [0.3, 1, 0], "shape": {"type": "sphere", "radius": 0.2}}, {"name": "c", "position": [0.6, 1, 0], "shape": {"type": "sphere", "radius": 0.2}}], "joints": [{"type": "ball", "bodies": ["a", "b"], "anchor": [0.15, 1, 0]}]})",
                             "rigid_bodies[2].position", "the sphere starts 0.1 m inside the body 'b'"},
                    BadScene{R"({"particles": [{"name": "s[0]", "position": [0, 1, 0]}], "swarms": [{"name": "s", "count": 10, "region": {"min": [0, 1, 0], "max": [1, 2, 1]}}]})",
                             "swarms[0].name", "its particles' rows would be named s[0], s[1], ..., and 's[0]' is already a body's name"},
                    BadScene{J(R"({"type": "distance", "bodies": ["r"], "anchors": [[0, 1, 0], [1, 1, 0]], "length": 0.5})"),
                             "joints[0].length", "its anchors are 1 m apart, not 0.5"},
                    BadScene{R"({"rigid_bodies": [{"name": "t", "fixed": true, "position": [0, 1, 0], "shape": {"type": "sphere", "radius": 0.1}}], "joints": [{"type": "ball", "bodies": ["t"], "anchor": [0, 1, 0]}]})",
                             "joints[0].bodies", "joins 't' to the world, and it is fixed"},
                    BadScene{R"({"rigid_bodies": [{"name": "t", "fixed": true, "position": [0, 1, 0], "shape": {"type": "sphere", "radius": 0.1}}, {"name": "u", "fixed": true, "position": [1, 1, 0], "shape": {"type": "sphere", "radius": 0.1}}], "joints": [{"type": "fixed", "bodies": ["t", "u"]}]})",
                             "joints[0].bodies", "joins 't' and 'u', and both are fixed"},
                    BadScene{J(R"({"type": "ball", "bodies": ["r"], "anchor": [0, 1, 0], "collide": true})"),
                             "joints[0].collide", "belongs to a joint of two bodies"},
                    BadScene{J(R"({"type": "ball", "bodies": ["r", "rope[2]"], "anchor": [0, 3, 0], "collide": 1})"),
                             "joints[0].collide", "expected a boolean, got a number"},
                    BadScene{R"({"camera": {"position": [0, 1, 0], "target": [0, 1, 0.05]}})", "camera.position",
                             "must be 0.1 to 1000 m from the target, got 0.05 m"},
                    BadScene{R"({"camera": {"position": [0, 9, 0], "target": [0, 1, 0.01]}})", "camera.position",
                             "is straight above the target"},
                    BadScene{R"({"camera": {"position": [0, 1, 5], "target": [0, 1, 0], "up": [0, 1, 0]}})",
                             "camera.up", "unknown key"},
                    BadScene{R"({"camera": {"position": [0, 1, 5]}})", "camera.target", "required"},
                    BadScene{J(R"({"type": "ball", "bodies": ["r", "rope[2]"], "anchor": [0, 1, 0]})"),
                             "joints[0].anchor", "must be at the particle 'rope[2]', (0, 3, 0), not 2 m from it"},
                    BadScene{J(R"({"type": "ball", "bodies": ["r"], "anchor": [0, 1e300, 0]})"),
                             "joints[0].anchor", "is 1e+300 m from 'r': an anchor must be within 1e+06 m"},
                    BadScene{J(R"({"type": "distance", "bodies": ["r"], "anchors": [[0, 1, 0], [0, 2, 0]], "length": 1e300, "stiffness": 10})"),
                             "joints[0].length", "must be at most 1e+06 m"},
                    BadScene{J(R"({"type": "distance", "bodies": ["r"], "anchors": [[0, 1, 0], [0, 2, 0]], "stiffness": 1e300})"),
                             "joints[0].stiffness", "must be at most 1e+15 N/m"},
                    BadScene{R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "ropes": [{"name": "rope", "from": [-1, 1, 0], "to": [1, 1, 0], "count": 5, "stiffness": 100, "radius": 0.02}], "rigid_bodies": [{"name": "r", "position": [0, 1, 0], "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}}]})",
                             "ropes[0]", "the particle 'rope[2]' (radius 0.02 m) starts 0.12 m inside the body 'r'"},
                    BadScene{R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "ropes": [{"name": "x", "from": [-1, 1, 0], "to": [1, 1, 0], "count": 5, "stiffness": 100}], "cloths": [{"name": "x", "origin": [-1, 2, 0], "across": [1, 0, 0], "down": [0, 0, 1], "columns": 3, "rows": 3, "stiffness": {"structural": 100}}]})",
                             "cloths[0].name", "'x' is already taken"},
                    BadScene{R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "swarms": [{"name": "s", "count": 10, "region": {"min": [-1, 1, -1], "max": [1, 2, 1]}, "radius": 1e-300, "collide": true, "seed": 1}]})",
                             "swarms[0].radius", "cannot be represented in single precision"},
                    BadScene{R(R"(, "shape": {"typ": "sphere", "radius": 0.1})"), "rigid_bodies[0].shape.typ",
                             "unknown key (did you mean \"type\"?)"},
                    BadScene{R"({"particles": [{"name": "a", "position": [0, 1, 0]}], "forces": [{"type": "spring", "particle": "a", "anchor": [0,2,0], "stiffness": 1, "attachment": [0.1, 0, 0]}]})",
                             "forces[0].attachment", "only a rigid body"},
                    BadScene{R"({"particles": [{"name": "a", "position": [0, 1, 0]}], "rigid_bodies": [{"name": "r", "shape": {"type": "sphere", "radius": 0.1}, "position": [0, 2, 0]}], "forces": [{"type": "spring", "particles": ["a", "r"], "stiffness": 1}]})",
                             "forces[0].particles", "'r' is a rigid body"}));
#undef R
#undef J
#undef S
#undef D
#undef P

// A rigid body of each shape, an OBJ mesh read relative to the scene file, and the defaults.
TEST(SceneLoader, AJointNamesARopesParticleByItsColumnName)
{
    Scene scene = parseScene(R"({"room": {"min": [-3, 0, -2], "max": [3, 4, 2]},
        "ropes": [{"name": "rope", "from": [0, 3.5, 0], "to": [0, 2.5, 0], "count": 5, "mass": 0.5, "stiffness": 500,
                   "pinned": ["start"]}],
        "rigid_bodies": [{"name": "crate", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1,
                          "position": [0, 2.4, 0]}],
        "joints": [{"type": "ball", "bodies": ["crate", "rope[4]"], "anchor": [0, 2.5, 0]}]})",
                             "hang.json");
    ASSERT_EQ(scene.world.jointCount(), 1u);
    const JointFrame frame = scene.world.jointFrame(0);
    EXPECT_EQ(frame.bodyB, scene.world.findBody("rope[4]"));
    EXPECT_EQ(frame.onA, frame.onB);
}

// Pi written to ten digits passes pi by 7e-12: it is read as pi, not refused as past it. A fixed
// body's velocities are read as zero (it never moves), so neither the summary's speed nor the
// world's energy counts them.
TEST(SceneLoader, LimitsOfPiToTenDigitsAndAFixedBodysVelocities)
{
    Scene scene = parseScene(R"({"room": {"min": [-3, 0, -2], "max": [3, 4, 2]},
        "rigid_bodies": [{"name": "post", "shape": {"type": "box", "size": [0.2, 1, 0.2]}, "position": [0, 0.5, 0],
                          "fixed": true, "velocity": [1, 0, 0], "angular_velocity": [0, 1e300, 0]},
                         {"name": "door", "shape": {"type": "box", "size": [1, 1, 0.1]}, "position": [0.7, 2, 0]}],
        "joints": [{"type": "hinge", "bodies": ["door"], "anchor": [0.2, 2, 0], "axis": [0, 1, 0],
                    "limits": [-3.1415926536, 3.1415926536]}]})",
                             "door.json");
    ASSERT_EQ(scene.world.jointCount(), 1u);
    const Body& post = scene.world.body(*scene.world.findBody("post"));
    EXPECT_EQ(post.getVel(), dvec3(0.0));
    EXPECT_EQ(static_cast<const RigidBody&>(post).getAngularVelocity(), dvec3(0.0));
}

// A scene may say where pictures of it look from; the rigid scenes place theirs on their action.
TEST(SceneLoader, ACameraKeyIsWherePicturesLookFrom)
{
    const Scene scene = parseScene(R"({"camera": {"position": [0.5, 2, 6], "target": [0, 1, 0]}})", "cam.json");
    ASSERT_TRUE(scene.camera);
    EXPECT_EQ(scene.camera->position, dvec3(0.5, 2.0, 6.0));
    EXPECT_EQ(scene.camera->target, dvec3(0.0, 1.0, 0.0));
    EXPECT_FALSE(parseScene("{}", "none.json").camera);
    EXPECT_TRUE(loadScene("newtons-cradle").camera);
}

TEST(SceneLoader, AJointsCollideKeyLetsItsBodiesCollide)
{
    for (const bool collide : {false, true}) {
        Scene scene = parseScene(fmt::format(R"({{"room": {{"min": [-2, 0, -2], "max": [2, 4, 2]}}, "rigid_bodies": [
            {{"name": "a", "shape": {{"type": "box", "size": [0.4, 0.2, 0.2]}}, "position": [0, 2, 0]}},
            {{"name": "b", "shape": {{"type": "box", "size": [0.2, 0.4, 0.2]}}, "position": [0.2995, 2, 0]}}],
            "joints": [{{"type": "fixed", "bodies": ["a", "b"]{}}}]}})",
                                             collide ? R"(, "collide": true)" : ""),
                                 "weld.json");
        scene.world.step(0.002);
        bool touch = false;
        for (const World::ContactPointView& p : scene.world.contactPoints())
            touch = touch || (p.bodyB && p.bodyA + *p.bodyB == 1u);
        EXPECT_EQ(touch, collide);
    }
}

// A direction is a direction at any length: scaled before it is normalised, an axis of 1e200 or
// 1e-200 (whose square overflows or vanishes) is the unit axis, as is such an orientation.
TEST(SceneLoader, DirectionsOfAnyFiniteLengthAreNormalised)
{
    for (const char* length : {"1e200", "1e-200", "3"}) {
        Scene scene = parseScene(fmt::format(R"({{"room": {{"min": [-2, 0, -2], "max": [2, 4, 2]}},
            "forces": [{{"type": "blow-dryer", "nozzle": [0, 0, 0], "axis": [0, {0}, 0], "height": 1, "top_radius": 1,
                         "strength": 1}}],
            "rigid_bodies": [{{"name": "a", "position": [0, 2, 0], "orientation": [{0}, 0, 0, 0],
                               "shape": {{"type": "box", "size": [0.2, 0.2, 0.2]}}}}],
            "joints": [{{"type": "hinge", "bodies": ["a"], "anchor": [0.5, 2, 0], "axis": [{0}, 0, 0]}}]}})",
                                             length),
                                 "s.json");
        const auto& box = static_cast<const RigidBody&>(scene.world.body(0));
        EXPECT_EQ(box.getOrientation(), dquat(1.0, 0.0, 0.0, 0.0)) << length;
        EXPECT_EQ(scene.world.jointFrame(0).axis, dvec3(1.0, 0.0, 0.0)) << length;
        ASSERT_EQ(blowDryers(scene.world).size(), 1u);
        EXPECT_EQ(blowDryers(scene.world).front().field.axis, dvec3(0.0, 1.0, 0.0)) << length;
        scene.world.step(0.002);
        EXPECT_TRUE(std::isfinite(box.getPos().x)) << length;
    }
}

TEST(SceneLoader, RigidBodiesOfEveryShapeLoadWithTheirKeys)
{
    const std::string dir = testing::TempDir();
    std::ofstream(dir + "/pba_tetra.obj") << "# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                             "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2/1/1 3/1/1 4/1/1\n";
    const std::string path = dir + "/pba_rigid_scene.json";
    std::ofstream(path) << R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]}, "rigid_bodies": [
        {"name": "box", "shape": {"type": "box", "size": [0.2, 0.4, 0.6]}, "density": 500, "position": [0, 1, 0],
         "orientation": [2, 0, 0, 0], "velocity": [1, 2, 3], "angular_velocity": [0, 1, 0], "restitution": 0.3,
         "friction": 0.7, "integrator": "implicit-gyroscopic"},
        {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 2, "position": [1, 1, 0]},
        {"name": "can", "shape": {"type": "cylinder", "radius": 0.1, "height": 0.3}, "position": [-1, 1, 0], "fixed": true},
        {"name": "tetra", "shape": {"type": "mesh", "path": "pba_tetra.obj"}, "position": [0, 2, 1]}]})";
    const Scene scene = loadScene(path);
    const World& world = scene.world;
    ASSERT_EQ(world.bodyCount(), 4u);
    for (std::size_t i = 0; i < 4; ++i)
        EXPECT_TRUE(world.isRigid(i));
    const auto& box = static_cast<const RigidBody&>(world.body(0));
    EXPECT_NEAR(box.getMass(), 500.0 * 0.2 * 0.4 * 0.6, 1e-12);
    EXPECT_EQ(box.getOrientation(), dquat(1.0, 0.0, 0.0, 0.0)); // normalised
    EXPECT_EQ(box.getCor(), 0.3);
    EXPECT_EQ(box.getFriction(), 0.7);
    EXPECT_EQ(box.getIntegrator(), Integrator::ImplicitGyroscopic);
    EXPECT_NEAR(glm::length(box.getAngularVelocity() - dvec3(0.0, 1.0, 0.0)), 0.0, 1e-12);
    const auto& ball = static_cast<const RigidBody&>(world.body(1));
    EXPECT_EQ(ball.getMass(), 2.0);
    EXPECT_EQ(ball.getCor(), 0.5);      // the default
    EXPECT_EQ(ball.getFriction(), 0.5); // the default
    EXPECT_TRUE(world.body(2).isFixed());
    const auto& tetra = static_cast<const RigidBody&>(world.body(3));
    EXPECT_NEAR(tetra.getMass(), 1000.0 / 6.0, 1e-9); // the default density, 1000 kg/m^3
    EXPECT_EQ(tetra.getShape().type, ShapeType::Mesh);
}

// A mesh that is not closed, or an OBJ line that cannot be read, is refused naming the file.
TEST(SceneLoader, ABadMeshFileIsRefusedWithTheReason)
{
    const std::string dir = testing::TempDir();
    std::ofstream(dir + "/pba_open.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir + "/pba_badline.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 9\n";
    for (const auto& [file, reason] : {std::pair{"pba_open.obj", "closed"}, std::pair{"pba_badline.obj", "line 3"},
                                       std::pair{"pba_missing.obj", "cannot be opened"}}) {
        const std::string path = dir + "/pba_bad_mesh_scene.json";
        std::ofstream(path) << R"({"rigid_bodies": [{"name": "m", "shape": {"type": "mesh", "path": ")" << file
                            << R"("}, "position": [0, 1, 0]}]})";
        try {
            loadScene(path);
            FAIL() << file;
        } catch (const SceneError& e) {
            EXPECT_EQ(e.field(), "rigid_bodies[0].shape.path") << e.what();
            EXPECT_NE(e.reason().find(file), std::string::npos) << e.what();
            EXPECT_NE(e.reason().find(reason), std::string::npos) << e.what();
        }
    }
}

// Text after a NUL byte was silently ignored; swarms that cannot fit in memory were made
// anyway, and killed by the kernel or std::bad_alloc long after.
TEST(SceneLoader, ANulByteAndSwarmsBeyondTheMemoryAreRefused)
{
    using namespace std::string_literals;
    try {
        parseScene("{\"dt\": 0.01}\0{\"dt\": 5}"s, "nul.json");
        FAIL() << "accepted a NUL byte";
    } catch (const SceneError& e) {
        EXPECT_NE(e.reason().find("NUL byte at offset 12"), std::string::npos) << e.what();
    }
    nlohmann::json scene = {{"ground", {{"height", 0}}}, {"swarms", nlohmann::json::array()}};
    for (int i = 0; i < 40; ++i) // 40 x 1e8 particles: 100 GB
        scene["swarms"].push_back({{"name", "s" + std::to_string(i)}, {"count", 100000000}, {"seed", 1},
                                   {"region", {{"min", {0, 1, 0}}, {"max", {0, 1, 0}}}}});
    try {
        parseScene(scene.dump(), "big.json");
        FAIL() << "made 100 GB of swarms";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.field().rfind("swarms[", 0), 0u) << e.what();
        EXPECT_NE(e.reason().find("of memory available"), std::string::npos) << e.what();
    }
}

// nlohmann's parse callback, which once watched for duplicate keys, made its parser rescan an
// array each time an object in it ended: a long list of particles took time in the square of its
// length. The loader is timed against a plain parse of the same text, linear on any machine and
// under any sanitizer: a quadratic loader takes many times as long at this length, and the
// loader's first pass, which builds nothing, less.
TEST(SceneLoader, ALongArrayIsReadInTimeLinearInItsLength)
{
    std::string json = R"({"ground": {"height": 0}, "particles": [)";
    for (int i = 0; i < 200000; ++i)
        json += fmt::format(R"({}{{"name": "p{}", {}"position": [0, 1, 0]}})", i > 0 ? ", " : "", i,
                            i == 1 ? R"("name": "twice", )" : "");
    json += "]}";
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    EXPECT_EQ(nlohmann::json::parse(json)["particles"].size(), 200000u);
    const auto parsed = Clock::now();
    try {
        parseScene(json, "long.json");
        FAIL() << "accepted a duplicate key";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.field(), "particles[1].name") << e.what();
        EXPECT_NE(e.reason().find("duplicate key"), std::string::npos) << e.what();
    }
    const auto loaded = Clock::now();
    EXPECT_LT(loaded - parsed, 3 * (parsed - start) + std::chrono::milliseconds(500))
        << "plain parse " << std::chrono::duration<double>(parsed - start).count() << " s, loader "
        << std::chrono::duration<double>(loaded - parsed).count() << " s";
}

// The parser keeps a record per level open, so a file of '[' alone took memory and time in
// proportion to its length before failing at its end; nesting is refused at the 65th level, long
// before (a message about the end of input would mean the whole file was read). 64 levels are
// still read, up to the scene's own checks.
TEST(SceneLoader, NestingDeeperThan64LevelsIsRefusedWhereItStarts)
{
    try {
        parseScene(std::string(100000, '['), "deep.json");
        FAIL() << "accepted 100,000 levels";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.field(), "(document)") << e.what();
        EXPECT_EQ(e.reason(), "nested deeper than 64 levels of objects and arrays") << e.what();
    }
    const auto nested = [](int arrays) {
        return R"({"gravity": )" + std::string(arrays, '[') + std::string(arrays, ']') + "}";
    };
    try {
        parseScene(nested(63), "deep.json"); // the object and 63 arrays: 64 levels
        FAIL() << "accepted an empty gravity";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.field(), "gravity") << e.what();
    }
    try {
        parseScene(nested(64), "deep.json");
        FAIL() << "accepted 65 levels";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.field(), "(document)") << e.what();
        EXPECT_NE(e.reason().find("nested deeper than 64 levels"), std::string::npos) << e.what();
    }
}

TEST(SceneLoader, MissingFileAndUnknownNameAreErrors)
{
    try {
        loadScene("/nonexistent/dir/scene.json");
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_EQ(e.file(), "/nonexistent/dir/scene.json");
        EXPECT_NE(e.reason().find("no such file"), std::string::npos);
    }
    EXPECT_THROW(loadScene("no-such-scene"), SceneError);
}

/// The one-line message parseScene gives for `json`, or "accepted".
std::string errorOf(const std::string& json)
{
    try {
        parseScene(json, "scene.json");
    } catch (const SceneError& e) {
        return e.what();
    }
    return "accepted";
}

// A misspelt key used to surface as whatever its absence caused next: "partcles" dropped the
// particles and the spring then found no particle named 'b'; "stifness" made stiffness missing.
// Each object's keys are now checked before anything of it is read.
TEST(SceneLoader, AnUnknownKeyIsReportedFirstWithTheKnownKeyItIsCloseTo)
{
    EXPECT_EQ(errorOf(R"({"partcles": [{"name": "b", "position": [0, 1, 0]}],
                          "forces": [{"type": "spring", "particle": "b", "anchor": [0, 2, 0], "stiffness": 1}]})"),
              R"(scene.json: partcles: unknown key (did you mean "particles"?))");
    EXPECT_EQ(errorOf(R"({"particles": [{"name": "b", "position": [0, 1, 0]}],
                          "forces": [{"type": "spring", "particle": "b", "anchor": [0, 2, 0], "stifness": 1}]})"),
              R"(scene.json: forces[0].stifness: unknown key (did you mean "stiffness"?))");
    // In a particle, before its bad mass; in a swarm's region; in a blow dryer; in the room.
    EXPECT_EQ(errorOf(R"({"particles": [{"name": "b", "position": [0, 1, 0], "mass": 0, "velcoity": [1, 0, 0]}]})"),
              R"(scene.json: particles[0].velcoity: unknown key (did you mean "velocity"?))");
    EXPECT_EQ(errorOf(expand(R"(@swarms{"region": {"min": [0, 1, 0], "mx": [1, 2, 1]}})")),
              R"(scene.json: swarms[0].region.mx: unknown key (did you mean "max"?))");
    EXPECT_EQ(errorOf(expand(R"(@forces{"nozle_radius": 0.1})")),
              R"(scene.json: forces[0].nozle_radius: unknown key (did you mean "nozzle_radius"?))");
    EXPECT_EQ(errorOf(R"({"room": {"min": [0, 0, 0], "max": [1, 1, 1], "Max": 2}})"),
              R"(scene.json: room.Max: unknown key (did you mean "max"?))");
    // A force's type is a key too; a misspelt type value gets the same help.
    EXPECT_EQ(errorOf(R"({"forces": [{"tpye": "drag", "coefficient": 1}]})"),
              R"(scene.json: forces[0].tpye: unknown key (did you mean "type"?))");
    EXPECT_EQ(errorOf(R"({"forces": [{"type": "sprign"}]})"),
              R"(scene.json: forces[0].type: unknown force type 'sprign' (did you mean "spring"?))");
    // A key of another force type is unknown in this one.
    EXPECT_EQ(errorOf(R"({"forces": [{"type": "drag", "coefficient": 1, "stiffness": 2}]})"),
              "scene.json: forces[0].stiffness: unknown key (expected one of: type, angular_coefficient, coefficient)");
}

// Springs tie named particles: a scene with swarms takes them, and the swarm feels nothing of
// them. (Every other scene force type acts on swarms too; a program's own force that cannot is
// refused by the World: tests/core/force_test.cpp.)
TEST(SceneLoader, ASpringInASwarmSceneTiesOnlyItsParticle)
{
    const std::string scene = R"({"room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
        "particles": [{"name": "a", "position": [0, 1, 0]}, {"name": "b", "position": [0.5, 1, 0]}],
        "swarms": [{"name": "s", "count": 10, "region": {"min": [0, 1, 0], "max": [1, 2, 1]}, "seed": 1}],
        "forces": [{"type": "drag", "coefficient": 0.1}, {"type": "blow-dryer", "nozzle": [0, 0, 0], "height": 3,
                    "nozzle_radius": 0.2, "top_radius": 1, "strength": 30},
                   {"type": "spring", "particle": "a", "anchor": [0, 2, 0], "stiffness": 1},
                   {"type": "spring", "particles": ["a", "b"], "stiffness": 1, "rest_length": 0.5}]})";
    EXPECT_EQ(errorOf(scene), "accepted");
}

TEST(SceneLoader, AnUnknownKeyFarFromEveryKnownOneGetsNoSuggestion)
{
    const std::string error = errorOf(R"({"particles": [{"name": "b", "position": [0, 1, 0], "colour": "red"}]})");
    EXPECT_EQ(error.rfind("scene.json: particles[0].colour: unknown key (expected one of: name, position,", 0), 0u)
        << error;
    EXPECT_EQ(error.find("did you mean"), std::string::npos) << error;
    // Two edits are too many for a three-letter key ("max" is not a typo of "mass").
    EXPECT_EQ(errorOf(R"({"particles": [{"name": "b", "position": [0, 1, 0], "max": 1}]})").find("did you mean"),
              std::string::npos);
    EXPECT_EQ(errorOf(R"({"wind": [1, 0, 0]})").find("did you mean"), std::string::npos);
}

TEST(SceneLoader, AMisspeltBuiltinSceneNameGetsASuggestion)
{
    try {
        loadScene("integrator");
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_STREQ(e.what(), R"(integrator: (scene): neither a built-in scene nor a file (did you mean "integrators"?))");
    }
}

TEST(SceneLoader, EveryBuiltinSceneHasAOneLineSummary)
{
    for (const auto& name : builtinSceneNames()) {
        const std::string summary = builtinSceneSummary(name);
        EXPECT_FALSE(summary.empty()) << name;
        EXPECT_LE(summary.size(), 80u) << name; // fits a help line
        EXPECT_EQ(loadScene(name).summary, summary) << name;
    }
    EXPECT_EQ(builtinSceneSummary("no-such-scene"), "");
}
