#include "flag_values.hpp"

#include <cctype>
#include <cstdlib>
#include <string>

#include <fmt/format.h>

#include "command.hpp"

namespace pba::app {

namespace {

/// How many digits `text` holds from `at` on.
std::size_t digitsAt(const std::string& text, std::size_t at)
{
    std::size_t n = 0;
    while (at + n < text.size() && std::isdigit(static_cast<unsigned char>(text[at + n])))
        ++n;
    return n;
}

/// Whether `text` is [+-]digits[.digits][(e|E)[+-]digits], with a digit before or after the point.
bool isDecimal(const std::string& text)
{
    std::size_t at = text.size() > 0 && (text[0] == '+' || text[0] == '-') ? 1 : 0;
    std::size_t mantissa = digitsAt(text, at);
    at += mantissa;
    if (at < text.size() && text[at] == '.') {
        const std::size_t fraction = digitsAt(text, at + 1);
        mantissa += fraction;
        at += 1 + fraction;
    }
    if (mantissa == 0)
        return false;
    if (at < text.size() && (text[at] == 'e' || text[at] == 'E')) {
        ++at;
        if (at < text.size() && (text[at] == '+' || text[at] == '-'))
            ++at;
        const std::size_t exponent = digitsAt(text, at);
        if (exponent == 0)
            return false;
        at += exponent;
    }
    return at == text.size();
}

/// `text` (decimal) without the leading zeros of its whole part, which strtoll reads as octal's.
void dropLeadingZeros(std::string& text)
{
    const std::size_t sign = text[0] == '+' || text[0] == '-' ? 1 : 0;
    std::size_t zeros = 0;
    while (sign + zeros + 1 < text.size() && text[sign + zeros] == '0' &&
           std::isdigit(static_cast<unsigned char>(text[sign + zeros + 1])))
        ++zeros;
    text.erase(sign, zeros);
}

std::string notANumber(const std::string& text)
{
    return fmt::format("cannot read '{}' as a number: write it in decimal, such as 0.25 or 1e-3", text);
}

} // namespace

std::optional<double> decimalNumber(const std::string& text)
{
    if (!isDecimal(text))
        return std::nullopt;
    return std::strtod(text.c_str(), nullptr);
}

CLI::Validator decimalOnly()
{
    return CLI::Validator(
        [](std::string& text) {
            if (!isDecimal(text))
                return notANumber(text);
            dropLeadingZeros(text);
            return std::string();
        },
        "", "decimal");
}

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
        const std::optional<double> x = decimalNumber(item);
        if (!x)
            throw UsageError(fmt::format("{}: {}", flag, notANumber(item)));
        numbers.push_back(*x);
    }
    return numbers;
}

} // namespace pba::app
