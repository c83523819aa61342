#include "work_precision.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <limits>

#include <fmt/format.h>

#include "pba/blow_up_watch.hpp"
#include "pba/rigid_body.hpp"
#include "pba/scene/scene.hpp"
#include "render/palette.hpp"

namespace pba::study {

namespace {

double cpuNow()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// What a run ends with: each moving body's position, and each rigid body's orientation.
struct End {
    std::vector<dvec3> position;
    std::vector<dquat> orientation;
};

/// The scene's world with every moving body on `integrator`, run to kWorkPrecisionSeconds.
/// Throws BlowUpError if it blows up.
End run(const Scene& scene, Integrator integrator, double dt)
{
    World world = scene.world;
    world.setThreads(1);
    for (std::size_t i = 0; i < world.bodyCount(); ++i)
        if (!world.body(i).isFixed())
            world.body(i).setIntegrator(integrator);
    BlowUpWatch watch(world);
    const auto steps = static_cast<long>(std::lround(workPrecisionSeconds(scene.name) / dt));
    for (long k = 0; k < steps; ++k) {
        world.step(dt);
        watch.check(world);
    }
    End end;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
        const Body& b = world.body(i);
        if (b.isFixed())
            continue;
        end.position.push_back(b.getPos());
        if (const auto* rigid = dynamic_cast<const RigidBody*>(&b))
            end.orientation.push_back(rigid->getOrientation());
    }
    return end;
}

double errorOf(const End& end, const End& reference, bool orientation)
{
    double error = 0.0;
    if (orientation)
        for (std::size_t i = 0; i < end.orientation.size(); ++i) {
            // The angle of the turn between them, by atan2: acos of a dot product near 1 loses
            // every angle below 1e-8 rad.
            const dquat turn = glm::inverse(reference.orientation[i]) * end.orientation[i];
            const double sine = glm::length(dvec3(turn.x, turn.y, turn.z));
            error = std::max(error, 2.0 * std::atan2(sine, std::abs(turn.w)));
        }
    else
        for (std::size_t i = 0; i < end.position.size(); ++i)
            error = std::max(error, glm::length(end.position[i] - reference.position[i]));
    return error;
}

/// The run timed: repeated until the repeats fill 3 ms (a run of a few microseconds is noise
/// alone), their mean CPU time.
WorkPrecisionPoint timed(const Scene& scene, Integrator integrator, double dt, const End& reference)
{
    WorkPrecisionPoint p{scene.name, integrator, dt, 0.0, 0.0, false};
    try {
        int repeats = 0;
        const double start = cpuNow();
        End end;
        do {
            end = run(scene, integrator, dt);
            ++repeats;
        } while (cpuNow() - start < 0.003 && repeats < 64);
        p.cpuSeconds = (cpuNow() - start) / repeats;
        p.error = errorOf(end, reference, measuresOrientation(scene.name));
    } catch (const BlowUpError&) {
        p.blewUp = true;
    }
    return p;
}

/// A scene of rigid bodies (the racket, the chain's links) takes the rigid methods, one of
/// particles the particles'.
std::vector<Integrator> methodsOf(const Scene& scene)
{
    bool rigid = false;
    for (std::size_t i = 0; i < scene.world.bodyCount(); ++i)
        rigid = rigid || (!scene.world.body(i).isFixed() && dynamic_cast<const RigidBody*>(&scene.world.body(i)));
    return rigid ? std::vector<Integrator>(kRigidIntegrators.begin(), kRigidIntegrators.end())
                 : std::vector<Integrator>(kParticleIntegrators.begin(), kParticleIntegrators.end());
}

} // namespace

bool measuresOrientation(const std::string& scene) { return scene == "tennis-racket"; }

double workPrecisionSeconds(const std::string& scene)
{
    return scene == "chain" ? kChainSeconds : kWorkPrecisionSeconds;
}

double workPrecisionError(const Scene& scene, Integrator integrator, double dt)
{
    return errorOf(run(scene, integrator, dt), run(scene, Integrator::RK4, kReferenceDt), measuresOrientation(scene.name));
}

std::vector<WorkPrecisionPoint> runWorkPrecision()
{
    std::vector<WorkPrecisionPoint> points;
    for (const char* name : kWorkPrecisionScenes) {
        const Scene scene = loadScene(name);
        const End reference = run(scene, Integrator::RK4, kReferenceDt);
        for (const Integrator integrator : methodsOf(scene))
            for (const double dt : kWorkPrecisionDts)
                points.push_back(timed(scene, integrator, dt, reference));
    }
    return points;
}

std::string workPrecisionFindings(const std::vector<WorkPrecisionPoint>& points, double error)
{
    std::string out;
    for (const char* scene : kWorkPrecisionScenes) {
        const WorkPrecisionPoint* best = nullptr;
        for (const WorkPrecisionPoint& p : points)
            if (p.scene == scene && !p.blewUp && p.error <= error && (!best || p.cpuSeconds < best->cpuSeconds))
                best = &p;
        const char* unit = measuresOrientation(scene) ? "rad" : "m";
        out += best ? fmt::format("- **{}**: {} reaches an error of {:g} {} cheapest, at dt = {:g} s in {:.3g} ms "
                                  "(its error {:.2g} {}).\n",
                                  scene, integratorName(best->integrator), error, unit, best->dt,
                                  1e3 * best->cpuSeconds, best->error, unit)
                    : fmt::format("- **{}**: no method reaches {:g} {} at these dt.\n", scene, error, unit);
    }
    return out;
}

std::string workPrecisionPlotScript(const std::filesystem::path& dir, const std::vector<WorkPrecisionPoint>& points)
{
    std::string script = "set terminal pngcairo size 1400,1000 font 'sans,10'\n" +
                         fmt::format("set output '{}'\n", kWorkPrecisionPlotFile);
    script += "set multiplot layout 2,2 title 'error at the end (1 s; the chain 0.8 s, before it strikes the wall) against CPU time, one line per method, each point "
              "labelled with its dt (runs that blew up left out)'\nset logscale xy\nset format x '10^{%T}'\n"
              "set format y '10^{%T}'\nset xlabel 'CPU time of the run (s, one thread)'\nset key outside right\n"
              "set grid\n";
    for (const char* scene : kWorkPrecisionScenes) {
        std::string lines;
        for (const Integrator integrator : methodsOf(loadScene(scene))) {
            const std::string file = fmt::format("wp_{}_{}.dat", scene, integratorName(integrator));
            std::ofstream out(dir / file);
            int n = 0;
            for (const WorkPrecisionPoint& p : points)
                if (p.scene == scene && p.integrator == integrator && !p.blewUp && p.error > 0.0 && p.cpuSeconds > 0.0) {
                    out << p.cpuSeconds << ' ' << p.error << ' ' << p.dt << '\n';
                    ++n;
                }
            if (n == 0)
                continue;
            const std::string colour = palette::hex(palette::integratorRgb(integrator));
            lines += fmt::format("'{0}' using 1:2 with linespoints lw 2 pt 7 ps 0.7 lc rgb '{1}' title '{2}', "
                                 "'{0}' using 1:2:(sprintf('%g', $3)) with labels offset char 0.6,0.5 font ',7' "
                                 "tc rgb '{1}' notitle, ",
                                 file, colour, integratorName(integrator));
        }
        script += fmt::format("set title '{}'\nset ylabel '{}'\n", scene,
                              measuresOrientation(scene) ? "orientation error (rad)" : "largest position error (m)");
        script += lines.empty() ? "plot 1e-99 notitle\n" : "plot " + lines.substr(0, lines.size() - 2) + "\n";
    }
    return script + "unset multiplot\n";
}

} // namespace pba::study
