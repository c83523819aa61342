#include "io/output_manifest.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstring>
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
    return !name.empty() && name != "." && name != ".." && name.find('/') == std::string_view::npos;
}

/// A name on one line: '%', the control characters and DEL as %XX (a user may name an output
/// "new\nline.png").
std::string escapeName(std::string_view name)
{
    std::string out;
    for (const char c : name) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f || c == '%')
            out += fmt::format("%{:02X}", byte);
        else
            out += c;
    }
    return out;
}

/// escapeName's inverse; nothing for a '%' that is not followed by two hex digits.
std::optional<std::string> unescapeName(std::string_view text)
{
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') {
            out += text[i];
            continue;
        }
        unsigned byte = 0;
        const char* digits = text.data() + i + 1;
        if (i + 3 > text.size() || std::from_chars(digits, digits + 2, byte, 16).ptr != digits + 2)
            return std::nullopt;
        out += static_cast<char>(byte);
        i += 2;
    }
    return out;
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
    const auto name = unescapeName(line.substr(space + 18));
    if (!name || !plainName(*name))
        return std::nullopt;
    entry.name = *name;
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
        out += fmt::format("{} {:016x} {}\n", e.fingerprint.size, e.fingerprint.hash, escapeName(e.name));
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

void writeManifest(const fs::path& folder, const OutputManifest& manifest)
{
    Temporary temporary(folder / kManifestName, Temporary::Kind::File); // its commit lists nothing
    writeFile(temporary.path(), manifest.text());
    temporary.commit();
}

ManifestLock::ManifestLock(const fs::path& folder) : m_fd(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC))
{
    // Without the lock (a folder that cannot be opened, a file system without flock) only two pba
    // runs into one folder at once could lose an entry: the file is then refused later, not lost.
    while (m_fd >= 0 && ::flock(m_fd, LOCK_EX) != 0 && errno == EINTR) {
    }
}

ManifestLock::~ManifestLock()
{
    if (m_fd >= 0)
        ::close(m_fd); // releases the lock
}

namespace {

enum class Owner { Pba, ChangedSince, User };

/// Whose the existing file `target` is: pba's while it holds the bytes the manifest lists.
Owner ownerOf(const fs::path& target, const OutputManifest& manifest, std::optional<Fingerprint>* bytes = nullptr)
{
    const std::string name = target.filename().string();
    std::error_code ec;
    const bool regular = fs::is_regular_file(fs::symlink_status(target, ec));
    const auto fingerprint = regular ? fingerprintOf(target) : std::nullopt;
    if (bytes)
        *bytes = fingerprint;
    if (fingerprint && manifest.lists(name, *fingerprint))
        return Owner::Pba;
    return manifest.listsName(name) ? Owner::ChangedSince : Owner::User;
}

} // namespace

void requireReplaceable(const fs::path& target, const fs::path& shown)
{
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(target, ec)))
        return;
    const Owner owner = ownerOf(target, readManifest(folderOf(target)));
    if (owner != Owner::Pba)
        throw BadOutput(fmt::format("{}: {} (pba replaces only its own files, as it wrote them): move it away, or "
                                    "write to another path", shown.string(),
                                    owner == Owner::User ? "a file pba did not write" : "changed since pba wrote it"));
}

OutputManifest stillThere(const fs::path& folder, const OutputManifest& manifest,
                          const std::function<bool(const std::string&)>& skip)
{
    OutputManifest out;
    for (const ManifestEntry& e : manifest.entries) {
        std::error_code ec;
        if (!skip(e.name) && fs::exists(fs::symlink_status(folder / e.name, ec)))
            out.entries.push_back(e);
    }
    return out;
}

void publishBetween(const fs::path& folder, const OutputManifest& during, const std::function<void()>& move,
                    const OutputManifest& after)
{
    writeManifest(folder, during);
    move();
    try {
        writeManifest(folder, after);
    } catch (const WriteError&) {
        // The files are in place and `during` lists each of them: true, only longer.
    }
}

void publishListed(const fs::path& made, const fs::path& target, const fs::path& shown)
{
    const fs::path folder = folderOf(target);
    const std::string name = target.filename().string();
    const ManifestLock lock(folder);
    const OutputManifest manifest = readManifest(folder);
    std::error_code ec;
    std::optional<Fingerprint> old;
    if (fs::exists(fs::symlink_status(target, ec)))
        if (const Owner owner = ownerOf(target, manifest, &old); owner != Owner::Pba)
            throw BadOutput(fmt::format("{}: {} while pba worked: nothing was written; move it away, or write to "
                                        "another path", shown.string(), owner == Owner::User ? "appeared" : "changed"));
    const auto written = fingerprintOf(made);
    if (!written)
        throw WriteError(fmt::format("{}: cannot be read back: {}", made.string(), std::strerror(errno)));
    // The folder's other files pba wrote, still there, and this one.
    OutputManifest after = stillThere(folder, manifest, [&](const std::string& n) { return n == name; });
    OutputManifest during = after;
    if (old)
        during.entries.push_back({name, *old});
    during.entries.push_back({name, *written});
    after.entries.push_back({name, *written});
    publishBetween(folder, during, [&] {
        fs::rename(made, target, ec);
        if (ec)
            throw WriteError(fmt::format("{}: cannot be replaced: {}", shown.string(), ec.message()));
    }, after);
}

} // namespace pba::io
