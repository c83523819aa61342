// The practical's class diagram, made real: Particle's defaults and Body's accessors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pba/particle.hpp"
#include "support/special_values.hpp"

using namespace pba;

using pba::test::kInf;
using pba::test::kNaN;

TEST(Particle, DefaultsFollowThePractical)
{
    Particle p;
    EXPECT_EQ(p.getMass(), 1.0);
    EXPECT_EQ(p.getCor(), 1.0);
    EXPECT_EQ(p.getVel(), dvec3(0.0));
    EXPECT_EQ(p.getAcc(), dvec3(0.0));
    EXPECT_FALSE(p.isFixed());
    EXPECT_EQ(p.getMesh().vertices().size(), 4u);
    EXPECT_EQ(p.getMesh().indices().size(), 6u);
    // Every particle's quad is one geometry, not a copy each (a cloth has thousands).
    EXPECT_EQ(Particle().getMesh().vertices().data(), p.getMesh().vertices().data());
    EXPECT_FLOAT_EQ(p.getMesh().getScale()[0][0], 0.1f);
    EXPECT_FLOAT_EQ(p.getMesh().getScale()[1][1], 0.1f);
    // Rotated by pi/2 about x: the quad's +y axis maps to +z, so it lies in the xz plane.
    const glm::vec4 y = p.getMesh().getRotate() * glm::vec4(0, 1, 0, 0);
    EXPECT_NEAR(y.z, 1.0f, 1e-6f);
    EXPECT_NEAR(y.y, 0.0f, 1e-6f);
}

// One truth: the body's position says where its mesh is drawn; the mesh has none of its own.
TEST(Body, TheMeshIsDrawnWhereTheBodyIs)
{
    Particle p;
    p.setPos(dvec3(1.5, -2.0, 3.25));
    EXPECT_EQ(p.getPos(), dvec3(1.5, -2.0, 3.25));
    EXPECT_EQ(glm::vec3(p.getTranslate()[3]), glm::vec3(1.5f, -2.0f, 3.25f));
    p.setPos(1, 7.0);
    EXPECT_EQ(p.getPos(), dvec3(1.5, 7.0, 3.25));
    EXPECT_EQ(p.getTranslate()[3][1], 7.0f);
    p.setState({dvec3(0.5, 1.0, -1.0), dvec3(0.0)});
    // The quad's corner (0.5, 0.5, 0) in its own frame: scaled by 0.1, turned into the xz plane
    // (+y to +z), then drawn at the body's position.
    const glm::vec4 corner = p.getModel() * glm::vec4(0.5f, 0.5f, 0.0f, 1.0f);
    EXPECT_NEAR(corner.x, 0.5f + 0.05f, 1e-6f);
    EXPECT_NEAR(corner.y, 1.0f, 1e-6f);
    EXPECT_NEAR(corner.z, -1.0f + 0.05f, 1e-6f);
}

TEST(Body, AccessorsReturnReferencesAndSetSingleComponents)
{
    Particle p;
    p.getVel() = dvec3(1, 2, 3);
    p.setVel(2, -4.0);
    EXPECT_EQ(p.getVel(), dvec3(1, 2, -4));
    p.getAcc().y = -9.81;
    EXPECT_EQ(p.getAcc().y, -9.81);
    p.setAcc(dvec3(0, 1, 0));
    EXPECT_EQ(p.getAcc(), dvec3(0, 1, 0));
}

// translate moves the body, and its mesh with it: the state is what moves.
TEST(Body, TranslateMovesTheBodyAndWhereItsMeshIsDrawn)
{
    Particle p;
    p.setPos(dvec3(1.0, 2.0, 3.0));
    p.translate(dvec3(1.0, 0.0, -0.5));
    EXPECT_EQ(p.getPos(), dvec3(2.0, 2.0, 2.5));
    EXPECT_EQ(p.getState().pos, dvec3(2.0, 2.0, 2.5));
    EXPECT_EQ(glm::vec3(p.getModel()[3]), glm::vec3(2.0f, 2.0f, 2.5f));
}

// Turning or scaling the mesh changes how the body is drawn about its centre, never where the
// body is or how it moves.
TEST(Body, TurningOrScalingTheMeshMovesNothing)
{
    Particle p;
    p.setPos(dvec3(1.0, 2.0, 3.0));
    p.setVel(dvec3(0.0, 1.0, 0.0));
    const glm::mat4 before = p.getMesh().getRotate();
    p.getMesh().rotate(std::numbers::pi_v<float>, glm::vec3(0, 1, 0));
    p.getMesh().scale(glm::vec3(2.0f));
    EXPECT_NE(p.getMesh().getRotate(), before);
    EXPECT_FLOAT_EQ(p.getMesh().getScale()[0][0], 0.2f);
    EXPECT_EQ(p.getPos(), dvec3(1.0, 2.0, 3.0));
    EXPECT_EQ(p.getVel(), dvec3(0.0, 1.0, 0.0));
    EXPECT_EQ(glm::vec3(p.getModel()[3]), glm::vec3(1.0f, 2.0f, 3.0f)) << "the mesh's centre stays on the body";
}

TEST(Body, RejectsBadMassAndRestitutionNamingTheValue)
{
    Particle p;
    for (double bad : {0.0, -1.0, kNaN, kInf}) {
        try {
            p.setMass(bad);
            FAIL() << "mass " << bad << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("mass"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(p.getMass(), 1.0);
    EXPECT_THROW(p.setCor(-0.1), std::invalid_argument);
    EXPECT_THROW(p.setCor(1.5), std::invalid_argument);
    EXPECT_THROW(p.setCor(kNaN), std::invalid_argument);
    try {
        p.setCor(1.5);
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("1.5"), std::string::npos) << e.what();
    }
    p.setCor(0.0);
    p.setCor(1.0);
    EXPECT_EQ(p.getCor(), 1.0);
}

TEST(Body, CloneIsDeep)
{
    Particle p;
    p.setName("a");
    p.setPos(dvec3(1, 2, 3));
    auto copy = p.clone();
    p.setPos(dvec3(0.0));
    EXPECT_EQ(copy->getPos(), dvec3(1, 2, 3));
    EXPECT_EQ(copy->getName(), "a");
}
