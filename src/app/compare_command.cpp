// `pba compare`: the integrator study as a reproducible report.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "clock_report.hpp"
#include "command.hpp"
#include "compare_report.hpp"
#include "flag_values.hpp"
#include "io/folder_output.hpp"
#include "progress.hpp"
#include "rotation_report.hpp"
#include "study/findings.hpp"
#include "study/clock_plots.hpp"
#include "study/plots.hpp"
#include "study/rotation_plots.hpp"
#include "scene/closest_name.hpp"
#include "scene_options.hpp"
#include "shown_path.hpp"

namespace pba::app {

namespace {

struct CompareOptions {
    std::string scene = "integrators";
    std::string out = "pba-compare";
    std::vector<std::string> integrators;
    std::vector<std::string> collisions;
    std::vector<double> dts;
    // The list flags as typed: one word each, so that a repeated flag is refused as sim's are.
    std::string integratorList, collisionList, dtList;
    std::optional<double> duration;
    std::optional<std::string> body; ///< --body: the rigid body the rotation study measures
    int jobs = 0;
    bool clocks = false;
    bool workPrecision = false; ///< --work-precision: also the four scenes' work against precision
};

/// Keeps the first of each repeated entry, in the order given.
template <class T>
void dropRepeats(std::vector<T>& list)
{
    std::vector<T> kept;
    for (const T& x : list)
        if (std::find(kept.begin(), kept.end(), x) == kept.end())
            kept.push_back(x);
    list = std::move(kept);
}

/// The options with their list flags split into the lists.
CompareOptions withLists(CompareOptions options)
{
    options.integrators = listItems("--integrators", options.integratorList);
    options.collisions = listItems("--collisions", options.collisionList);
    options.dts = numberList("--dt", options.dtList);
    return options;
}

/// The longest run, and so the largest dt, a study takes: gnuplot's axes reach a few times past
/// the largest value plotted, and near the largest double that overflowed (1.7e308 s).
constexpr double kMaxStudySeconds = 1e300;

/// The run's length: --duration, or the scene's.
double readDuration(const CompareOptions& options, const Scene& scene)
{
    const double duration = options.duration.value_or(scene.duration);
    if (!(std::isfinite(duration) && duration > 0))
        throw UsageError(fmt::format("--duration: must be finite and positive, got {}", duration));
    if (duration > kMaxStudySeconds)
        throw UsageError(fmt::format("--duration: {:g} s is more than the {:g} s a study may plot", duration,
                                     kMaxStudySeconds));
    return duration;
}

/// --integrators by name, each once (the study's own list when none is given).
void readIntegrators(const CompareOptions& options, std::vector<Integrator>& integrators)
{
    if (!options.integrators.empty()) {
        integrators.clear();
        for (const auto& name : options.integrators) {
            const auto integrator = integratorFromName(name);
            if (!integrator)
                throw UsageError(fmt::format("--integrators: unknown integrator '{}'", name));
            integrators.push_back(*integrator);
        }
    }
    dropRepeats(integrators);
}

/// --dt (the study's own list when none is given), sorted, each value once (a repeated dt would
/// be a repeated column, and a fit through two equal dt has no slope), each a run that fits.
void readDts(const CompareOptions& options, double duration, std::vector<double>& dts)
{
    if (!options.dts.empty())
        dts = options.dts;
    for (double dt : dts)
        if (!(std::isfinite(dt) && dt > 0))
            throw UsageError(fmt::format("--dt: every dt must be finite and positive, got {}", dt));
    // A dt longer than the run would run past its end in one step (and 1e308 s overflowed the
    // plots' axes). The study's own list is left as it is: the user did not choose it.
    for (double dt : options.dts)
        if (dt > duration)
            throw UsageError(fmt::format("--dt: {:g} s is longer than the run ({:g} s): a dt must be at most the "
                                         "duration", dt, duration));
    std::sort(dts.begin(), dts.end());
    dts.erase(std::unique(dts.begin(), dts.end()), dts.end());
    for (double dt : dts)
        stepCount(duration, dt, "--duration");
}

/// --jobs: runs at once (0: one a core).
int readJobs(const CompareOptions& options)
{
    if (options.jobs < 0 || options.jobs > 256)
        throw UsageError(fmt::format("--jobs: must be from 1 to 256 (0: all cores), got {}", options.jobs));
    return options.jobs > 0 ? options.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void sayIfNoPlots(bool plots)
{
    if (!plots)
        fmt::print(stderr, "pba: gnuplot is not installed, so there are no plots: install the Debian package "
                           "gnuplot-nox\n");
}

/// Fills a study's folder and publishes it: `tables(dir)` writes its tables and plots and says
/// whether there are plots, `report(dir, plots)` its report; then the folder replaces the old one
/// whole, so a study that fails leaves the previous one untouched, not a mix of new and old files.
template <class Tables, class Report>
bool publishStudy(io::FolderOutput& folder, Tables&& tables, Report&& report)
{
    const std::filesystem::path dir = folder.path();
    const bool plots = tables(dir);
    sayIfNoPlots(plots);
    report(dir, plots);
    folder.commit();
    return plots;
}

/// The same for a study of one table, `csvName`, its plots and its report.
template <class Config, class Result>
bool publishStudy(io::FolderOutput& folder, const Config& config, const Result& result, const char* csvName,
                  void (*csv)(const std::filesystem::path&, const Result&),
                  bool (*plots)(const std::filesystem::path&, const Config&, const Result&),
                  void (*report)(const std::filesystem::path&, const Config&, const Result&, bool))
{
    return publishStudy(
        folder,
        [&](const std::filesystem::path& dir) {
            csv(dir / csvName, result);
            return plots(dir, config, result);
        },
        [&](const std::filesystem::path& dir, bool withPlots) { report(dir / "report.md", config, result, withPlots); });
}

study::StudyConfig makeConfig(const CompareOptions& options)
{
    study::StudyConfig config;
    config.scene = loadSceneArgument(options.scene);
    bool moving = false;
    for (std::size_t i = 0; i < config.scene.world.bodyCount(); ++i)
        moving = moving || !config.scene.world.body(i).isFixed();
    if (!moving)
        throw UsageError(fmt::format("{}: the study compares particles, and this scene has no moving particle{}",
                                     config.scene.source,
                                     config.scene.world.swarmCount() > 0 ? " (only swarms: try pba sim or pba bench)" : ""));
    config.duration = readDuration(options, config.scene);
    readIntegrators(options, config.integrators);
    if (!options.collisions.empty()) {
        config.collisions.clear();
        for (const auto& name : options.collisions) {
            const auto collision = collisionResponseFromName(name);
            if (!collision)
                throw UsageError(fmt::format("--collisions: unknown collision response '{}'", name));
            config.collisions.push_back(*collision);
        }
    }
    readDts(options, config.duration, config.dts);
    dropRepeats(config.collisions);
    config.jobs = readJobs(options);
    return config;
}

/// --body NAME's index in the scene: a moving rigid body, or bad input naming what it is.
std::size_t readStudiedBody(const std::string& name, const Scene& scene)
{
    const World& world = scene.world;
    const std::optional<std::size_t> found = world.findBody(name);
    if (!found) {
        std::vector<std::string> moving;
        for (std::size_t i = 0; i < world.bodyCount(); ++i)
            if (world.isRigid(i) && !world.body(i).isFixed())
                moving.push_back(world.body(i).getName());
        const auto close = scene_detail::closestName(name, moving);
        throw UsageError(fmt::format("--body: {} has no body named '{}'{}", scene.source, name,
                                     close ? fmt::format(": did you mean '{}'?", *close) : ""));
    }
    if (!world.isRigid(*found) || world.body(*found).isFixed())
        throw UsageError(fmt::format("--body: '{}' in {} is {}: the rotation study measures a moving rigid body", name,
                                     scene.source, world.isRigid(*found) ? "fixed" : "not a rigid body"));
    return *found;
}

/// The rotation study's settings: the same options, with its own defaults (all six integrators,
/// dt up to 0.05 s). Collision responses are the particles' rules: a rigid body meets the room
/// with contact impulses, so --collisions is refused rather than ignored.
study::RotationConfig makeRotationConfig(const CompareOptions& options, Scene scene)
{
    if (!options.collisions.empty())
        throw UsageError(fmt::format("--collisions: {} is a scene with rigid bodies, which meet the room with contact "
                                     "impulses whatever the collision response: the rotation study has no responses "
                                     "to compare", scene.source));
    study::RotationConfig config;
    if (options.body)
        config.body = readStudiedBody(*options.body, scene);
    config.duration = readDuration(options, scene);
    readIntegrators(options, config.integrators);
    for (const Integrator integrator : config.integrators)
        if (std::find(kRigidIntegrators.begin(), kRigidIntegrators.end(), integrator) == kRigidIntegrators.end())
            throw UsageError(fmt::format("--integrators: {} is a scene with rigid bodies, and {} steps particles "
                                         "joined by springs: the rotation study takes forward-euler, "
                                         "semi-implicit-euler, velocity-verlet, rk4, implicit-gyroscopic or splitting",
                                         scene.source, integratorName(integrator)));
    config.scene = std::move(scene);
    readDts(options, config.duration, config.dts);
    config.jobs = readJobs(options);
    return config;
}

/// The names either study writes: a study replaces pba's files of these names in its folder
/// (the other study's too, once stale) and leaves every other file there alone.
bool isStudyFile(const std::string& name)
{
    static const std::vector<std::string> names = [] {
        std::vector<std::string> all{"report.md", "results.csv", "orders.csv", "stability.csv", "clocks.csv",
                                     "work_precision.csv", study::kWorkPrecisionPlotFile,
                                     study::kClockPlotFile,
                                     study::kStabilityPlotFile, study::kDriftPlotFile, study::kFlipPlotFile,
                                     study::kPeriodPlotFile};
        all.insert(all.end(), study::kPlotFiles.begin(), study::kPlotFiles.end());
        return all;
    }();
    return std::find(names.begin(), names.end(), name) != names.end();
}

int runRotationCompare(const CompareOptions& options, Scene scene)
{
    const study::RotationConfig config = makeRotationConfig(options, std::move(scene));
    io::FolderOutput folder(options.out, isStudyFile);
    Progress progress("comparing", long(config.integrators.size() * config.dts.size()));
    const study::RotationResult result =
        study::runRotationStudy(config, [&](long done, long) { progress.update(done); });
    const bool plots =
        publishStudy(folder, config, result, "results.csv", writeRotationCsv, writeRotationPlots, writeRotationReport);
    fmt::print("largest |E/E0 - 1|, rigid body {} of {}:\n{}\n", result.body, config.scene.name,
               rotationTable(config, result, RotationMeasure::EnergyDrift, false));
    fmt::print("largest ||L|/|L0| - 1|:\n{}\n", rotationTable(config, result, RotationMeasure::MomentumDrift, false));
    if (!std::isnan(result.exactPeriod))
        fmt::print("flip period error (T - T_exact) / T_exact, T_exact = {:.6f} s:\n{}\n", result.exactPeriod,
                   rotationTable(config, result, RotationMeasure::PeriodError, false));
    progress.finish(fmt::format("wrote {}/report.md, results.csv{} ({} runs)", shownPath(options.out),
                                plots ? " and plots" : "", result.runs.size()));
    return kExitSuccess;
}

/// --clocks: the scene with each clock at 30, 60 and 144 Hz, steady and through a hitch, at its
/// dt or the one --dt names. The integrator study's other choices do not apply: refused.
int runClockCompare(const CompareOptions& options)
{
    if (!options.integrators.empty() || !options.collisions.empty())
        throw UsageError("--clocks: runs the scene as it is, with each clock: --integrators and --collisions do not "
                         "apply (set them in the scene, or run pba compare without --clocks)");
    if (options.body || options.workPrecision)
        throw UsageError(fmt::format("--clocks: runs the scene as it is, with each clock: {} does not apply (run pba "
                                     "compare without --clocks for it)",
                                     options.body ? "--body" : "--work-precision"));
    if (options.dts.size() > 1)
        throw UsageError(fmt::format("--clocks: takes one --dt (the fixed clock's), got {}", options.dts.size()));
    study::ClockConfig config;
    config.scene = loadSceneArgument(options.scene);
    config.duration = readDuration(options, config.scene);
    if (config.duration < study::kClockMinDuration)
        throw UsageError(fmt::format("--duration: the clocks study needs at least {:g} s (the hitch is at {:g} s), "
                                     "got {:g} s", study::kClockMinDuration, study::kHitchAt, config.duration));
    std::vector<double> dts{config.scene.dt};
    readDts(options, config.duration, dts);
    config.dt = dts.front();
    io::FolderOutput folder(options.out, isStudyFile);
    const study::ClockResult result = study::runClockStudy(config);
    const bool plot = publishStudy(folder, config, result, "clocks.csv", writeClockCsv, writeClockPlot, writeClockReport);
    fmt::print("largest distance of a body from the 60 Hz run, {} at dt = {:g} s:\n{}\n{}", config.scene.name,
               config.dt, clockTable(config, result, false), clockFindings(config, result));
    fmt::print("wrote {}/report.md, clocks.csv{}\n", shownPath(options.out), plot ? " and clocks.png" : "");
    return kExitSuccess;
}

int runCompare(const CompareOptions& options)
{
    if (options.clocks)
        return runClockCompare(options);
    {
        // A scene with a moving rigid body gets the rotation study.
        Scene scene = loadSceneArgument(options.scene);
        if (study::studiedRigidBody(scene.world)) {
            if (options.workPrecision)
                throw UsageError(fmt::format("--work-precision: goes with the integrator study, and {} has a moving "
                                             "rigid body, which gets the rotation study (run it on a scene without one, "
                                             "such as integrators)",
                                             scene.source));
            return runRotationCompare(options, std::move(scene));
        }
        if (options.body)
            throw UsageError(fmt::format("--body: chooses the rigid body the rotation study measures, and {} has no "
                                         "moving rigid body",
                                         scene.source));
    }
    const study::StudyConfig config = makeConfig(options);
    io::FolderOutput folder(options.out, isStudyFile);
    Progress progress("comparing", study::studyTaskCount(config));
    const study::StudyResult result = study::runStudy(config, [&](long done, long) { progress.update(done); });
    // Its references at dt 1e-4 s cost several times the study itself: on request only.
    const std::vector<study::WorkPrecisionPoint> points =
        options.workPrecision ? study::runWorkPrecision() : std::vector<study::WorkPrecisionPoint>{};
    const bool plots = publishStudy(
        folder,
        [&](const std::filesystem::path& dir) {
            writeResultsCsv(dir / "results.csv", result);
            writeOrdersCsv(dir / "orders.csv", result);
            if (!result.stability.empty())
                writeStabilityCsv(dir / "stability.csv", result);
            return writePlots(dir, config, result);
        },
        [&](const std::filesystem::path& dir, bool withPlots) {
            const std::string workPrecision =
                options.workPrecision ? writeWorkPrecision(dir, points, withPlots) : std::string();
            writeReport(dir / "report.md", config, result, withPlots, workPrecision);
        });
    const auto responses = study::distinctResponses(config, result);
    for (CollisionResponse c : responses)
        fmt::print("E(end)/E(0), {}, {} of {}:\n{}\n",
                   !study::anyCollision(result) && config.collisions.size() > 1
                       ? "every collision response (nothing collides)"
                       : fmt::format("{} response{}", collisionResponseName(c),
                                     c == CollisionResponse::Reflect && study::exactShownAsReflect(config, result)
                                         ? " (and exact, the same runs)"
                                         : ""),
                   result.followsSystem ? "the whole system" : "first moving particle", config.scene.name,
                   energyTable(config, result, c, false));
    fmt::print("order of accuracy (spring):");
    for (const auto& o : result.orders)
        fmt::print("  {} {} (expected {})", integratorName(o.integrator), study::orderText(o), o.expected);
    if (result.omegaMax) {
        fmt::print("\nstability limit in dt (omega_max {:.6g} rad/s):", *result.omegaMax);
        for (const auto& s : result.stability)
            fmt::print("  {} {} (theory {})", integratorName(s.integrator),
                       std::isnan(s.measuredDt) ? std::string("not measured") : fmt::format("{:.5g} s", s.measuredDt),
                       std::isnan(s.theoryDt)   ? std::string("none")
                       : std::isinf(s.theoryDt) ? std::string("any dt")
                                                : fmt::format("{:.5g} s", s.theoryDt));
    }
    fmt::print("\n\n{}", study::findings(config, result));
    if (options.workPrecision)
        fmt::print("\nwork against precision (work_precision.csv), cheapest to an error of 1e-3 on one thread:\n{}",
                   study::workPrecisionFindings(points, 1e-3));
    progress.finish(fmt::format("wrote {}/report.md, results.csv, orders.csv{}{} ({} runs)", shownPath(options.out),
                                result.stability.empty() ? "" : ", stability.csv", plots ? " and plots" : "",
                                result.runs.size()));
    return kExitSuccess;
}

} // namespace

void addCompareCommand(CLI::App& root, Action& selected)
{
    auto options = std::make_shared<CompareOptions>();
    CLI::App* compare = root.add_subcommand("compare", "The integrator study: every integrator, collision response "
                                                       "and dt against the exact solution, as tables, plots and a report");
    addScenePositional(*compare, options->scene, "integrators");
    compare->add_option("--out", options->out, "Directory for report.md, results.csv, orders.csv and the PNG plots "
                                               "(default pba-compare)")
        ->type_name("DIR");
    compare->add_option("--integrators", options->integratorList,
                        "Comma-separated integrators (default all four; with rigid bodies all six)")
        ->option_text("NAME,...");
    compare->add_option("--collisions", options->collisionList,
                        "Comma-separated collision responses (default all three)")
        ->option_text("MODE,...");
    compare->add_option("--dt", options->dtList, "Comma-separated timesteps (default 0.0005,0.001,0.002,0.005,0.01,0.02,"
                                                 "0.05,0.1; with rigid bodies the first seven, up to 0.05)")
        ->option_text("DT,...");
    compare->add_option("--duration", options->duration, "Simulated time of each run (default the scene's)")
        ->transform(decimalOnly())
        ->type_name("SECONDS");
    compare->add_option("--body", options->body,
                        "With rigid bodies: the one the rotation study measures (default the first moving one)")
        ->type_name("NAME");
    compare->add_flag("--clocks", options->clocks,
                      "Instead of the integrators: the scene with each clock (fixed, semi-fixed, variable) at 30, 60 "
                      "and 144 frames a second, steady and with a 0.25 s frame, and how far the runs drift apart");
    compare->add_flag("--work-precision", options->workPrecision,
                      "Also run the spring, chain, cloth and tennis racket with every method they take at six dt and "
                      "write work_precision.csv and .png: error against CPU time, the cheapest method for an accuracy "
                      "(seconds more than the study alone)");
    compare->add_option("--jobs", options->jobs, "Runs in parallel (default all cores); results do not depend on it")
        ->transform(decimalOnly())
        ->type_name("N");
    compare->footer("\nOn a scene with rigid bodies (dice, tennis-racket, rolling, blow-dryer-boxes) it studies rotation\n"
                    "instead: every integrator (all six) and dt (default up to 0.05) on the first moving rigid body\n"
                    "(or --body NAME): its drift of energy and of |L|, and its flip period against the elliptic\n"
                    "integral's.\n"
                    "\nExamples:\n  pba compare --out pba-out/study    (then read pba-out/study/report.md)\n"
                    "  pba compare stiff-spring --out pba-out/stiff    (each integrator's stability limit in dt)\n"
                    "  pba compare tennis-racket --out pba-out/racket\n"
                    "  pba compare incline --body steep-box --out pba-out/incline\n"
                    "  pba compare --clocks blow-dryer --out pba-out/clocks\n");
    compare->callback([options, &selected] { selected = [options] { return runCompare(withLists(*options)); }; });
}

} // namespace pba::app
