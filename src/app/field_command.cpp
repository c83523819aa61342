// `pba field`: look at the force fields of a scene: the force at a point, or a picture of
// the blow dryer's field in the vertical plane through its axis.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "atomic_file.hpp"
#include "command.hpp"
#include "flag_values.hpp"
#include "gnuplot.hpp"
#include "io/output_file.hpp"
#include "pba/blow_dryer.hpp"
#include "pba/scene/scene.hpp"
#include "scene_options.hpp"
#include "shown_path.hpp"

namespace pba::app {

namespace {

struct FieldOptions {
    std::string scene;
    std::vector<double> at;
    std::string atText; ///< --at as typed: one word, split here so that its count is checked whole
    bool json = false;
    bool slice = false;
    std::optional<std::string> out;
    int resolution = 240;
};

struct Contribution {
    std::string type;
    dvec3 force;
};

/// Every force of the scene on a unit-mass particle at rest at x. Forces tied to one particle
/// (springs) are not fields and contribute nothing.
std::vector<Contribution> fieldAt(const World& world, const dvec3& x)
{
    Particle probe;
    std::vector<Contribution> result;
    for (std::size_t i = 0; i < world.forceCount(); ++i) {
        const Force& force = world.force(i);
        result.push_back({std::string(force.type()), force.force(world.bodyCount(), probe, x, dvec3(0.0))});
    }
    return result;
}

int printFieldAt(const World& world, const FieldOptions& options)
{
    if (options.at.size() != 3)
        throw UsageError(fmt::format("--at: expected 3 numbers (x,y,z), got {}", options.at.size()));
    for (const double c : options.at)
        if (!std::isfinite(c))
            throw UsageError(fmt::format("--at: every coordinate must be a finite number, got {}", c));
    const dvec3 x(options.at[0], options.at[1], options.at[2]);
    const auto parts = fieldAt(world, x);
    dvec3 total(0.0);
    for (const auto& part : parts)
        total += part.force;
    if (options.json) {
        nlohmann::json out;
        out["at"] = {x.x, x.y, x.z};
        out["total"] = {total.x, total.y, total.z};
        out["forces"] = nlohmann::json::array();
        for (const auto& part : parts)
            out["forces"].push_back({{"type", part.type}, {"force", {part.force.x, part.force.y, part.force.z}}});
        std::cout << out.dump() << "\n";
        return kExitSuccess;
    }
    fmt::print("force on a unit-mass particle at rest at ({}, {}, {}), in N:\n", x.x, x.y, x.z);
    for (const auto& part : parts)
        fmt::print("  {:<12} ({:.6g}, {:.6g}, {:.6g})\n", part.type, part.force.x, part.force.y, part.force.z);
    fmt::print("  {:<12} ({:.6g}, {:.6g}, {:.6g})\n", "total", total.x, total.y, total.z);
    return kExitSuccess;
}

/// The slice's frame: origin at the nozzle, `up` along the axis, `across` horizontal.
struct SliceFrame {
    dvec3 origin, up, across;
    double sMin, sMax, hMin, hMax;
};

SliceFrame sliceFrame(const World& world, const BlowDryerField& f)
{
    SliceFrame frame{f.nozzle, f.axis, glm::cross(f.axis, dvec3(0, 0, 1)), 0, 0, 0, 0};
    if (glm::length(frame.across) < 1e-9)
        frame.across = glm::cross(f.axis, dvec3(1, 0, 0));
    frame.across = glm::normalize(frame.across);
    const double reach = std::max(f.topRadius, f.nozzleRadius) * 1.3;
    frame.sMin = -reach;
    frame.sMax = reach;
    frame.hMin = -0.15 * f.height;
    frame.hMax = 1.15 * f.height;
    if (world.room() && std::abs(f.axis.y - 1.0) < 1e-12) { // the usual case: show the whole room
        const Aabb& room = *world.room();
        frame.sMin = std::min(frame.sMin, glm::dot(room.min - f.nozzle, frame.across));
        frame.sMax = std::max(frame.sMax, glm::dot(room.max - f.nozzle, frame.across));
        frame.hMin = room.min.y - f.nozzle.y - 0.1;
        frame.hMax = room.max.y - f.nozzle.y;
    }
    return frame;
}

dvec3 dryerForce(const std::vector<WorldDryer>& dryers, const dvec3& x)
{
    dvec3 sum(0.0);
    for (const WorldDryer& dryer : dryers)
        sum += blowDryerForce(dryer.field, x);
    return sum;
}

void writeSliceData(const std::vector<WorldDryer>& dryers, const SliceFrame& fr, int resolution, double scale,
                    const std::filesystem::path& dir, double& maxMagnitude)
{
    const int ns = resolution;
    // Rows in proportion to the picture's height, but never more than four times the columns: a
    // thin, tall dryer would otherwise ask for millions of rows of scratch data.
    const double rows = resolution * (fr.hMax - fr.hMin) / (fr.sMax - fr.sMin);
    const int nh = static_cast<int>(std::clamp(std::isfinite(rows) ? rows : 0.0, 2.0, 4.0 * resolution));
    std::ofstream magnitude(dir / "magnitude.dat");
    maxMagnitude = 0.0;
    for (int j = 0; j < nh; ++j) {
        for (int i = 0; i < ns; ++i) {
            const double s = fr.sMin + (i + 0.5) * (fr.sMax - fr.sMin) / ns;
            const double h = fr.hMin + (j + 0.5) * (fr.hMax - fr.hMin) / nh;
            const double m = glm::length(dryerForce(dryers, fr.origin + s * fr.across + h * fr.up));
            maxMagnitude = std::max(maxMagnitude, m);
            magnitude << s << ' ' << h << ' ' << m << '\n';
        }
        magnitude << '\n';
    }
    // Arrows on a coarse grid, scaled so a force of `scale` spans one cell; a stronger one (the
    // axis pull near the nozzle) is drawn one cell long.
    const int as = 22;
    const double cell = (fr.sMax - fr.sMin) / as;
    std::ofstream arrows(dir / "arrows.dat");
    const double rowStep = std::max(cell, (fr.hMax - fr.hMin) / 100.0); // at most 100 rows of arrows
    for (double h = fr.hMin + rowStep / 2; h < fr.hMax; h += rowStep) {
        for (int i = 0; i < as; ++i) {
            const double s = fr.sMin + (i + 0.5) * cell;
            const dvec3 f = dryerForce(dryers, fr.origin + s * fr.across + h * fr.up);
            const double length = glm::length(f);
            if (length <= 1e-9 * std::max(scale, 1e-300))
                continue;
            const double k = 0.9 * cell / std::max({scale, length, 1e-300});
            arrows << s << ' ' << h << ' ' << k * glm::dot(f, fr.across) << ' ' << k * glm::dot(f, fr.up) << '\n';
        }
    }
}

void writeOutlines(const BlowDryerField& f, const SliceFrame& fr, double grilleDepth, const std::filesystem::path& dir)
{
    std::ofstream cone(dir / "cone.dat");
    cone << -f.nozzleRadius << " 0\n" << -f.topRadius << ' ' << f.height << '\n' << f.topRadius << ' ' << f.height
         << '\n' << f.nozzleRadius << " 0\n";
    std::ofstream floor(dir / "floor.dat");
    floor << fr.sMin << " 0\n" << -f.nozzleRadius << " 0\n\n" << f.nozzleRadius << " 0\n" << fr.sMax << " 0\n\n";
    floor << -f.nozzleRadius << ' ' << -grilleDepth << '\n' << f.nozzleRadius << ' ' << -grilleDepth << '\n';
}

int drawSlice(const Scene& scene, const FieldOptions& options)
{
    if (!options.out)
        throw UsageError("--slice needs --out FILE.png");
    const std::vector<WorldDryer> dryers = blowDryers(scene.world);
    if (dryers.empty())
        throw UsageError(fmt::format("{}: scene has no blow-dryer force to slice", scene.source));
    const std::filesystem::path target = resolveWritableFile("--out", *options.out); // before any work
    const BlowDryerField& f = dryers.front().field;
    const SliceFrame frame = sliceFrame(scene.world, f);
    ScratchDir dir("pba-field");
    // The colours and arrows are scaled by the strongest dryer's strength (its push at the nozzle):
    // the axis pull, where a scene has one, is far stronger near the nozzle and saturates.
    double scale = 0.0;
    for (const WorldDryer& dryer : dryers)
        scale = std::max(scale, std::abs(dryer.field.strength));
    double maxMagnitude = 0.0;
    writeSliceData(dryers, frame, options.resolution, scale, dir.path(), maxMagnitude);
    if (scale <= 0.0)
        scale = maxMagnitude;
    const auto& hole = scene.world.floorHole();
    writeOutlines(f, frame, hole ? hole->depth : 0.0, dir.path());
    const std::string script = fmt::format(
        "set terminal pngcairo size 1100,900 font 'sans,12'\n"
        "set output 'slice.png'\n"
        "set title sprintf('%s: blow dryer force in the vertical plane through its axis', ARG1) . \"\\n({dir}, "
        "{axial} axial, {radial} radial falloff{saturated})\" noenhanced\n"
        "set xlabel 'across the axis (m)'\nset ylabel 'along the axis, from the nozzle (m)'\n"
        // A short colour-bar label, well clear of the tick labels; the saturation note is in the title.
        "set cblabel '|F| (N)' offset 2,0\nset size ratio -1\nset xrange [{s0}:{s1}]\nset yrange [{h0}:{h1}]\n"
        "set cbrange [0:{max}]\nset palette defined (0 '#0d0887', 0.25 '#7e03a8', 0.5 '#cc4778', 0.75 '#f89540', 1 '#f0f921')\n"
        // A dark legend, so that the white direction arrow shows in it as it does on the picture.
        "set key top right box lc rgb 'gray70' opaque fc rgb '#2b2b3a' textcolor rgb 'white'\n"
        "plot 'magnitude.dat' with image notitle, "
        "'arrows.dat' with vectors head filled size screen 0.008,20 lc rgb '#ffffff' title 'direction', "
        "'cone.dat' with lines lw 2 dt 2 lc rgb '#00c0ff' title 'cone edge', "
        "'floor.dat' with lines lw 4 lc rgb '#808080' title 'floor and grille'\n",
        fmt::arg("saturated", maxMagnitude > 1.001 * scale
                                  ? fmt::format("; colours saturate at {:.4g} N, the force reaches {:.0f} N near the nozzle",
                                                scale, maxMagnitude)
                                  : ""),
        fmt::arg("dir", flowDirectionName(f.direction)), fmt::arg("axial", falloffName(f.axialFalloff)),
        fmt::arg("radial", falloffName(f.radialFalloff)), fmt::arg("s0", frame.sMin), fmt::arg("s1", frame.sMax),
        fmt::arg("h0", frame.hMin), fmt::arg("h1", frame.hMax), fmt::arg("max", std::max(scale, 1e-9)));
    runGnuplot(script, dir.path(), {scene.name}); // the name is data (ARG1), never script text
    publish(dir.path() / "slice.png", target);
    fmt::print("wrote {} (peak |F| = {:.4g} N)\n", shownPath(*options.out), maxMagnitude);
    return kExitSuccess;
}

/// The options of --at and of --slice do not mix: one that the chosen one would ignore is refused.
void checkFieldOptions(const FieldOptions& options)
{
    if (options.slice && !options.at.empty())
        throw UsageError("--at: prints the force at a point, and --slice draws a picture instead: give one of them");
    if (options.slice && options.json)
        throw UsageError("--json: prints --at's forces as JSON; --slice draws a picture: give --at, or drop --json");
    if (!options.slice && options.out)
        throw UsageError("--out: names --slice's picture, and there is no --slice (--at prints to the terminal)");
    // (A path ending in '/' has no file name to check: the output's own check names it a folder.)
    const std::filesystem::path out = options.out.value_or("");
    if (options.out && out.has_filename() && out.extension() != ".png")
        throw UsageError(fmt::format("--out: --slice writes a PNG, so the file must end in .png, got '{}'", *options.out));
}

int runField(const FieldOptions& options)
{
    checkFieldOptions(options);
    const Scene scene = loadSceneArgument(options.scene);
    if (options.slice)
        return drawSlice(scene, options);
    if (options.at.empty())
        throw UsageError("give --at X,Y,Z or --slice --out FILE.png");
    return printFieldAt(scene.world, options);
}

} // namespace

void addFieldCommand(CLI::App& root, Action& selected)
{
    auto options = std::make_shared<FieldOptions>();
    CLI::App* field = root.add_subcommand("field", "Inspect a scene's force fields: the force at a point, or a "
                                                   "picture of the blow dryer's field");
    addScenePositional(*field, options->scene, "blow-dryer");
    field->add_option("--at", options->atText, "Print the force on a unit-mass particle at rest at this point "
                                               "(each field's share and the total, gravity included)")
        ->option_text("X,Y,Z");
    field->add_flag("--json", options->json,
                    "With --at: print {\"at\": [x,y,z], \"forces\": [{\"force\": [x,y,z], \"type\": NAME}, ...], "
                    "\"total\": [x,y,z]} instead");
    field->add_flag("--slice", options->slice, "Draw the field in the vertical plane through the dryer's axis: "
                                               "magnitude colour map, arrows, the cone and the floor");
    field->add_option("--out", options->out, "With --slice: the PNG to write")->type_name("FILE.png");
    field->add_option("--resolution", options->resolution,
                      "With --slice: colour map samples across the picture, 16 to 2000 (default 240)")
        ->transform(decimalOnly())
        ->check(CLI::Range(16, 2000))
        ->option_text("N");
    field->footer("\nExamples:\n  pba field blow-dryer --at 0,1,0\n  pba field blow-dryer-flow --slice --out pba-out/field.png\n");
    field->callback([options, &selected] {
        selected = [options] {
            FieldOptions read = *options;
            read.at = numberList("--at", read.atText);
            return runField(read);
        };
    });
}

} // namespace pba::app
