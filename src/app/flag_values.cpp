#include "flag_values.hpp"

#include <cstdlib>
#include <string>

#include <fmt/format.h>

#include "command.hpp"

namespace pba::app {

std::vector<std::string> listItems(const std::string& flag, const std::string& text)
{
    if (text.empty())
        return {}; // not given: main() refuses an empty value typed on the command line
    std::vector<std::string> items(1);
    for (const char c : text) {
        if (c == ',')
            items.emplace_back();
        else
            items.back() += c;
    }
    for (std::size_t i = 0; i < items.size(); ++i)
        if (items[i].empty())
            throw UsageError(fmt::format("{}: item {} of '{}' is empty; give a comma-separated list with no empty "
                                         "item", flag, i + 1, text));
    return items;
}

std::vector<double> numberList(const std::string& flag, const std::string& text)
{
    std::vector<double> numbers;
    for (const std::string& item : listItems(flag, text)) {
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (end != item.c_str() + item.size())
            throw UsageError(fmt::format("{}: cannot read '{}' as a number", flag, item));
        numbers.push_back(x);
    }
    return numbers;
}

} // namespace pba::app
