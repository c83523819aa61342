// What the picture shows of rigid bodies, as draw lists (no GL): a colour per body and per rope
// or cloth, faces told apart, the rods of joints always, and contacts, joint frames and axes
// only when asked for, where the world says they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "pba/scene/scene.hpp"
#include "render/rigid_view.hpp"
#include "render/world_view.hpp"

using namespace pba;
using namespace pba::render;

namespace {

DrawList drawn(const World& world, const ViewSettings& settings)
{
    DrawList list;
    buildDrawList(world, world, 1.0, settings, nullptr, list);
    return list;
}

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-4f) { return glm::length(a - b) < tolerance; }

/// Whether the list has a line from a to b (either way round).
bool hasLine(const std::vector<ColouredVertex>& lines, const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-4f)
{
    for (std::size_t k = 0; k + 1 < lines.size(); k += 2)
        if ((near(lines[k].position, a, tolerance) && near(lines[k + 1].position, b, tolerance)) ||
            (near(lines[k].position, b, tolerance) && near(lines[k + 1].position, a, tolerance)))
            return true;
    return false;
}

std::size_t linesOfColour(const std::vector<ColouredVertex>& lines, const glm::vec4& colour)
{
    std::size_t n = 0;
    for (std::size_t k = 0; k + 1 < lines.size(); k += 2)
        n += lines[k].colour == colour ? 1 : 0;
    return n;
}

} // namespace

// Every die a colour of its own (the tray's walls are fixed: grey); the rope's particles share the
// rope's one colour, its pin is grey, and the ball beside it has a colour of its own.
TEST(BodyColours, EveryBodyAndEveryRopeOrClothHasItsOwnColour)
{
    const Scene dice = loadScene("dice");
    const BodyGroups diceGroups(dice.world, dice.fabric);
    ASSERT_EQ(diceGroups.size(), dice.world.bodyCount());
    std::set<std::array<float, 3>> colours;
    for (const std::size_t i : dice.dice) {
        const glm::vec4 c = diceGroups.bodyColour(i);
        EXPECT_EQ(c, diceGroups[diceGroups.groupOf(i)].colour) << "drawn, bullet and plot: one colour";
        colours.insert({c.r, c.g, c.b});
    }
    EXPECT_EQ(colours.size(), dice.dice.size()) << "no two dice alike";

    Scene rope = parseScene(R"({"room": {"min": [-3, 0, -2], "max": [3, 4, 2]},
        "ropes": [{"name": "r", "from": [-2, 3, 0], "to": [2, 3, 0], "count": 5, "stiffness": 100, "pinned": ["start"]}],
        "particles": [{"name": "ball", "position": [0, 1, 0]}]})", "rope.json");
    const BodyGroups groups(rope.world, rope.fabric);
    ASSERT_EQ(groups.size(), 2u); // the ball (loaded first) and the rope
    const std::size_t r = groups[0].fabric() ? 0 : 1;
    const BodyGroup& line = groups[r];
    EXPECT_EQ(line.label, "rope r: 5 particles");
    ASSERT_EQ(line.members, rope.fabric.ropes[0].particles);
    for (std::size_t k = 1; k < 5; ++k)
        EXPECT_EQ(groups.bodyColour(line.members[k]), line.colour);
    EXPECT_NE(groups.bodyColour(line.members[0]), line.colour) << "the pin is drawn grey";
    EXPECT_NE(groups[1 - r].colour, line.colour) << "the ball";
    EXPECT_EQ(groups.groupOf(line.members[3]), r);
    // Deterministic: the same scene gets the same colours.
    EXPECT_EQ(BodyGroups(rope.world, rope.fabric)[1].colour, groups[1].colour);
}

// The rope is drawn in its group's colour: the legend's bullet, not a colour of its own.
TEST(BodyColours, TheRopeIsDrawnInItsLegendColour)
{
    const Scene rope = loadScene("rope");
    ViewSettings settings;
    settings.fabric = rope.fabric;
    const DrawList list = drawn(rope.world, settings);
    const glm::vec4 colour = BodyGroups(rope.world, rope.fabric)[0].colour;
    EXPECT_EQ(linesOfColour(list.lines, colour), rope.fabric.ropes[0].particles.size() - 1);
}

// A body's faces carry its colour and their direction in its own frame, from which the renderer
// shades each face apart (a box's along its axes); a die's also where on the die they are, its
// faces at +-1, for its pips. The tray's walls are no dice.
TEST(BodyColours, ABodysFacesCarryItsColourAndTheirDirectionInItsFrame)
{
    const Scene dice = loadScene("dice");
    ViewSettings settings;
    settings.dice = dice.dice;
    const DrawList list = drawn(dice.world, settings);
    ASSERT_EQ(list.surfaces.size(), 36 * dice.world.bodyCount()); // twelve triangles a box
    ASSERT_GT(dice.dice.size(), 30u);
    const BodyGroups groups(dice.world, dice.fabric);
    for (std::size_t i = 0; i < dice.world.bodyCount(); ++i) {
        const bool die = std::binary_search(dice.dice.begin(), dice.dice.end(), i);
        EXPECT_EQ(die, !dice.world.body(i).isFixed()) << dice.world.body(i).getName();
        for (std::size_t v = 36 * i; v < 36 * (i + 1); ++v) {
            const LitVertex& vertex = list.surfaces[v];
            EXPECT_EQ(vertex.colour, groups.bodyColour(i));
            const glm::vec3 a = glm::abs(vertex.bodyNormal);
            EXPECT_NEAR(a.x + a.y + a.z, 1.0f, 1e-5f) << "along one of the box's axes";
            EXPECT_NEAR(std::max({a.x, a.y, a.z}), 1.0f, 1e-5f);
            EXPECT_EQ(vertex.die, die ? 1.0f : 0.0f);
            if (die) {
                EXPECT_NEAR(glm::dot(vertex.onDie, vertex.bodyNormal), 1.0f, 1e-5f) << "on its face";
            }
        }
    }
}

// A pendulum's bob hangs from a rod drawn from its centre to the pivot, and the pivot is a small
// ball, with or without the joints toggle; the toggle adds the frame's dots on top.
TEST(JointMarks, RodsAreAlwaysDrawnAndFramesWhenAsked)
{
    const Scene pendulum = loadScene("pendulum");
    ViewSettings settings;
    DrawList list = drawn(pendulum.world, settings);
    const glm::vec3 bob(pendulum.world.body(0).getPos()), pivot(0.0f, 3.0f, 0.0f);
    EXPECT_TRUE(hasLine(list.lines, bob, pivot));
    EXPECT_TRUE(list.overlaySprites.empty());
    settings.joints = true;
    list = drawn(pendulum.world, settings);
    ASSERT_EQ(list.overlaySprites.size(), 2u);
    EXPECT_TRUE(near(list.overlaySprites[0].position, pivot)) << "the joint's point on the bob";

    const Scene chain = loadScene("chain"); // twelve hinges about z
    list = drawn(chain.world, settings);
    EXPECT_EQ(linesOfColour(list.overlayLines, kHingeAxisColour), chain.world.jointCount());
    for (std::size_t k = 0; k + 1 < list.overlayLines.size(); k += 2)
        if (list.overlayLines[k].colour == kHingeAxisColour) {
            const glm::vec3 axis = list.overlayLines[k + 1].position - list.overlayLines[k].position;
            EXPECT_NEAR(std::abs(glm::normalize(axis).z), 1.0f, 1e-5f);
        }
}

// A distance joint is a string between its two points: Newton's cradle's balls hang from them.
TEST(JointMarks, ADistanceJointIsAStringBetweenItsPoints)
{
    const Scene cradle = loadScene("newtons-cradle");
    const DrawList list = drawn(cradle.world, ViewSettings{});
    for (std::size_t j = 0; j < cradle.world.jointCount(); ++j) {
        const JointFrame frame = cradle.world.jointFrame(j);
        EXPECT_TRUE(hasLine(list.lines, glm::vec3(frame.onA), glm::vec3(frame.onB))) << j;
    }
}

// Each contact point of the last step, with a line the way it pushes the body: out of the floor
// (up) for the bottom slab of a stack; none unless asked for.
TEST(ContactMarks, EachContactPointWithItsPushOnlyWhenAsked)
{
    Scene stack = loadScene("box-stack");
    for (int n = 0; n < 20; ++n)
        stack.world.step(stack.dt);
    const auto contacts = stack.world.contactPoints();
    ASSERT_FALSE(contacts.empty());
    ViewSettings settings;
    EXPECT_TRUE(drawn(stack.world, settings).overlayLines.empty());
    settings.contacts = true;
    const DrawList list = drawn(stack.world, settings);
    ASSERT_EQ(list.overlaySprites.size(), contacts.size());
    ASSERT_EQ(list.overlayLines.size(), 2 * contacts.size());
    std::size_t floor = 0;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
        EXPECT_TRUE(near(list.overlaySprites[k].position, glm::vec3(contacts[k].point), 1e-3f));
        const glm::vec3 line = list.overlayLines[2 * k + 1].position - list.overlayLines[2 * k].position;
        EXPECT_NEAR(glm::dot(glm::normalize(line), -glm::normalize(glm::vec3(contacts[k].normal))), 1.0f, 1e-4f);
        EXPECT_GE(glm::length(line), 0.02f - 1e-6f);
        EXPECT_LE(glm::length(line), 0.3f + 1e-6f);
        if (!contacts[k].bodyB) {
            ++floor;
            EXPECT_GT(line.y, 0.0f) << "out of the floor";
        }
    }
    EXPECT_GT(floor, 0u);
}

// The racket's axes (its own frame), omega along omega and L along L, each arrow's length on the
// scale of turns a second; L stays put while omega wanders (the flip).
TEST(AxesMarks, AxesOmegaAndLArrowsOfEachRigidBody)
{
    Scene racket = loadScene("tennis-racket");
    for (int n = 0; n < 700; ++n) // 1.4 s: omega has left L's direction
        racket.world.step(racket.dt);
    ViewSettings settings;
    settings.axes = true;
    const DrawList list = drawn(racket.world, settings);
    const auto& body = static_cast<const RigidBody&>(racket.world.body(0));
    const glm::vec3 centre(body.getPos());
    for (int k = 0; k < 3; ++k) {
        dvec3 e(0.0);
        e[k] = 1.0;
        const glm::vec3 along(body.getOrientation() * e);
        const float r = 1.3f * float(body.getBoundingRadius());
        EXPECT_TRUE(hasLine(list.overlayLines, centre, centre + r * along, 1e-3f)) << "axis " << k;
    }
    const glm::vec3 w(body.getAngularVelocity()), L(body.getAngularMomentum());
    EXPECT_TRUE(hasLine(list.overlayLines, centre, centre + spinArrowLength(body) * glm::normalize(w), 1e-3f));
    EXPECT_TRUE(hasLine(list.overlayLines, centre, centre + momentumArrowLength(body) * glm::normalize(L), 1e-3f));
    EXPECT_LT(glm::dot(glm::normalize(w), glm::normalize(L)), 0.999f) << "omega is not along L in a flip";
    // About 6 rad/s, about one turn a second: 1.5 reaches, as kArrowPerTurn says.
    EXPECT_NEAR(spinArrowLength(body) / float(body.getBoundingRadius()),
                kArrowPerTurn * glm::length(w) / (2.0f * 3.14159265f), 1e-3f);
    settings.axes = false;
    EXPECT_TRUE(drawn(racket.world, settings).overlayLines.empty());
}
