// Swarms follow the same rules as particles: the same trajectories (within single precision),
// the same results whatever the thread count, and nobody leaves the room.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <set>

#include "pba/scene/scene.hpp"
#include "pba/detail/swarm_kernel.hpp"
#include "pba/world.hpp"
#include "support/fast_swarm.hpp"

using namespace pba;

namespace {

/// Changes every blow dryer of the world through its setter (which remakes its kernel).
template <class Edit>
void editDryers(World& world, Edit&& edit)
{
    for (std::size_t f = 0; f < world.forceCount(); ++f)
        if (auto* dryer = dynamic_cast<BlowDryer*>(&world.force(f))) {
            BlowDryerField field = dryer->field();
            edit(field);
            dryer->setField(field);
        }
}

/// The blow-dryer-swarm scene with n particles.
World swarmWorld(std::size_t n, CollisionResponse response = CollisionResponse::Reflect)
{
    World world = loadScene("blow-dryer-swarm").world;
    SwarmDesc desc = world.swarm(0).desc();
    desc.count = n;
    world.swarm(0) = Swarm(desc);
    world.setCollisionResponse(response);
    return world;
}

/// One double-precision Particle for each of the swarm's particles, with its state and rules.
void addParticlesLike(World& world, const Swarm& swarm)
{
    for (std::size_t i = 0; i < swarm.size(); ++i) {
        Particle p;
        p.setPos(dvec3(swarm.position(i)));
        p.setVel(dvec3(swarm.velocity(i)));
        p.setCor(swarm.restitution());
        p.setIntegrator(swarm.integrator());
        world.addParticle(p);
    }
}

} // namespace

TEST(Swarm, InitialStatesDependOnSeedAndIndexOnly)
{
    World a = swarmWorld(1000);
    World b = swarmWorld(200);
    for (std::size_t i = 0; i < 200; ++i) {
        EXPECT_EQ(a.swarm(0).position(i), b.swarm(0).position(i));
        EXPECT_EQ(a.swarm(0).velocity(i), b.swarm(0).velocity(i));
    }
    const SwarmDesc& desc = a.swarm(0).desc();
    for (std::size_t i = 0; i < 1000; ++i) {
        const dvec3 x(a.swarm(0).position(i));
        EXPECT_TRUE(x.x >= desc.regionMin.x - 1e-6 && x.x <= desc.regionMax.x + 1e-6);
        EXPECT_TRUE(x.y >= desc.regionMin.y - 1e-6 && x.y <= desc.regionMax.y + 1e-6);
    }
}

// A swarm particle and a double-precision Particle from the same state, under the same
// forces and collisions, stay together to single precision: over 1 s of falling, bouncing and
// being blown (500 steps) the float path drifts from the double one by a few float roundings
// per step, amplified by the bounces; 2 mm bounds it with margin.
TEST(Swarm, FollowsTheSameTrajectoriesAsParticles)
{
    for (CollisionResponse response : kAllCollisionResponses) {
        for (Integrator integrator : kAllIntegrators) {
            World world = swarmWorld(64, response);
            world.swarm(0).setIntegrator(integrator);
            const Swarm& swarm = world.swarm(0);
            addParticlesLike(world, swarm);
            for (int n = 0; n < 500; ++n)
                world.step(0.002);
            double worst = 0.0;
            for (std::size_t i = 0; i < swarm.size(); ++i)
                worst = std::max(worst, glm::length(dvec3(swarm.position(i)) - world.body(i).getPos()));
            EXPECT_LT(worst, 2e-3) << collisionResponseName(response) << " " << integratorName(integrator);
        }
    }
}

// Particles in the hole of a dryer too weak to lift them (its push in the shaft below their
// weight) slide around the shaft's wall on the grille for good. The wall is resolved in the same
// vectorised pass as the floor (pushIntoShaft, the function a Particle's rule calls): they stay
// within the shaft and follow the Particles, bouncing off the wall over and over.
TEST(Swarm, ParticlesSlidingInTheShaftStayWithinItsWallAsParticlesDo)
{
    constexpr float kHoleRadius = 0.25f; // the blow-dryer-swarm scene's nozzle radius
    for (CollisionResponse response : {CollisionResponse::Reflect, CollisionResponse::Clamp}) {
        World world = swarmWorld(64, response);
        const double strength = 0.5 * 9.81 * world.swarm(0).mass();
        editDryers(world, [&](BlowDryerField& field) { field.strength = strength; });
        Swarm& swarm = world.swarm(0);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            const float angle = 0.37f * float(i);
            const float r = 0.2f * float(i % 8) / 8.0f;
            const Vec3<float> x(r * std::cos(angle), -0.03f, r * std::sin(angle));
            const Vec3<float> v(1.5f * std::cos(1.7f * angle), 0.0f, 1.5f * std::sin(1.7f * angle));
            swarm.set(i, x, v);
        }
        addParticlesLike(world, swarm);
        double worst = 0.0;
        for (int n = 0; n < 300; ++n) {
            world.step(0.002);
            for (std::size_t i = 0; i < swarm.size(); ++i) {
                const Vec3<float> x = swarm.position(i);
                ASSERT_LT(std::hypot(x.x, x.z), kHoleRadius) << "particle " << i << " step " << n;
                ASSERT_LT(x.y, 0.0f) << "particle " << i << " step " << n;
                worst = std::max(worst, glm::length(dvec3(x) - world.body(i).getPos()));
            }
        }
        EXPECT_LT(worst, 2e-3) << collisionResponseName(response);
    }
}

// The loop is compiled for the forces a swarm meets (a dryer along +y or any axis, with drag
// or without): each variant follows the Particles as the built-in scene's does.
TEST(Swarm, FollowsParticlesWithDragAndATiltedDryer)
{
    for (const bool drag : {false, true}) {
        for (const bool tilted : {false, true}) {
            if (!drag && !tilted)
                continue; // the scene itself: FollowsTheSameTrajectoriesAsParticles
            World world = swarmWorld(64);
            if (drag)
                world.addForce(std::make_unique<Drag>(0.4));
            if (tilted)
                editDryers(world, [](BlowDryerField& field) { field.axis = glm::normalize(dvec3(0.3, 1.0, -0.2)); });
            ASSERT_EQ(world.swarmFields().drag, drag ? 0.4f : 0.0f);
            addParticlesLike(world, world.swarm(0));
            for (int n = 0; n < 500; ++n)
                world.step(0.002);
            double worst = 0.0;
            for (std::size_t i = 0; i < world.swarm(0).size(); ++i)
                worst = std::max(worst, glm::length(dvec3(world.swarm(0).position(i)) - world.body(i).getPos()));
            EXPECT_LT(worst, 2e-3) << "drag " << drag << " tilted " << tilted;
        }
    }
}

// A dryer with the air terms (drag toward the air's velocity, the pull toward the axis) goes
// through the swarm's general loop: the same kernel in float, for every integrator and response,
// and the particles that fall into the hole are blown out of it as Particles are.
TEST(Swarm, FollowsParticlesWithTheDryersAirTerms)
{
    for (CollisionResponse response : kAllCollisionResponses) {
        for (Integrator integrator : kAllIntegrators) {
            World world = swarmWorld(64, response);
            world.swarm(0).setIntegrator(integrator);
            editDryers(world, [](BlowDryerField& field) {
                field.airSpeed = 15.0;
                field.axisPull = 1.0;
            });
            ASSERT_TRUE(SwarmKernelFields(world.swarmFields(), 1.0f).air);
            addParticlesLike(world, world.swarm(0));
            for (int n = 0; n < 500; ++n)
                world.step(0.002);
            double worst = 0.0;
            for (std::size_t i = 0; i < world.swarm(0).size(); ++i)
                worst = std::max(worst, glm::length(dvec3(world.swarm(0).position(i)) - world.body(i).getPos()));
            EXPECT_LT(worst, 2e-3) << collisionResponseName(response) << " " << integratorName(integrator);
        }
    }
}

// Through the landing (1.2 s: the rain reaches the floor and the hole after about 0.7 s), with
// every response: the collision passes work on whole blocks, whose bounds do not move with the
// thread count. 40,000 particles, above the size where the step goes parallel.
TEST(Swarm, ResultsDoNotDependOnTheThreadCount)
{
    for (CollisionResponse response : kAllCollisionResponses) {
        World one = swarmWorld(40000, response);
        World two = swarmWorld(40000, response);
        one.setThreads(1);
        two.setThreads(2);
        for (int n = 0; n < 600; ++n) {
            one.step(0.002);
            two.step(0.002);
        }
        const Swarm &a = one.swarm(0), &b = two.swarm(0);
        for (std::size_t i = 0; i < a.size(); ++i) {
            ASSERT_EQ(a.position(i), b.position(i)) << collisionResponseName(response) << " particle " << i;
            ASSERT_EQ(a.velocity(i), b.velocity(i)) << collisionResponseName(response) << " particle " << i;
        }
    }
}

// A particle's first state depends on the seed and its index alone, and its step on nothing but
// its own state: so the first particles of a swarm of a million and of one of 40,000 are the same
// particles, and stay the same, though the two are split into different tasks and blocks of
// other particles, and the larger one's state is in huge pages.
TEST(Swarm, ResultsDoNotDependOnTheSwarmsSize)
{
    World small = swarmWorld(40000);
    World large = swarmWorld(1'000'000);
    for (int n = 0; n < 50; ++n) {
        small.step(0.002);
        large.step(0.002);
    }
    const Swarm &a = small.swarm(0), &b = large.swarm(0);
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.position(i), b.position(i)) << "particle " << i;
        ASSERT_EQ(a.velocity(i), b.velocity(i)) << "particle " << i;
    }
}

// Bodies that cross the room several times a step (500 m/s, dt 0.1 s: up to 12 widths) are
// folded back in by the swarm's vectorised pass exactly as a Particle's rule folds them: after
// one step the float swarm and the double Particles agree to single precision.
TEST(Swarm, FastParticlesFoldBackIntoTheRoomAsParticlesDo)
{
    World world = pba::test::fastSwarmWorld(1000, 0.9);
    const Swarm& swarm = world.swarm(0);
    addParticlesLike(world, swarm);
    world.step(0.1);
    for (std::size_t i = 0; i < swarm.size(); ++i) {
        ASSERT_LT(glm::length(dvec3(swarm.position(i)) - world.body(i).getPos()), 1e-4) << "particle " << i;
        ASSERT_LT(glm::length(dvec3(swarm.velocity(i)) - world.body(i).getVel()), 1e-3) << "particle " << i;
    }
}

// A block with a few particles at a wall has them gathered, with those of other such blocks,
// for the rule; one with many runs the rule over all of its particles. Either way a particle
// gets the same result, bit for bit: five particles (on the floor, in a corner, over the hole,
// in the shaft, at the ceiling) among clear ones, and the same five among others that all meet
// the floor. Also with 64 at a wall (the most gathered: the first clear one is in the second
// word of flags), in a last, partial block (particles 512 on of 600), and over eight blocks.
TEST(Swarm, AFewAtAWallGetTheSameRuleAsAWholeBlock)
{
    const std::array<std::pair<Vec3<float>, Vec3<float>>, 5> few = {{
        {{1.0f, 0.001f, 1.0f}, {0.5f, -3.0f, 0.2f}},    // the floor
        {{1.999f, 0.002f, -1.999f}, {4.0f, -4.0f, -4.0f}}, // a corner: three walls
        {{0.1f, 0.001f, 0.05f}, {0.0f, -3.0f, 0.0f}},   // over the hole
        {{0.05f, -0.05f, 0.0f}, {2.0f, -1.0f, 0.0f}},   // in the shaft
        {{-1.0f, 3.999f, 0.5f}, {0.0f, 2.0f, 0.0f}},    // the ceiling
    }};
    const auto onTheFloor = [](std::size_t i) {
        return std::pair(Vec3<float>(-1.5f + 0.005f * float(i % 512), 0.001f, 1.2f), Vec3<float>(0.0f, -2.0f, 0.0f));
    };
    struct Case {
        std::size_t count, first, atWall; // swarm size, first particle at a wall, how many a block
    };
    // One block; the most a block gathers; a last, partial block; and eight blocks whose 40 each
    // fill the batch (128) twice before the last is run at the end.
    for (const Case c : {Case{512, 0, 5}, Case{512, 0, 64}, Case{600, 512, 5}, Case{4096, 0, 40}}) {
        for (CollisionResponse response : {CollisionResponse::Reflect, CollisionResponse::Clamp}) {
            World gathered = swarmWorld(c.count, response);
            World whole = swarmWorld(c.count, response);
            const auto atWall = [&](std::size_t i) { return i >= c.first && (i - c.first) % 512 < c.atWall; };
            for (std::size_t i = c.first; i < c.count; ++i) {
                const std::size_t k = (i - c.first) % 512;
                const auto [x, v] = k < few.size() ? few[k] : onTheFloor(i);
                whole.swarm(0).set(i, x, v);
                if (atWall(i))
                    gathered.swarm(0).set(i, x, v);
            }
            gathered.step(0.002);
            whole.step(0.002);
            for (std::size_t i = 0; i < c.count; ++i) {
                if (!atWall(i))
                    continue;
                ASSERT_EQ(gathered.swarm(0).position(i), whole.swarm(0).position(i))
                    << collisionResponseName(response) << " particle " << i << " of " << c.count;
                ASSERT_EQ(gathered.swarm(0).velocity(i), whole.swarm(0).velocity(i))
                    << collisionResponseName(response) << " particle " << i << " of " << c.count;
            }
        }
    }
}

// The surface test counts against the room's walls alone when every other plane is clear of the
// whole room (the grille below the floor's hole). A plane that cuts into the room is not: here
// one across an edge, which the particles (thrown at it, no gravity) meet before any wall.
TEST(Swarm, AnInnerPlaneBesideTheRoomIsNotMissed)
{
    const auto room = roomPlanes(Vec3<float>(-2.0f), Vec3<float>(2.0f));
    const Vec3<float> corner = glm::normalize(Vec3<float>(-1.0f, 0.0f, -1.0f));
    std::vector<PlaneT<float>> planes(room.begin(), room.end());
    planes.push_back(PlaneT<float>{corner, -2.0f}); // x + z <= 2 sqrt(2): cuts off the (2, 2) edge
    SwarmDesc desc;
    desc.count = 2000;
    desc.regionMin = dvec3(-1.0);
    desc.regionMax = dvec3(1.0);
    desc.velocity = dvec3(3.0, 0.0, 3.0);
    desc.velocityJitter = 0.2;
    desc.mass = 1.0;
    desc.restitution = 0.8;
    for (CollisionResponse response : {CollisionResponse::Reflect, CollisionResponse::Clamp}) {
        Swarm swarm(desc);
        const SwarmFields fields;
        for (int n = 0; n < 125; ++n) // 0.25 s: the edge from 0.14 s, a wall from 0.3 s
            swarm.step(fields, planes, response, 0.002f, 1);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            ASSERT_GE(planes[6].distance(swarm.position(i)), -1e-5f) << collisionResponseName(response) << " " << i;
        }
    }
}

TEST(Swarm, NoParticleEverLeavesTheRoom)
{
    for (CollisionResponse response : kAllCollisionResponses) {
        World world = swarmWorld(2000, response);
        const Aabb room = *world.room();
        const double grille = room.min.y - world.floorHole()->depth;
        for (int n = 0; n < 2500; ++n) // 5 s
            world.step(0.002);
        const Swarm& swarm = world.swarm(0);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            const dvec3 x(swarm.position(i));
            ASSERT_TRUE(x.x >= room.min.x - 1e-5 && x.x <= room.max.x + 1e-5 && x.z >= room.min.z - 1e-5 &&
                        x.z <= room.max.z + 1e-5 && x.y <= room.max.y + 1e-5 && x.y >= grille - 1e-5)
                << collisionResponseName(response) << " particle " << i;
            if (x.y < room.min.y - 1e-5) {
                ASSERT_LE(std::hypot(x.x, x.z), world.floorHole()->radius + 1e-5);
            }
        }
    }
}

#include <nlohmann/json.hpp>

#include "support/run_command.hpp"

// pba bench's JSON has the keys docs/commands.md documents, for every layout; a row's rate is its
// best window, so never below its median, and its fraction of the bound is best over best.
TEST(PbaBench, QuickJsonHasEveryLayout)
{
    const auto r = pba::test::runPba("bench --quick --json --sizes 1000");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    std::set<std::string> layouts;
    double bound = 0.0;
    nlohmann::json scene, cloth = nlohmann::json::array(), piles = nlohmann::json::array(),
                          grains = nlohmann::json::array();
    std::set<std::string> swarmPhases;
    for (const auto& row : json["results"]) {
        layouts.insert(row["layout"].get<std::string>());
        if (row["layout"] == "scene")
            scene = row;
        if (row["layout"] == "cloth") {
            cloth.push_back(row);
            continue;
        }
        if (row["layout"] == "pile") {
            piles.push_back(row);
            continue;
        }
        if (row["layout"] == "granular") {
            grains.push_back(row);
            continue;
        }
        for (const char* key : {"integrator", "n", "threads", "particle_steps_per_s", "particle_steps_per_s_median",
                                "bytes_per_particle"})
            EXPECT_TRUE(row.contains(key)) << key;
        const double rate = row["particle_steps_per_s"].get<double>();
        EXPECT_GT(rate, 0.0);
        EXPECT_GT(row["particle_steps_per_s_median"].get<double>(), 0.0);
        EXPECT_LE(row["particle_steps_per_s_median"].get<double>(), rate);
        if (row["layout"] == "bound")
            bound = rate;
        if (row["layout"] == "swarm") {
            swarmPhases.insert(row["phase"].get<std::string>());
            // The baseline is timed in flight only: a landed row has no ratio to it.
            EXPECT_EQ(row["times_baseline"].get<double>() > 0.0, row["phase"] == "flight");
            EXPECT_DOUBLE_EQ(row["fraction_of_bound"].get<double>(), rate / bound);
        }
    }
    EXPECT_EQ(layouts, (std::set<std::string>{"bound", "baseline", "swarm", "scene", "cloth", "pile", "granular"}));
    // The grains: 1e5 only with --quick, on all cores, with and without their contacts.
    ASSERT_EQ(grains.size(), 1u);
    EXPECT_EQ(grains[0]["n"], 100000);
    EXPECT_EQ(grains[0]["scene"], "granular");
    EXPECT_EQ(grains[0]["threads"], json["machine"]["cores"]);
    for (const char* key : {"particle_steps_per_s", "without_collisions"})
        EXPECT_GT(grains[0][key].get<double>(), 0.0) << key;
    // The piles: 1,000 and 10,000 dice on all cores, two spans of 10 steps each with --quick, the
    // slowest span's rate never above the whole run's.
    ASSERT_EQ(piles.size(), 2u);
    EXPECT_EQ(piles[0]["n"], 1000);
    EXPECT_EQ(piles[1]["n"], 10000);
    for (const auto& pile : piles) {
        EXPECT_EQ(pile["scene"], "dice");
        EXPECT_EQ(pile["threads"], json["machine"]["cores"]);
        EXPECT_EQ(pile["integrator"], "semi-implicit-euler");
        EXPECT_EQ(pile["spans"], 2);
        EXPECT_EQ(pile["steps_per_span"], 10);
        EXPECT_GT(pile["steps_per_s"].get<double>(), 0.0);
        EXPECT_LE(pile["steps_per_s"].get<double>(), pile["steps_per_s_overall"].get<double>());
        // where the slowest span starts: the first span's start or the second's, 10 steps of 5 ms later
        const double from = pile["slowest_span_from_s"].get<double>();
        EXPECT_TRUE(from == 0.0 || std::abs(from - 0.05) < 1e-12) << from;
    }
    EXPECT_EQ(swarmPhases, (std::set<std::string>{"flight", "landed", "rested"}));
    // The cloth: 128 x 128 with each method on 1 thread and on all cores: semi-implicit Euler at
    // dt 0.002 (one spring evaluation per spring a step), implicit-euler and xpbd at 1/60.
    std::map<std::string, double> dts;
    std::map<std::string, std::set<int>> threads;
    for (const auto& row : cloth) {
        EXPECT_EQ(row["scene"], "cloth-in-the-dryer");
        EXPECT_EQ(row["n"], 16384);
        EXPECT_EQ(row["springs"], 97026);
        const std::string integrator = row["integrator"].get<std::string>();
        dts[integrator] = row["dt"].get<double>();
        threads[integrator].insert(row["threads"].get<int>());
        const double steps = row["steps_per_s"].get<double>();
        EXPECT_GT(steps, 0.0);
        EXPECT_LE(row["steps_per_s_median"].get<double>(), steps);
        if (integrator == "semi-implicit-euler") {
            EXPECT_DOUBLE_EQ(row["spring_evaluations_per_s"].get<double>(), steps * 97026.0);
        }
        if (integrator == "implicit-euler") {
            EXPECT_GT(row["cg_iterations"].get<int>(), 0);
        }
        if (integrator == "xpbd") {
            EXPECT_EQ(row["substeps"], 10);
        }
    }
    EXPECT_EQ(dts, (std::map<std::string, double>{{"semi-implicit-euler", 0.002}, {"implicit-euler", 1.0 / 60.0},
                                                  {"xpbd", 1.0 / 60.0}}));
    for (const auto& [integrator, counts] : threads)
        EXPECT_EQ(counts, (std::set<int>{1, json["machine"]["cores"].get<int>()})) << integrator;
    EXPECT_EQ(scene["scene"], "fountain-1m");
    EXPECT_EQ(scene["n"], 1000000);
    EXPECT_GT(scene["steps_per_s"].get<double>(), 0.0);
    // steps_per_s is the slowest span's: never above the whole run's
    EXPECT_LE(scene["steps_per_s"].get<double>(), scene["steps_per_s_overall"].get<double>());
    EXPECT_EQ(scene["spans"], 2);
    EXPECT_EQ(scene["steps_per_span"], 4);
    // where the slowest span starts: the first span's start or the second's, 4 steps of dt later
    const double from = scene["slowest_span_from_s"].get<double>();
    EXPECT_TRUE(from == 0.0 || std::abs(from - 4.0 / 480.0) < 1e-12) << from;
}

// Timing the phases changes nothing: the same states to the bit, and every phase takes time.
TEST(Swarm, TimingThePhasesLeavesTheStepAsItWas)
{
    pba::Scene timed = pba::loadScene("blow-dryer-swarm"), plain = pba::loadScene("blow-dryer-swarm");
    pba::SwarmPhaseTimes times;
    timed.world.swarm(0).setPhaseTimes(&times);
    for (int n = 0; n < 300; ++n) {
        timed.world.step(timed.dt);
        plain.world.step(plain.dt);
    }
    const pba::Swarm& a = timed.world.swarm(0);
    const pba::Swarm& b = plain.world.swarm(0);
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.position(i), b.position(i)) << i;
        ASSERT_EQ(a.velocity(i), b.velocity(i)) << i;
    }
    for (std::size_t p = 0; p < pba::SwarmPhaseTimes::kCount; ++p)
        EXPECT_GT(times.nanoseconds[p].load(), 0u) << pba::SwarmPhaseTimes::kNames[p];
}

// `pba bench --phases --json`: a row per size and phase, each with every phase's milliseconds.
TEST(PbaBench, PhasesSplitTheSwarmStep)
{
    const auto r = pba::test::runPba("bench --phases --quick --json --sizes 20000");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    ASSERT_EQ(json["results"].size(), 3u);
    std::set<std::string> phases;
    for (const auto& row : json["results"]) {
        EXPECT_EQ(row["layout"], "phases");
        EXPECT_EQ(row["n"], 20000);
        phases.insert(row["phase"].get<std::string>());
        for (const char* key : {"integrate_ms", "surface_test_ms", "collide_ms", "check_ms"})
            EXPECT_GE(row[key].get<double>(), 0.0) << key;
        EXPECT_GT(row["integrate_ms"].get<double>(), 0.0);
        EXPECT_GT(row["steps_per_s"].get<double>(), 0.0);
    }
    EXPECT_EQ(phases, (std::set<std::string>{"flight", "landed", "rested"}));
}

// `--integrator` picks the swarm's integrator for --phases; an unknown one, or one a swarm cannot
// take, is a usage error.
TEST(PbaBench, PhasesTakeAnIntegrator)
{
    const auto r = pba::test::runPba("bench --phases --quick --json --sizes 5000 --integrator rk4");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    ASSERT_EQ(json["results"].size(), 3u);
    for (const auto& row : json["results"])
        EXPECT_EQ(row["integrator"], "rk4");
    const auto bad = pba::test::runPba("bench --phases --quick --sizes 5000 --integrator leapfrog");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("--integrator: unknown integrator 'leapfrog'"), std::string::npos) << bad.err;
    EXPECT_TRUE(bad.out.empty()) << bad.out;
    // A spring system's method has no springs in a swarm: refused, as a scene's swarm refuses it,
    // rather than run as semi-implicit Euler under its name.
    for (const char* method : {"xpbd", "implicit-euler"}) {
        const auto springs = pba::test::runPba(std::string("bench --phases --quick --sizes 5000 --integrator ") + method);
        EXPECT_EQ(springs.exitCode, 2) << method;
        EXPECT_NE(springs.err.find("steps particles joined by springs; a swarm has none"), std::string::npos)
            << springs.err;
    }
}

// The peer worker steps --integrator's swarm (for alternated windows of velocity Verlet or RK4);
// --integrator with neither --phases nor --peer-worker is a usage error, not silently ignored.
TEST(PbaBench, PeerWorkerTakesAnIntegrator)
{
    const auto r = pba::test::runShell("printf 'window 3\\n' | " + pba::test::pbaBinary() +
                                       " bench --peer-worker --sizes 3000 --phase flight --integrator rk4");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::istringstream lines(r.out);
    std::string ready, window;
    ASSERT_TRUE(std::getline(lines, ready) && std::getline(lines, window)) << r.out;
    EXPECT_EQ(nlohmann::json::parse(ready)["integrator"], "rk4");
    EXPECT_EQ(nlohmann::json::parse(window)["steps"], 3);
    EXPECT_GT(nlohmann::json::parse(window)["particle_steps_per_s"].get<double>(), 0.0);
    const auto alone = pba::test::runPba("bench --quick --integrator rk4");
    EXPECT_EQ(alone.exitCode, 2);
    EXPECT_NE(alone.err.find("--integrator: only with --phases or --peer-worker"), std::string::npos) << alone.err;
    EXPECT_TRUE(alone.out.empty()) << alone.out;
}

// A block whose particles rest on the floor skips the surface test and takes the collision pass
// whole (a crowded block), one with a few at a surface has them gathered, one alone is stepped
// by itself: each particle's states are the same, bit for bit, every step. Here 2,048 particles
// resting on the floor, some sliding into a wall (reaching it on different steps, so some while
// their block is crowded: the whole rule), some over the hole and in the dryer's cone at its
// foot (blocks that become crowded), then lifted off, against each particle stepped as a swarm
// of one, with reflect and clamp, and both Eulers.
TEST(Swarm, CrowdedBlocksGetTheSameRuleAsParticlesAlone)
{
    for (const auto& [response, integrator] :
         {std::pair{CollisionResponse::Reflect, Integrator::SemiImplicitEuler},
          std::pair{CollisionResponse::Clamp, Integrator::SemiImplicitEuler},
          std::pair{CollisionResponse::Reflect, Integrator::ForwardEuler}}) {
        World world = swarmWorld(2048, response);
        Swarm& swarm = world.swarm(0);
        swarm.setIntegrator(integrator);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            const float u = float(i % 64) / 64.0f, w = float(i / 64) / 32.0f;
            const bool resting = i < 1536; // three blocks on the floor, one in the air
            const bool atWall = resting && i % 64 == 0; // sliding into the low x wall: the whole rule
            const float across = atWall ? -1.998f + 0.0005f * float(i / 64) : -1.9f + 3.8f * u;
            const Vec3<float> x(across, resting ? 1e-4f : 1.0f + w, -1.9f + 3.8f * w);
            swarm.set(i, x, Vec3<float>(atWall ? -0.5f : 0.3f * (u - 0.5f), resting ? -0.05f : 2.0f, 0.1f));
        }
        std::vector<World> alone;
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            World one = swarmWorld(1, response);
            one.swarm(0).setIntegrator(integrator);
            one.swarm(0).set(0, swarm.position(i), swarm.velocity(i));
            alone.push_back(std::move(one));
        }
        for (int n = 0; n < 60; ++n) {
            world.step(0.002);
            for (std::size_t i = 0; i < swarm.size(); ++i) {
                alone[i].step(0.002);
                ASSERT_EQ(swarm.position(i), alone[i].swarm(0).position(0)) << "particle " << i << " step " << n;
                ASSERT_EQ(swarm.velocity(i), alone[i].swarm(0).velocity(0)) << "particle " << i << " step " << n;
            }
        }
    }
}

// A swarm steps a block whose dryer is busy (over kGatherMax particles in its cone or shaft)
// with the whole acceleration, and a quiet one with the acceleration away from the dryer,
// stepping again with the whole one the few it may push. Two blocks that share all
// but 90 particles, 10 in the cone and 402 resting far from the hole (the quiet one has the
// 90 on the floor, the busy one in the cone), take those 412 through both paths: the same states
// bit for bit, with the scene's dryer and a tilted one with drag. (A compiler that took the
// away acceleration's product with dt out of the loop rounded it differently: this fails then.)
TEST(Swarm, ADryersFewParticlesAndTheRestStepAsInABusyBlock)
{
    const auto place = [](Swarm& swarm, bool busy) {
        for (std::size_t i = 0; i < 512; ++i) {
            const float u = float(i % 32) / 32.0f, w = float(i / 32) / 16.0f;
            const bool inCone = i < 10 || (busy && i < 100);
            const Vec3<float> x = inCone ? Vec3<float>(0.2f * (u - 0.5f), 0.3f + 2.0f * w, 0.2f * (w - 0.5f))
                                         : Vec3<float>(0.8f + u, 1e-4f, -1.9f + 3.8f * w);
            swarm.set(i, x, Vec3<float>(0.3f * (u - 0.5f), inCone ? 0.5f : -0.05f, 0.1f * w));
        }
    };
    for (const bool tiltedWithDrag : {false, true}) {
        for (Integrator integrator : kAllIntegrators) {
            World quiet = swarmWorld(512), busy = swarmWorld(512);
            for (World* world : {&quiet, &busy}) {
                world->swarm(0).setIntegrator(integrator);
                if (tiltedWithDrag) {
                    world->addForce(std::make_unique<Drag>(0.4));
                    editDryers(*world, [](BlowDryerField& field) { field.axis = glm::normalize(dvec3(0.2, 1.0, 0.1)); });
                }
            }
            place(quiet.swarm(0), false);
            place(busy.swarm(0), true);
            for (int n = 0; n < 60; ++n) {
                quiet.step(0.002);
                busy.step(0.002);
                for (std::size_t i = 0; i < 512; ++i) {
                    if (i >= 10 && i < 100)
                        continue;
                    const Swarm &a = quiet.swarm(0), &b = busy.swarm(0);
                    ASSERT_EQ(a.position(i), b.position(i)) << integratorName(integrator) << " tilted " << tiltedWithDrag
                                                            << " particle " << i << " step " << n;
                    ASSERT_EQ(a.velocity(i), b.velocity(i)) << integratorName(integrator) << " tilted " << tiltedWithDrag
                                                            << " particle " << i << " step " << n;
                }
            }
        }
    }
}

// Without a dryer the loop's acceleration is gravity and drag alone, as the Particles' forces
// give it, where with one it adds the dryer's force: a dryer of zero strength (above the floor,
// so no hole) adds zeros, and the two swarms stay equal, bit for bit, for every integrator and
// response, with drag and without.
TEST(Swarm, WithoutADryerStepsAsWithADryerOfZeroStrength)
{
    const auto rain = [](bool dryer) {
        const std::string forces = dryer ? R"(, "forces": [{"type": "blow-dryer", "nozzle": [0, 1, 0], "axis": [0, 1, 0],
            "height": 2, "nozzle_radius": 0.3, "top_radius": 1.5, "strength": 40}])"
                                         : "";
        return R"({"name": "rain", "dt": 0.002, "duration": 1, "gravity": [0, -9.81, 0],
            "room": {"min": [-2, 0, -2], "max": [2, 4, 2]},
            "swarms": [{"name": "rain", "count": 1000, "region": {"min": [-1.8, 0.5, -1.8], "max": [1.8, 3.5, 1.8]},
                        "velocity": [0, -1, 0], "velocity_jitter": 3, "mass": 1, "restitution": 0.6,
                        "integrator": "semi-implicit-euler", "seed": 7}])" +
               forces + "}";
    };
    for (CollisionResponse response : kAllCollisionResponses) {
        for (Integrator integrator : kAllIntegrators) {
            for (const bool drag : {false, true}) {
                std::array<World, 2> worlds{parseScene(rain(false), "rain.json").world,
                                            parseScene(rain(true), "rain.json").world};
                editDryers(worlds[1], [](BlowDryerField& field) { field.strength = 0.0; });
                for (World& world : worlds) {
                    world.setCollisionResponse(response);
                    world.swarm(0).setIntegrator(integrator);
                    if (drag)
                        world.addForce(std::make_unique<Drag>(0.4));
                    for (int n = 0; n < 500; ++n)
                        world.step(0.002);
                }
                ASSERT_TRUE(worlds[0].swarmFields().dryers.empty());
                ASSERT_EQ(worlds[1].swarmFields().dryers.size(), 1u);
                const Swarm &alone = worlds[0].swarm(0), &zero = worlds[1].swarm(0);
                std::size_t differ = 0;
                for (std::size_t i = 0; i < alone.size(); ++i)
                    differ += alone.position(i) != zero.position(i) || alone.velocity(i) != zero.velocity(i);
                EXPECT_EQ(differ, 0u) << collisionResponseName(response) << " " << integratorName(integrator)
                                      << " drag " << drag;
            }
        }
    }
}
