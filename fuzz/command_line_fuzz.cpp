// libFuzzer target for the command line's numbers and the CSV writer:
//  - any four strings given as --dt, --duration, --integrator and --collision to a scene-taking
//    command either parse into a run that is finite, positive and at most kMaxSteps steps long,
//    or are refused as bad input (CLI11's ParseError, UsageError, SceneError): never a crash, a
//    hang or an unbounded run;
//  - any name written as a CSV field reads back, by RFC 4180, as the same name in one field.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "command.hpp"
#include "csv.hpp"
#include "scene_options.hpp"

namespace {

/// Reads one RFC 4180 field from the start of `text`; `rest` is what follows it.
std::string readCsvField(std::string_view text, std::string_view& rest)
{
    std::string field;
    if (text.empty() || text[0] != '"') {
        const std::size_t end = text.find(',');
        rest = end == std::string_view::npos ? std::string_view() : text.substr(end);
        return std::string(text.substr(0, end));
    }
    std::size_t i = 1;
    for (; i < text.size(); ++i) {
        if (text[i] == '"') {
            if (i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else {
                break;
            }
        } else {
            field += text[i];
        }
    }
    if (i >= text.size())
        __builtin_trap(); // an opened quote that never closes
    rest = text.substr(i + 1);
    return field;
}

void checkCsv(std::string_view name)
{
    const std::string row = pba::app::csvField(std::string(name)) + ",1";
    std::string_view rest;
    const std::string back = readCsvField(row, rest);
    if (back != name || rest != ",1")
        __builtin_trap();
}

void checkFlags(const std::vector<std::string>& values)
{
    using namespace pba::app;
    CLI::App app;
    SceneOptions options;
    addSceneOptions(app, options, "spring");
    std::vector<std::string> args{"spring", "--dt", values[0], "--duration", values[1], "--integrator", values[2],
                                  "--collision", values[3]};
    std::reverse(args.begin(), args.end()); // CLI11 takes them in reverse
    try {
        app.parse(args);
        const pba::Scene scene = loadSceneWithOverrides(options);
        if (!(std::isfinite(scene.dt) && scene.dt > 0.0 && std::isfinite(scene.duration) && scene.duration > 0.0 &&
              std::round(scene.duration / scene.dt) <= kMaxSteps))
            __builtin_trap();
    } catch (const CLI::ParseError&) {
    } catch (const UsageError&) {
    } catch (const pba::SceneError&) {
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    checkCsv(text);
    std::vector<std::string> values(4);
    std::size_t k = 0;
    for (const char c : text) {
        if (c == '\n' && k < 3)
            ++k;
        else
            values[k] += c;
    }
    checkFlags(values);
    return 0;
}
