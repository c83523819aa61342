#include "lanes.hpp"

#include <vector>

#include "study/exact_solution.hpp"

namespace pba::app {

std::function<std::optional<glm::vec3>(std::size_t, double)> exactGhosts(const World& initial)
{
    std::vector<std::optional<study::ExactSolution>> exact;
    for (std::size_t i = 0; i < initial.bodyCount(); ++i)
        exact.push_back(initial.body(i).isFixed() ? std::nullopt : study::ExactSolution::find(initial, i));
    return [exact](std::size_t i, double t) -> std::optional<glm::vec3> {
        if (i >= exact.size() || !exact[i])
            return std::nullopt;
        return glm::vec3(exact[i]->position(t));
    };
}

} // namespace pba::app
