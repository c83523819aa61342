// Forces through their interface: a program's own Force acts on bodies like a built-in one, is
// refused for a world with swarms unless it says what it does to a swarm, and every force is
// found by what it is through the visitor, not a type switch.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "pba/blow_dryer.hpp"
#include "pba/forces.hpp"
#include "pba/world.hpp"

using namespace pba;

namespace {

/// A program's own force: a steady wind pushing along x, F = m a, as a user would write one.
class Wind final : public ForceBase<Wind> {
public:
    explicit Wind(double a) : m_a(a) {}
    std::string_view type() const override { return "wind"; }
    dvec3 force(std::size_t, const Body& body, const dvec3&, const dvec3&) const override
    {
        return body.getMass() * dvec3(m_a, 0.0, 0.0);
    }

private:
    double m_a;
};

/// The same wind, which also says what it does to a swarm particle: an acceleration, as gravity's.
class SwarmWind final : public ForceBase<SwarmWind> {
public:
    explicit SwarmWind(double a) : m_a(a) {}
    std::string_view type() const override { return "swarm-wind"; }
    dvec3 force(std::size_t, const Body& body, const dvec3&, const dvec3&) const override
    {
        return body.getMass() * dvec3(m_a, 0.0, 0.0);
    }
    bool addToSwarmFields(SwarmFields& fields) const override
    {
        fields.gravity += Vec3<float>(float(m_a), 0.0f, 0.0f);
        return true;
    }

private:
    double m_a;
};

SwarmDesc smallSwarm()
{
    SwarmDesc desc;
    desc.name = "rain";
    desc.count = 8;
    desc.regionMin = dvec3(0.0, 1.0, 0.0);
    desc.regionMax = dvec3(1.0, 2.0, 1.0);
    return desc;
}

/// What the visitor says each force is.
struct Names final : ForceVisitor {
    std::string seen;
    void visit(const Gravity&) override { seen += "gravity "; }
    void visit(const Drag&) override { seen += "drag "; }
    void visit(const Spring&) override { seen += "spring "; }
    void visit(const BlowDryer&) override { seen += "blow-dryer "; }
    void visit(const Force& other) override { seen += "other:" + std::string(other.type()) + " "; }
};

} // namespace

// Constant acceleration a from rest: semi-implicit Euler gives v_n = n a dt exactly and
// x_n = x_0 + a dt^2 n (n + 1) / 2 (each step adds the new velocity), to rounding.
TEST(Force, AProgramsOwnForceActsOnBodies)
{
    World world;
    world.addForce(std::make_unique<Wind>(2.0));
    Particle p;
    p.setMass(3.0);
    p.setIntegrator(Integrator::SemiImplicitEuler);
    world.addParticle(p);
    const double dt = 0.01;
    const int n = 100;
    for (int i = 0; i < n; ++i)
        world.step(dt);
    EXPECT_NEAR(world.body(0).getVel().x, n * 2.0 * dt, 1e-12);
    EXPECT_NEAR(world.body(0).getPos().x, 2.0 * dt * dt * n * (n + 1) / 2.0, 1e-12);
    EXPECT_DOUBLE_EQ(world.acceleration(0, dvec3(0.0), dvec3(0.0)).x, 2.0);
    // A copy of the world clones it with the rest.
    const World copy(world);
    EXPECT_EQ(copy.force(0).type(), "wind");
}

TEST(Force, OneThatCannotActOnASwarmIsRefusedNamingItsType)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.addSwarm(smallSwarm());
    try {
        world.addForce(std::make_unique<Wind>(2.0));
        FAIL() << "a wind that cannot act on the swarm was taken";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()),
                  "a wind force cannot act on swarm 'rain': a swarm feels gravity, drag and blow dryers only");
    }
    EXPECT_EQ(world.forceCount(), 1u);
    // The other way round: a swarm is not added to a world with such a force.
    World bodies;
    bodies.addForce(std::make_unique<Wind>(2.0));
    EXPECT_THROW(bodies.addSwarm(smallSwarm()), std::invalid_argument);
    EXPECT_EQ(bodies.swarmCount(), 0u);
}

// Every particle of the swarm from rest under a constant acceleration: v = a dt after a step.
TEST(Force, OneThatSaysWhatItDoesToASwarmActsOnIt)
{
    World world;
    world.addSwarm(smallSwarm());
    world.addForce(std::make_unique<SwarmWind>(2.0));
    world.addForce(std::make_unique<Gravity>(dvec3(0, -1.0, 0)));
    EXPECT_EQ(world.swarmFields().gravity, Vec3<float>(2.0f, -1.0f, 0.0f));
    world.step(0.01);
    for (std::size_t i = 0; i < world.swarm(0).size(); ++i) {
        EXPECT_FLOAT_EQ(world.swarm(0).velocity(i).x, 0.02f);
        EXPECT_FLOAT_EQ(world.swarm(0).velocity(i).y, -0.01f);
        EXPECT_FLOAT_EQ(world.swarm(0).velocity(i).z, 0.0f);
    }
}

TEST(Force, TheBuiltInOnesAddTheirFieldsForSwarms)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.addForce(std::make_unique<Drag>(0.5));
    world.addForce(std::make_unique<Gravity>(dvec3(1, 0, 0)));
    BlowDryerField field;
    field.strength = 30.0;
    world.addForce(std::make_unique<BlowDryer>(field));
    world.addForce(std::make_unique<Drag>(0.25));
    const SwarmFields fields = world.swarmFields();
    EXPECT_EQ(fields.gravity, Vec3<float>(1.0f, -9.81f, 0.0f));
    EXPECT_EQ(fields.drag, 0.75f);
    ASSERT_EQ(fields.dryers.size(), 1u);
    EXPECT_EQ(fields.dryers[0].strength, 30.0f);
    EXPECT_EQ(world.gravity(), dvec3(1.0, -9.81, 0.0));
}

TEST(Force, TheVisitorMeetsEachForceAsWhatItIs)
{
    World world;
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    world.addForce(std::make_unique<Wind>(1.0));
    world.addForce(std::make_unique<Spring>(0, dvec3(0.0), 1.0, 1.0, 0.0));
    BlowDryerField field;
    field.strength = 12.0;
    world.addForce(std::make_unique<BlowDryer>(field));
    world.addForce(std::make_unique<Drag>(0.1));
    Names names;
    for (std::size_t i = 0; i < world.forceCount(); ++i)
        world.force(i).accept(names);
    EXPECT_EQ(names.seen, "gravity other:wind spring blow-dryer drag ");
    const auto dryers = blowDryers(world);
    ASSERT_EQ(dryers.size(), 1u);
    EXPECT_EQ(dryers[0].force, 3u);
    EXPECT_EQ(dryers[0].field.strength, 12.0);
}

// The editor reaches the force itself: what the viewer's dryer settings change.
TEST(Force, TheEditorChangesTheForceItVisits)
{
    World world;
    world.addForce(std::make_unique<BlowDryer>(BlowDryerField{}));
    struct Stronger final : ForceEditor {
        void visit(BlowDryer& dryer) override
        {
            BlowDryerField field = dryer.field();
            field.strength = 45.0;
            dryer.setField(field);
        }
    } stronger;
    world.force(0).accept(stronger);
    EXPECT_EQ(blowDryers(world).at(0).field.strength, 45.0);
    // The force follows the new field (its kernel is made anew, not left at the old strength).
    Particle p;
    const dvec3 x(0.0, 0.1, 0.0);
    EXPECT_EQ(world.force(0).force(0, p, x, dvec3(0.0)), blowDryerForce(blowDryers(world).at(0).field, x));
}
