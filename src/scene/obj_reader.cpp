#include "obj_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "one_line.hpp"

namespace pba::scene_detail {

namespace {

/// A word of a line quoted in a message: enough to find it, too little to show a file's secrets.
constexpr std::size_t kQuotedWordLength = 24;

std::string quoted(std::string_view word) { return fmt::format("'{}'", oneLine(word, kQuotedWordLength)); }

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// The whitespace-separated words of a line, into `words` (kept from line to line).
void wordsOf(std::string_view line, std::vector<std::string_view>& words)
{
    words.clear();
    for (std::size_t i = 0; i < line.size();) {
        while (i < line.size() && isSpace(line[i]))
            ++i;
        const std::size_t start = i;
        while (i < line.size() && !isSpace(line[i]))
            ++i;
        if (i > start)
            words.push_back(line.substr(start, i - start));
    }
}

/// `word` read whole as a finite number (a leading '+' allowed, as C's strtod does).
std::optional<double> finiteNumber(std::string_view word)
{
    if (word.size() > 1 && word[0] == '+' && word[1] != '-' && word[1] != '+')
        word.remove_prefix(1);
    double x = 0.0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), x);
    if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(x))
        return std::nullopt;
    return x;
}

/// `word` read whole as a whole number.
std::optional<long> wholeNumber(std::string_view word)
{
    long n = 0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), n);
    if (word.empty() || error != std::errc() || end != word.data() + word.size())
        return std::nullopt;
    return n;
}

dvec3 readVertex(const std::vector<std::string_view>& words, std::size_t line)
{
    // x y z, or x y z r g b (a colour, as some exporters write it): nothing else.
    if (words.size() != 4 && words.size() != 7)
        throw std::runtime_error(fmt::format("line {}: a vertex is three numbers x y z (or six, with a colour r g b), "
                                             "got {} words", line, words.size() - 1));
    double xyz[6] = {};
    for (std::size_t k = 1; k < words.size(); ++k) {
        const auto x = finiteNumber(words[k]);
        if (!x)
            throw std::runtime_error(fmt::format("line {}: {} is not a finite number", line, quoted(words[k])));
        xyz[k - 1] = *x;
    }
    return {xyz[0], xyz[1], xyz[2]};
}

/// A face's corner, v or v/vt or v//vn or v/vt/vn, as an index into the vertices so far.
std::uint32_t readCorner(std::string_view corner, std::size_t count, std::size_t line)
{
    std::vector<std::string_view> parts;
    for (std::size_t start = 0;;) {
        const std::size_t slash = corner.find('/', start);
        parts.push_back(corner.substr(start, slash == std::string_view::npos ? slash : slash - start));
        if (slash == std::string_view::npos)
            break;
        start = slash + 1;
    }
    const auto index = wholeNumber(parts[0]);
    bool valid = index.has_value() && parts.size() <= 3;
    for (std::size_t k = 1; valid && k < parts.size(); ++k)
        valid = parts[k].empty() ? k == 1 && parts.size() == 3 : wholeNumber(parts[k]).has_value();
    if (!valid)
        throw std::runtime_error(fmt::format("line {}: {} is not a corner (v, v/vt, v//vn or v/vt/vn, whole numbers)",
                                             line, quoted(corner)));
    const long n = static_cast<long>(count);
    const long resolved = *index < 0 ? n + *index : *index - 1;
    if (*index == 0 || resolved < 0 || resolved >= n)
        throw std::runtime_error(
            fmt::format("line {}: vertex {} does not exist (there are {} so far)", line, *index, count));
    return static_cast<std::uint32_t>(resolved);
}

void readFace(const std::vector<std::string_view>& words, std::size_t line, ObjMesh& mesh)
{
    std::vector<std::uint32_t> polygon;
    for (std::size_t k = 1; k < words.size(); ++k)
        polygon.push_back(readCorner(words[k], mesh.vertices.size(), line));
    if (polygon.size() < 3)
        throw std::runtime_error(fmt::format("line {}: a face needs at least three vertices", line));
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
        mesh.triangles.insert(mesh.triangles.end(), {polygon[0], polygon[k], polygon[k + 1]});
}

} // namespace

ObjMesh parseObj(std::string_view text)
{
    // A byte order mark would make the first statement "\xEF\xBB\xBFv" and drop its vertex.
    constexpr std::string_view kBom = "\xEF\xBB\xBF";
    if (text.substr(0, kBom.size()) == kBom)
        text.remove_prefix(kBom.size());
    ObjMesh mesh;
    std::vector<std::string_view> words;
    std::size_t number = 0;
    for (std::size_t start = 0; start < text.size();) {
        ++number;
        const std::size_t end = std::min(text.find('\n', start), text.size());
        if (end - start > kMaxObjLineBytes)
            throw std::runtime_error(fmt::format("line {} is longer than {} KiB: not an OBJ file?", number,
                                                 kMaxObjLineBytes / 1024));
        wordsOf(text.substr(start, end - start), words);
        start = end + 1;
        if (words.empty())
            continue;
        if (words[0] == "v")
            mesh.vertices.push_back(readVertex(words, number));
        else if (words[0] == "f")
            readFace(words, number, mesh);
    }
    if (mesh.triangles.empty())
        throw std::runtime_error("has no faces");
    return mesh;
}

} // namespace pba::scene_detail
