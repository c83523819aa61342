#include "io/output_manifest.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <fstream>

#include <fmt/format.h>

#include "io/output_file.hpp"

namespace pba::io {

namespace {

namespace fs = std::filesystem;

/// The first line; a later format would change the number.
constexpr std::string_view kHeader = "# pba-output 1";

bool plainName(std::string_view name)
{
    return !name.empty() && name != "." && name != ".." &&
           std::none_of(name.begin(), name.end(), [](char c) { return c == '/' || static_cast<unsigned char>(c) < 0x20; });
}

/// "SIZE HASH NAME", HASH 16 hex digits; nothing if the line is not one.
std::optional<ManifestEntry> parseEntry(std::string_view line)
{
    const std::size_t space = line.find(' ');
    if (space == std::string_view::npos || line.size() < space + 19 || line[space + 17] != ' ')
        return std::nullopt;
    ManifestEntry entry;
    const char* sizeEnd = line.data() + space;
    const char* hashEnd = sizeEnd + 17;
    if (std::from_chars(line.data(), sizeEnd, entry.fingerprint.size).ptr != sizeEnd ||
        std::from_chars(sizeEnd + 1, hashEnd, entry.fingerprint.hash, 16).ptr != hashEnd)
        return std::nullopt;
    entry.name = std::string(line.substr(space + 18));
    if (!plainName(entry.name))
        return std::nullopt;
    return entry;
}

} // namespace

std::optional<Fingerprint> fingerprintOf(const fs::path& file)
{
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return std::nullopt;
    Fingerprint f{0, 14695981039346656037ull}; // FNV-1a's offset basis and prime
    std::array<unsigned char, 1 << 16> buffer;
    ssize_t n = 0;
    while ((n = ::read(fd, buffer.data(), buffer.size())) != 0) {
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            break;
        for (ssize_t i = 0; i < n; ++i)
            f.hash = (f.hash ^ buffer[std::size_t(i)]) * 1099511628211ull;
        f.size += std::uintmax_t(n);
    }
    ::close(fd);
    if (n < 0)
        return std::nullopt;
    return f;
}

bool OutputManifest::lists(const std::string& name, const Fingerprint& fingerprint) const
{
    return std::any_of(entries.begin(), entries.end(),
                       [&](const ManifestEntry& e) { return e.name == name && e.fingerprint == fingerprint; });
}

bool OutputManifest::listsName(const std::string& name) const
{
    return std::any_of(entries.begin(), entries.end(), [&](const ManifestEntry& e) { return e.name == name; });
}

std::string OutputManifest::text() const
{
    std::string out = fmt::format("{}: the files pba wrote in this folder (bytes, FNV-1a hash, name). pba replaces "
                                  "or removes only these, and only while they hold these bytes.\n",
                                  kHeader);
    std::vector<ManifestEntry> sorted = entries;
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    for (const ManifestEntry& e : sorted)
        out += fmt::format("{} {:016x} {}\n", e.fingerprint.size, e.fingerprint.hash, e.name);
    return out;
}

OutputManifest readManifest(const fs::path& folder)
{
    const fs::path path = folder / kManifestName;
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(path, ec);
    if (!fs::exists(status))
        return {};
    std::ifstream in(path, std::ios::binary);
    std::string line;
    if (!fs::is_regular_file(status) || !in || !std::getline(in, line) || line.rfind(kHeader, 0) != 0)
        throw BadOutput(fmt::format("{}: not a list pba wrote of its files: move it away, or give --out another "
                                    "folder", path.string()));
    OutputManifest manifest;
    for (int number = 2; std::getline(in, line); ++number) {
        auto entry = parseEntry(line);
        if (!entry)
            throw BadOutput(fmt::format("{}: line {}: not an entry pba wrote (SIZE HASH NAME): move the file away, or "
                                        "give --out another folder", path.string(), number));
        manifest.entries.push_back(std::move(*entry));
    }
    return manifest;
}

} // namespace pba::io
