#include "json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "one_line.hpp"

namespace pba::scene_detail {

namespace {
std::string typeName(const Json& value)
{
    if (value.is_number())
        return "a number";
    if (value.is_string())
        return "a string";
    if (value.is_boolean())
        return "a boolean";
    if (value.is_array())
        return "an array";
    if (value.is_object())
        return "an object";
    return "null";
}
std::string unknownKeyReason(const std::string& key, const std::vector<std::string>& known)
{
    if (const auto close = closestName(key, known))
        return fmt::format("unknown key (did you mean \"{}\"?)", *close);
    return fmt::format("unknown key (expected one of: {})", fmt::join(known, ", "));
}
} // namespace

ObjectReader::ObjectReader(const Json& value, std::string path, const std::string& file)
    : m_value(value), m_path(std::move(path)), m_file(file)
{
    if (!value.is_object())
        failHere(fmt::format("expected an object, got {}", typeName(value)));
}

void ObjectReader::expectKeys(std::vector<std::string> known)
{
    m_known = std::move(known);
    for (const auto& item : m_value.items())
        if (std::find(m_known.begin(), m_known.end(), item.key()) == m_known.end())
            fail(item.key(), unknownKeyReason(item.key(), m_known));
}

std::string ObjectReader::pathOf(const std::string& key) const
{
    // An unknown key is the user's text: escaped and cut like any other.
    return m_path.empty() ? oneLine(key) : m_path + "." + oneLine(key);
}

void ObjectReader::fail(const std::string& key, const std::string& reason) const
{
    throw SceneError(m_file, pathOf(key), reason);
}

void ObjectReader::failHere(const std::string& reason) const
{
    throw SceneError(m_file, m_path.empty() ? "(scene)" : m_path, reason);
}

const Json& ObjectReader::require(const std::string& key)
{
    // A key read but not declared would be refused as unknown in every file that gives it.
    if (!m_known.empty() && std::find(m_known.begin(), m_known.end(), key) == m_known.end())
        throw std::logic_error(fmt::format("scene reader: {} is read but not in its object's expected keys",
                                           pathOf(key)));
    if (!m_value.contains(key))
        fail(key, "is required but missing");
    m_read.insert(key);
    return m_value.at(key);
}

const Json& ObjectReader::raw(const std::string& key) { return require(key); }

double ObjectReader::toNumber(const Json& value, const std::string& key) const
{
    if (!value.is_number())
        fail(key, fmt::format("expected a number, got {}", typeName(value)));
    const double x = value.get<double>();
    if (!std::isfinite(x))
        fail(key, "must be finite");
    return x;
}

double ObjectReader::number(const std::string& key) { return toNumber(require(key), key); }

double ObjectReader::number(const std::string& key, double fallback) { return has(key) ? number(key) : fallback; }

double ObjectReader::positive(const std::string& key, std::optional<double> fallback)
{
    const double x = fallback && !has(key) ? *fallback : number(key);
    if (!(x > 0.0))
        fail(key, fmt::format("must be positive, got {}", x));
    return x;
}

double ObjectReader::nonNegative(const std::string& key, std::optional<double> fallback)
{
    const double x = fallback && !has(key) ? *fallback : number(key);
    if (x < 0.0)
        fail(key, fmt::format("must not be negative, got {}", x));
    return x;
}

std::string ObjectReader::string(const std::string& key)
{
    const Json& value = require(key);
    if (!value.is_string())
        fail(key, fmt::format("expected a string, got {}", typeName(value)));
    return value.get<std::string>();
}

std::string ObjectReader::string(const std::string& key, const std::string& fallback)
{
    return has(key) ? string(key) : fallback;
}

bool ObjectReader::boolean(const std::string& key, bool fallback)
{
    if (!has(key))
        return fallback;
    const Json& value = require(key);
    if (!value.is_boolean())
        fail(key, fmt::format("expected a boolean, got {}", typeName(value)));
    return value.get<bool>();
}

dvec3 ObjectReader::vec3(const std::string& key)
{
    const Json& value = require(key);
    if (!value.is_array() || value.size() != 3)
        fail(key, fmt::format("expected an array of 3 numbers, got {}",
                              value.is_array() ? fmt::format("{} elements", value.size()) : typeName(value)));
    dvec3 v;
    for (int i = 0; i < 3; ++i)
        v[i] = toNumber(value[static_cast<std::size_t>(i)], fmt::format("{}[{}]", key, i));
    return v;
}

dvec3 ObjectReader::vec3(const std::string& key, const dvec3& fallback) { return has(key) ? vec3(key) : fallback; }

ObjectReader ObjectReader::object(const std::string& key) { return ObjectReader(require(key), pathOf(key), m_file); }

void ObjectReader::array(const std::string& key,
                         const std::function<void(const Json&, const std::string&, std::size_t)>& each)
{
    if (!has(key))
        return;
    const Json& value = require(key);
    if (!value.is_array())
        fail(key, fmt::format("expected an array, got {}", typeName(value)));
    for (std::size_t i = 0; i < value.size(); ++i)
        each(value[i], fmt::format("{}[{}]", pathOf(key), i), i);
}

void ObjectReader::finish() const
{
    for (const auto& item : m_value.items())
        if (!m_read.count(item.key()))
            fail(item.key(), m_known.empty() ? "unknown key (a typo?)" : "is not used here");
}

} // namespace pba::scene_detail
