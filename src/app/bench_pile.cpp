#include "bench_pile.hpp"

#include <array>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "atomic_file.hpp"
#include "bench_timing.hpp"
#include "bench_worker.hpp"
#include "command.hpp"
#include "csv.hpp"
#include "pba/rigid_body.hpp"
#include "pba/scene/scene.hpp"

namespace pba::app::bench {

namespace {

const RigidBody& dieOf(const World& world, std::size_t i) { return static_cast<const RigidBody&>(world.body(i)); }

/// A die's 13 numbers in writePileState's order.
std::array<double, 13> dieState(const RigidBody& die)
{
    const dvec3 x = die.getPos(), v = die.getVel(), w = die.getAngularVelocity();
    const dquat q = die.getOrientation();
    return {x.x, x.y, x.z, q.w, q.x, q.y, q.z, v.x, v.y, v.z, w.x, w.y, w.z};
}

nlohmann::json vec(const dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

/// The ready line: what a peer needs to build the same pile (runPileWorker).
nlohmann::json readyLine(const Scene& scene, int threads)
{
    const World& world = scene.world;
    const RigidBody& die = dieOf(world, 0); // every die is a copy of one
    const dmat3& inertia = die.getInertiaBody();
    return {{"ready", true},
            {"n", world.bodyCount()},
            {"t", world.time()},
            {"dt", scene.dt},
            {"threads", threads},
            {"velocity_iterations", world.contactSettings().velocityIterations},
            {"integrator", std::string(integratorName(die.getIntegrator()))},
            {"gravity", vec(world.gravity())},
            {"room", {{"min", vec(world.room()->min)}, {"max", vec(world.room()->max)}}},
            {"die",
             {{"shape", "box"},
              {"size", vec(die.getShape().size)},
              {"mass", die.getMass()},
              {"inertia", nlohmann::json::array({inertia[0][0], inertia[1][1], inertia[2][2]})},
              {"friction", die.getFriction()},
              {"restitution", die.getCor()}}},
            {"start_bits_sum", pileStateBits(world)}};
}

} // namespace

std::uint64_t pileStateBits(const World& world)
{
    std::uint64_t bits = 0;
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        for (const double value : dieState(dieOf(world, i))) {
            const auto rounded = static_cast<float>(value);
            std::uint32_t word;
            std::memcpy(&word, &rounded, sizeof word);
            bits += word;
        }
    return bits;
}

void writePileState(const World& world, const std::filesystem::path& path)
{
    AtomicFile file(path);
    std::ofstream& out = file.stream();
    out << "name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        const RigidBody& die = dieOf(world, i);
        out << csvField(die.getName());
        for (const double value : dieState(die))
            out << fmt::format(",{}", value); // the shortest text that reads back as the same double
        out << '\n';
    }
    file.commit();
}

void usePileSolver(World& world, int iterations)
{
    ContactSettings& s = world.contactSettings();
    s.velocityIterations = s.maxVelocityIterations = iterations;
}

int runPileWorker(std::size_t dice, int iterations)
{
    Scene scene = [dice] {
        try {
            return manyDice(dice);
        } catch (const std::invalid_argument& e) {
            throw UsageError(fmt::format("--dice: {}", e.what()));
        }
    }();
    World& world = scene.world;
    world.setThreads(0);
    usePileSolver(world, iterations);
    const auto window = [&](std::istringstream& args, const std::string& line) -> nlohmann::json {
        const long steps = windowSteps("--pile-worker", args, line);
        const auto start = Clock::now();
        for (long k = 0; k < steps; ++k)
            world.step(scene.dt);
        const double elapsed = seconds(start);
        return {{"seconds", elapsed}, {"steps", steps}, {"t", world.time()}, {"steps_per_s", double(steps) / elapsed}};
    };
    const auto save = [&](std::istringstream& args, const std::string& line) -> nlohmann::json {
        std::string path;
        std::getline(args >> std::ws, path);
        if (path.empty())
            throw UsageError(fmt::format("--pile-worker: 'save PATH', got '{}'", line));
        writePileState(world, path);
        return {{"saved", path}, {"t", world.time()}};
    };
    return serveWorker("--pile-worker", readyLine(scene, machineCores()), {{"window", "window STEPS", window}, {"save", "save PATH", save}});
}

} // namespace pba::app::bench
