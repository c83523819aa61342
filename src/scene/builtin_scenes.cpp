#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pba/scene/scene.hpp"

namespace pba {
namespace detail {
extern const std::pair<std::string_view, std::string_view> kBuiltinScenes[];
extern const std::size_t kBuiltinSceneCount;
} // namespace detail

std::vector<std::string> builtinSceneNames()
{
    std::vector<std::string> names;
    for (std::size_t i = 0; i < detail::kBuiltinSceneCount; ++i)
        names.emplace_back(detail::kBuiltinScenes[i].first);
    return names;
}

std::string_view builtinSceneText(std::string_view name)
{
    for (std::size_t i = 0; i < detail::kBuiltinSceneCount; ++i)
        if (detail::kBuiltinScenes[i].first == name)
            return detail::kBuiltinScenes[i].second;
    return {};
}

std::string builtinSceneSummary(std::string_view name)
{
    const std::string_view text = builtinSceneText(name);
    if (text.empty())
        return {};
    const auto document = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
    if (!document.is_object() || !document.contains("summary") || !document["summary"].is_string())
        return {};
    return document["summary"].get<std::string>();
}

} // namespace pba
