// Hardening: replayed fuzz regressions, tunnelling at 500 m/s, a 10^7-step soak, and the
// program's behaviour on blow-ups and failed writes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "pba/blow_up_watch.hpp"
#include "pba/forces.hpp"
#include "pba/scene/scene.hpp"
#include "support/fast_swarm.hpp"
#include "support/run_command.hpp"

using namespace pba;
using namespace pba::test;

namespace {

bool insideRoom(const Aabb& room, const dvec3& x)
{
    return x.x >= room.min.x && x.x <= room.max.x && x.y >= room.min.y && x.y <= room.max.y && x.z >= room.min.z &&
           x.z <= room.max.z;
}

} // namespace

// Every input that ever crashed the fuzzer (or probes an edge) loads or is refused cleanly.
TEST(FuzzRegressions, EveryKeptInputLoadsOrIsRefusedCleanly)
{
    int replayed = 0;
    for (const auto& entry : std::filesystem::directory_iterator(sourceDir() / "fuzz" / "regressions")) {
        if (entry.path().extension() != ".json")
            continue;
        ++replayed;
        try {
            Scene scene = parseScene(readFile(entry.path()), entry.path().string());
            for (int n = 0; n < 3; ++n)
                scene.world.step(scene.dt);
        } catch (const SceneError&) {
        } catch (const BlowUpError&) { // a state not finite, or a rigid body left inside a wall
        }
    }
    EXPECT_GT(replayed, 0);
}

// 500 m/s in a 4 m room with dt = 0.1: the body crosses the room a dozen times a step.
TEST(Tunnelling, AFastParticleStaysInTheRoomForASimulatedHour)
{
    for (CollisionResponse response : kAllCollisionResponses) {
        for (Integrator integrator : kAllIntegrators) {
            World world = loadScene("bouncing-cube").world;
            world.setCollisionResponse(response);
            world.body(0).setIntegrator(integrator);
            world.body(0).setVel(dvec3(500.0, 300.0, -400.0));
            const Aabb room = *world.room();
            for (int n = 0; n < 36000; ++n) {
                world.step(0.1);
                ASSERT_TRUE(insideRoom(room, world.body(0).getPos()))
                    << collisionResponseName(response) << " " << integratorName(integrator) << " step " << n;
            }
        }
    }
}

// The same for a swarm: 10,000 particles at up to 500 m/s per component for a simulated hour,
// checked every simulated minute. (A few seconds in a release build: a particle that crosses the
// room several times a step is folded back in closed form.)
TEST(Tunnelling, ASwarmOfFastParticlesStaysInTheRoomForASimulatedHour)
{
    World world = pba::test::fastSwarmWorld(10000, 1.0, 11);
    world.addForce(std::make_unique<Gravity>(dvec3(0, -9.81, 0)));
    const Aabb room = *world.room();
    const Swarm& swarm = world.swarm(0);
    for (int minute = 1; minute <= 60; ++minute) {
        for (int n = 0; n < 600; ++n)
            world.step(0.1);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            const dvec3 x(swarm.position(i));
            ASSERT_TRUE(x.x >= room.min.x - 1e-4 && x.x <= room.max.x + 1e-4 && x.y >= room.min.y - 1e-4 &&
                        x.y <= room.max.y + 1e-4 && x.z >= room.min.z - 1e-4 && x.z <= room.max.z + 1e-4)
                << "particle " << i << " after " << minute << " min";
        }
    }
}

// Semi-implicit Euler with restitution 1 keeps its energy within a bounded band however long
// it runs: the band it spans in its first 10^6 steps (its shadow-energy oscillation, wide here
// because the ball also strikes the ceiling) is never left in the next 10^7, and the ball never
// leaves the room. The reflect response is the one under which semi-implicit Euler conserves
// (with exact impacts it loses m g |v| dt at every floor bounce, see pba compare).
TEST(Soak, TenMillionStepsInTheCubeStayInsideWithBoundedEnergy)
{
    World world = loadScene("bouncing-cube").world;
    world.setCollisionResponse(CollisionResponse::Reflect);
    world.body(0).setIntegrator(Integrator::SemiImplicitEuler);
    ASSERT_EQ(world.body(0).getCor(), 1.0);
    const Aabb room = *world.room();
    const double e0 = world.energy(0);
    double low = 1.0, high = 1.0;
    for (long n = 0; n < 1'000'000; ++n) {
        world.step(0.01);
        low = std::min(low, world.energy(0) / e0);
        high = std::max(high, world.energy(0) / e0);
    }
    const double margin = 0.01 * (high - low);
    for (long n = 0; n < 10'000'000; ++n) {
        world.step(0.01);
        if (n % 100 == 0) {
            ASSERT_TRUE(insideRoom(room, world.body(0).getPos())) << n;
            const double ratio = world.energy(0) / e0;
            ASSERT_TRUE(ratio >= low - margin && ratio <= high + margin)
                << "step " << n << ": " << ratio << " outside [" << low << ", " << high << "]";
        }
    }
}

// Forward Euler on a spring of stiffness 1e200 gives the bob a speed of 5e199 m/s in its first
// step, whose kinetic energy is not finite although its state is. The run stops there; the CSV
// keeps step 0, both bodies' rows.
TEST(NonFinite, PbaSimExitsThreeAndKeepsTheCsvValid)
{
    const auto dir = freshDir("nonfinite");
    const auto scene = dir / "stiff.json";
    std::ofstream(scene) << R"({"gravity": [0, 0, 0], "dt": 0.5, "duration": 100,
        "particles": [{"name": "bob", "position": [0, 1, 0], "integrator": "forward-euler"},
                      {"name": "still", "position": [5, 1, 0]}],
        "forces": [{"type": "spring", "particle": "bob", "anchor": [0, 0, 0], "stiffness": 1e200}]})";
    const auto csv = dir / "run.csv";
    const CommandResult r = runPba("sim " + scene.string() + " --out " + csv.string());
    EXPECT_EQ(r.exitCode, 3) << r.err;
    for (const char* part : {"bob", "step", "smaller dt", "not finite"})
        EXPECT_NE(r.err.find(part), std::string::npos) << part << ": " << r.err;
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line.rfind("step,t,body", 0), 0u);
    int rows = 0;
    while (std::getline(in, line)) {
        ++rows;
        EXPECT_EQ(line.find("nan"), std::string::npos) << line;
        EXPECT_EQ(line.find("inf"), std::string::npos) << line;
    }
    EXPECT_GT(rows, 1);
}

TEST(AtomicWrites, AFailedRunLeavesAnExistingFileUntouched)
{
    const auto dir = freshDir("atomic");
    const auto out = dir / "run.csv";
    std::ofstream(out) << "old contents\n";
    const CommandResult r = runPba("sim no-such-scene --out " + out.string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(readFile(out), "old contents\n");
    const CommandResult png = runPba("render integrators --size 10x10 --out " + (dir / "x.png").string());
    EXPECT_EQ(png.exitCode, 2);
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1) << "only run.csv";
}

// docs/hardening.md's Hardening section says what exit 3 means, with the factor the code uses,
// and the exit codes' section points there; the README's exit code table says it in short.
TEST(NonFinite, TheDocsStateWhatExitThreeMeans)
{
    const std::string readme = readFile(sourceDir() / "docs" / "hardening.md");
    const std::size_t hardening = readme.find("\n## Hardening\n");
    const std::size_t codes = readme.find("\n## Exit codes\n");
    ASSERT_NE(hardening, std::string::npos);
    ASSERT_NE(codes, std::string::npos);
    const std::string section = readme.substr(hardening, codes - hardening);
    std::ostringstream factor;
    factor << "**" << BlowUpWatch::kEnergyGrowthLimit << " energy scales**";
    for (const std::string& part : {std::string("Every blow-up is exit 3, naming the body"), factor.str(),
                                    std::string("stops being finite"), std::string("on or beyond the floor"),
                                    std::string("the work of its energy sources"), std::string("blew_up_at")})
        EXPECT_NE(section.find(part), std::string::npos) << part;
    EXPECT_NE(readme.find("3 simulation failure (the run blew up", codes), std::string::npos);
    const std::string front = readFile(sourceDir() / "README.md");
    EXPECT_NE(front.find("| 3 | simulation failure: the run blew up"), std::string::npos);
    EXPECT_NE(front.find("docs/hardening.md"), std::string::npos);
}
