#pragma once
// Reading a JSON object field by field while keeping the JSON path, so that every
// error names the file, the field (e.g. particles[1].mass) and the reason, and keys
// nobody asked for are reported (they are usually typos).
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "pba/math.hpp"
#include "pba/scene/scene.hpp"
#include "closest_name.hpp"

namespace pba::scene_detail {

using Json = nlohmann::json;

class ObjectReader {
public:
    /// Throws unless `value` is an object.
    ObjectReader(const Json& value, std::string path, const std::string& file);

    /// Declares the keys this object may hold and reports the first other one, with the known key
    /// it is closest to. Called before anything is read: a typo ("stifness") must be named rather
    /// than the required key it hides ("stiffness is missing") or a later error it causes.
    void expectKeys(std::vector<std::string> known);

    bool has(const std::string& key) const { return m_value.contains(key); }
    /// The path of a field of this object, e.g. "particles[1].mass".
    std::string pathOf(const std::string& key) const;
    [[noreturn]] void fail(const std::string& key, const std::string& reason) const;
    [[noreturn]] void failHere(const std::string& reason) const;

    const Json& raw(const std::string& key);
    double number(const std::string& key);
    double number(const std::string& key, double fallback);
    double positive(const std::string& key, std::optional<double> fallback = std::nullopt);
    double nonNegative(const std::string& key, std::optional<double> fallback = std::nullopt);
    std::string string(const std::string& key);
    std::string string(const std::string& key, const std::string& fallback);
    bool boolean(const std::string& key, bool fallback);
    dvec3 vec3(const std::string& key);
    dvec3 vec3(const std::string& key, const dvec3& fallback);
    ObjectReader object(const std::string& key);
    /// Calls `each(item, index)` for every element of the array at `key` (absent: none).
    void array(const std::string& key, const std::function<void(const Json&, const std::string&, std::size_t)>& each);

    /// Reports the first key that was never read.
    void finish() const;

    const std::string& path() const { return m_path; }
    const std::string& file() const { return m_file; }

private:
    const Json& require(const std::string& key);
    double toNumber(const Json& value, const std::string& key) const;

    const Json& m_value;
    std::string m_path;
    const std::string& m_file;
    std::set<std::string> m_read;
    std::vector<std::string> m_known; ///< empty until expectKeys()
};

} // namespace pba::scene_detail
