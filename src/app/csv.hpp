#pragma once
// CSV as RFC 4180 has it, for the fields pba writes that come from a user (names).
#include <string>

namespace pba::app {

/// The field, quoted with its quotes doubled when it holds a comma, a quote or a line break.
inline std::string csvField(const std::string& text)
{
    if (text.find_first_of(",\"\r\n") == std::string::npos)
        return text;
    std::string quoted = "\"";
    for (const char c : text)
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

} // namespace pba::app
