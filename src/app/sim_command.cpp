// `pba sim`: run a scene without drawing it, print its summary (sim_summary.cpp) and, on
// request, write every physics step to CSV.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "atomic_file.hpp"
#include "command.hpp"
#include "flag_values.hpp"
#include "csv.hpp"
#include "progress.hpp"
#include "scene_options.hpp"
#include "shown_path.hpp"
#include "sim_summary.hpp"
#include "pba/blow_up_watch.hpp"
#include "pba/clock.hpp"
#include "study/jet_watch.hpp"
#include "study/rigid_watch.hpp"

namespace pba::app {

namespace {

struct SimOptions {
    SceneOptions scene;
    std::optional<std::string> out;
    std::optional<double> frameRate;
    bool swarmParticles = false;
    bool everyParticle = false;
};

/// A scene with rigid bodies adds each body's orientation and angular velocity (world frame)
/// after its energy: 1,0,0,0,0,0,0 for a particle, which does not turn.
void writeCsvHeader(std::ostream& out, bool turning)
{
    out << "step,t,body,x,y,z,vx,vy,vz,energy" << (turning ? ",qw,qx,qy,qz,wx,wy,wz\n" : "\n");
}

/// The rigid-body columns of body i (see writeCsvHeader).
std::string turnColumns(const World& world, std::size_t i)
{
    if (!world.isRigid(i))
        return ",1,0,0,0,0,0,0";
    const auto& b = static_cast<const RigidBody&>(world.body(i));
    const dquat& q = b.getOrientation();
    const dvec3 w = b.getAngularVelocity();
    return fmt::format(",{},{},{},{},{},{},{}", q.w, q.x, q.y, q.z, w.x, w.y, w.z);
}

void writeCsvRows(std::ostream& out, const World& world, bool turning)
{
    // {} formats doubles as the shortest text that reads back to the same value:
    // exact, and identical for identical runs.
    const std::vector<double> energies = world.energies();
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        const Body& b = world.body(i);
        const dvec3& x = b.getPos();
        const dvec3& v = b.getVel();
        out << fmt::format("{},{},{},{},{},{},{},{},{},{}{}\n", world.stepCount(), world.time(), csvField(b.getName()),
                           x.x, x.y, x.z, v.x, v.y, v.z, energies[i], turning ? turnColumns(world, i) : "");
    }
}

/// Swarm particles as CSV rows, named NAME[i]; only on request (a million rows a step).
void writeSwarmRows(std::ostream& out, const World& world, bool turning)
{
    const dvec3 g = world.gravity();
    for (std::size_t s = 0; s < world.swarmCount(); ++s) {
        const Swarm& swarm = world.swarm(s);
        for (std::size_t i = 0; i < swarm.size(); ++i) {
            const Vec3<float> x = swarm.position(i), v = swarm.velocity(i);
            const double energy = swarm.mass() * (0.5 * glm::dot(v, v) - glm::dot(Vec3<float>(g), x));
            out << fmt::format("{},{},{},{},{},{},{},{},{},{}{}\n", world.stepCount(), world.time(),
                               csvField(fmt::format("{}[{}]", swarm.name(), i)),
                               x.x, x.y, x.z, v.x, v.y, v.z, energy, turning ? ",1,0,0,0,0,0,0" : "");
        }
    }
}

/// --frame-rate's checks: a rate the clock can take, and no more frames than a run may.
void checkFrameRate(const SimOptions& options, const Scene& scene)
{
    if (!options.frameRate)
        return;
    const double hz = *options.frameRate;
    if (!(std::isfinite(hz) && hz > 0.0))
        throw UsageError(fmt::format("--frame-rate: must be finite and positive, got {}", hz));
    if (!(scene.duration * hz <= kMaxSteps))
        throw UsageError(fmt::format("--frame-rate: {:g} s at {:g} Hz is {:.3g} frames, more than the {:g} a run may "
                                     "take", scene.duration, hz, scene.duration * hz, kMaxSteps));
}

/// What a run keeps of each step: the summary's highest points, and the CSV rows on request.
class StepRecord {
public:
    StepRecord(const World& world, AtomicFile* csv, bool swarmParticles)
        : world_(world), csv_(csv), swarmParticles_(swarmParticles), summary_(world.bodyCount())
    {
        const std::vector<double> startEnergies = world.energies();
        for (std::size_t i = 0; i < world.bodyCount(); ++i) {
            summary_[i].startEnergy = startEnergies[i];
            if (!world.body(i).isFixed())
                summary_[i].startMomentum = world.body(i).getMass() * world.body(i).getVel();
            summary_[i].highest = world.body(i).getPos().y;
        }
    }

    void operator()()
    {
        for (std::size_t i = 0; i < world_.bodyCount(); ++i)
            summary_[i].highest = std::max(summary_[i].highest, world_.body(i).getPos().y);
        if (csv_)
            writeCsvRows(csv_->stream(), world_, world_.hasRigidBodies());
        if (csv_ && swarmParticles_)
            writeSwarmRows(csv_->stream(), world_, world_.hasRigidBodies());
    }

    const std::vector<BodySummary>& summary() const { return summary_; }

private:
    const World& world_;
    AtomicFile* csv_;
    bool swarmParticles_;
    std::vector<BodySummary> summary_;
};

/// Steps the scene to its end, recording every step. The number of steps depends on dt and
/// duration alone. With --frame-rate the clock hands them out in frames of 1/HZ seconds, as the
/// viewer would: same steps, same bytes. Throws BlowUpError at the first step that blows up,
/// before its rows are written (the world's own checks, then the BlowUpWatch's: an energy that
/// is not finite is no more a valid row than an infinite position).
void stepToEnd(const SimOptions& options, Scene& scene, StepRecord& record, RunWatches& watches)
{
    World& world = scene.world;
    const std::uint64_t total = stepCount(scene.duration, scene.dt, "--duration");
    std::optional<FixedTimestepClock> clock;
    if (options.frameRate)
        clock.emplace(scene.dt);
    const study::JetWatch::Attachment attached = watches.jet.attach(world);
    Progress progress("simulating", static_cast<long>(total)); // a bar on a terminal, after a second
    try {
        while (world.stepCount() < total) {
            const std::uint64_t now = clock ? static_cast<std::uint64_t>(clock->advance(1.0 / *options.frameRate)) : 1;
            for (std::uint64_t k = 0; k < now && world.stepCount() < total; ++k) {
                world.step(scene.dt);
                watches.record(world);
                record();
                if (world.stepCount() % 1024 == 0)
                    progress.update(static_cast<long>(world.stepCount()));
            }
        }
    } catch (...) {
        progress.clear();
        throw;
    }
    progress.clear();
}

/// --swarm-particles writes a row per particle per step, about 100 bytes each: a scene's
/// whole run can be more than a disk holds. Past a gigabyte, the run says so before it starts.
void warnOfLargeCsv(const SimOptions& options, const Scene& scene)
{
    if (!options.out || !options.swarmParticles)
        return;
    double particles = 0.0;
    for (std::size_t s = 0; s < scene.world.swarmCount(); ++s)
        particles += double(scene.world.swarm(s).size());
    const double steps = double(stepCount(scene.duration, scene.dt, "--duration")) + 1.0;
    const double bytes = 100.0 * particles * steps;
    if (bytes > 1e9)
        fmt::print(stderr, "pba sim: --swarm-particles will write about {:.0f} GB ({:g} rows of swarm particles) to {}; "
                           "a shorter --duration writes less\n",
                   bytes / 1e9, particles * steps, shownPath(*options.out));
}

/// A CSV under a picture's, a video's or JSON's name would open as a broken file of that kind.
void checkCsvName(const std::optional<std::string>& out)
{
    if (!out)
        return;
    std::string extension = std::filesystem::path(*out).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    for (const char* other : {".png", ".jpg", ".jpeg", ".mp4", ".gif", ".json"})
        if (extension == other)
            throw UsageError(fmt::format("--out: sim writes CSV, and '{}' names a {} file: give a name such as run.csv",
                                         *out, extension.substr(1)));
}

int runSim(const SimOptions& options)
{
    if (options.swarmParticles && !options.out)
        throw UsageError("--swarm-particles: writes the swarms' particles to --out's CSV, and there is no --out");
    checkCsvName(options.out);
    Scene scene = loadSceneWithOverrides(options.scene);
    checkFrameRate(options, scene);
    warnOfLargeCsv(options, scene);
    std::unique_ptr<AtomicFile> csv;
    if (options.out) {
        csv = std::make_unique<AtomicFile>(*options.out, "--out");
        writeCsvHeader(csv->stream(), scene.world.hasRigidBodies());
    }
    World& world = scene.world;
    StepRecord record(world, csv.get(), options.swarmParticles);
    RunWatches watches(scene);
    record();
    try {
        stepToEnd(options, scene, record, watches);
    } catch (const BlowUpError& error) {
        if (csv)
            csv->commit(); // the rows so far are valid, up to the last finite step
        fmt::print(stderr, "pba: error: {}: {}\n", shownPath(scene.source), error.what());
        return kExitSimulationFailure;
    }
    if (csv)
        csv->commit();
    watches.finish(world);
    printSummary(scene, world, record.summary(), watches, options.everyParticle);
    if (options.out)
        fmt::print("wrote {} to {}\n", options.swarmParticles ? "every body and swarm particle at every step"
                                                              : fmt::format("{} rows", (world.stepCount() + 1) * world.bodyCount()),
                   shownPath(*options.out));
    return kExitSuccess;
}

} // namespace

void addSimCommand(CLI::App& root, Action& selected)
{
    auto options = std::make_shared<SimOptions>();
    CLI::App* sim = root.add_subcommand("sim", "Run a scene without drawing it and print a per-body summary");
    sim->footer(fmt::format(
        "\nExit status 3: the run blew up, and the message names the body, the step, the time and the\n"
        "reason: a state not finite, a rigid body's centre inside a wall, or the energy\n"
        "{:g} times its scale above its start and the work of its energy sources (the blow dryer).\n"
        "--out keeps the rows up to the step before.\n\nExamples:\n  pba sim integrators --dt 0.05 --integrator rk4\n"
        "  pba sim bouncing-cube --out pba-out/run.csv --frame-rate 30\n",
        BlowUpWatch::kEnergyGrowthLimit));
    addSceneOptions(*sim, options->scene, kDefaultScene);
    sim->add_option("--out", options->out,
                    "Write one CSV row per body per physics step (step 0 included) to this file; columns "
                    "step,t,body,x,y,z,vx,vy,vz,energy, and with rigid bodies in the scene qw,qx,qy,qz,wx,wy,wz "
                    "(orientation and world-frame angular velocity; 1,0,0,0,0,0,0 for particles)")
        ->type_name("FILE.csv");
    sim->add_option("--frame-rate", options->frameRate,
                    "Drive the fixed-timestep clock with synthetic frames of 1/HZ seconds (the results do not "
                    "change: only dt and the number of steps matter)")
        ->transform(decimalOnly())
        ->type_name("HZ");
    sim->add_flag("--swarm-particles", options->swarmParticles,
                  "With --out: also write a row per swarm particle (named as its swarm, NAME[i]) at every step, about 100 "
                  "bytes each (10 MB a step for 100,000 particles: pair it with a short --duration); without it "
                  "swarms are summarised by statistics");
    sim->add_flag("--every-particle", options->everyParticle,
                  "List every particle of each rope and cloth in the summary too (by default a rope or cloth is "
                  "one row of totals)");
    sim->callback([options, &selected] { selected = [options] { return runSim(*options); }; });
}

} // namespace pba::app
