#include "flag_values.hpp"

#include <cstdlib>
#include <string>

#include <fmt/format.h>

#include "command.hpp"

namespace pba::app {

std::vector<std::string> listItems(const std::string& text)
{
    std::vector<std::string> items(1);
    for (const char c : text) {
        if (c == ',')
            items.emplace_back();
        else
            items.back() += c;
    }
    std::erase(items, std::string());
    return items;
}

std::vector<double> numberList(const std::string& flag, const std::string& text)
{
    std::vector<double> numbers;
    for (const std::string& item : listItems(text)) {
        char* end = nullptr;
        const double x = std::strtod(item.c_str(), &end);
        if (item.empty() || end != item.c_str() + item.size())
            throw UsageError(fmt::format("{}: cannot read '{}' as a number", flag, item));
        numbers.push_back(x);
    }
    return numbers;
}

} // namespace pba::app
