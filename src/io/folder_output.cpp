#include "io/folder_output.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

namespace pba::io {

namespace fs = std::filesystem;

FolderOutput::MadeFolders::~MadeFolders()
{
    for (auto p = paths.rbegin(); p != paths.rend(); ++p) {
        std::error_code ignored;
        if (!keep)
            fs::remove(*p, ignored); // only if empty: nothing of anyone's goes
        unregisterMadeFolder(*p);
    }
}

FolderOutput::FolderOutput(const fs::path& requested, NamePredicate owns)
    : m_folder(resolveOutputFolder(requested)), m_owns(std::move(owns))
{
    checkFolder();
    makeFolders();
    // The staging folder is pba's own name: a folder that refuses it is named as the user gave it.
    if (::access(m_folder.c_str(), W_OK) != 0)
        throw BadOutput(fmt::format("{}: cannot be written: {}", m_folder.string(), std::strerror(errno)));
    m_staging.emplace(m_folder / ".pba-staging", Temporary::Kind::Folder);
}

FolderOutput::~FolderOutput() = default;

std::optional<FolderOutput::Stamp> FolderOutput::stampOf(const fs::path& file)
{
    struct stat s {};
    if (::lstat(file.c_str(), &s) != 0)
        return std::nullopt;
    return Stamp{std::uintmax_t(s.st_size), s.st_mtim.tv_sec * 1'000'000'000LL + s.st_mtim.tv_nsec,
                 (unsigned long long)s.st_ino};
}

/// Every file with one of this output's names must be pba's, with the bytes pba wrote: anything
/// else would be replaced, or left among the new files as if it were one of them.
void FolderOutput::checkFolder()
{
    std::error_code ec;
    if (!fs::is_directory(m_folder, ec))
        return; // made below: nothing in it yet
    m_manifest = readManifest(m_folder);
    for (fs::directory_iterator it(m_folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!m_owns(name))
            continue;
        std::error_code statError;
        const bool regular = fs::is_regular_file(it->symlink_status(statError));
        const auto fingerprint = regular ? fingerprintOf(it->path()) : std::nullopt;
        const auto stamp = stampOf(it->path());
        if (fingerprint && stamp && m_manifest.lists(name, *fingerprint)) {
            m_owned.emplace(name, *stamp);
            continue;
        }
        const char* why = !regular                     ? "not a file pba wrote (a folder, a link or a device)"
                          : m_manifest.listsName(name) ? "changed since pba wrote it"
                                                       : "not written by pba";
        throw BadOutput(fmt::format("{}: {}, and this output writes files of that name: move it away, or give --out "
                                    "another folder", it->path().string(), why));
    }
    if (ec)
        throw BadOutput(fmt::format("{}: cannot be read: {}", m_folder.string(), ec.message()));
}

void FolderOutput::makeFolders()
{
    for (const fs::path& folder : {m_folder.parent_path(), m_folder}) {
        std::error_code ec;
        if (fs::is_directory(folder, ec))
            continue;
        if (!fs::create_directory(folder, ec))
            throw BadOutput(fmt::format("{}: cannot be made: {}", folder.string(),
                                        ec ? ec.message() : std::string("it is not a folder")));
        m_made.paths.push_back(folder);
        registerMadeFolder(folder);
    }
}

/// The staging folder's files, fingerprinted; each must have one of this output's names.
std::vector<ManifestEntry> FolderOutput::newFiles() const
{
    std::vector<ManifestEntry> written;
    for (const auto& entry : fs::directory_iterator(path())) {
        const std::string name = entry.path().filename().string();
        if (!m_owns(name) || !entry.is_regular_file())
            throw WriteError(fmt::format("{}: pba made a file it does not own here: {}", m_folder.string(), name));
        const auto fingerprint = fingerprintOf(entry.path());
        if (!fingerprint)
            throw WriteError(fmt::format("{}: cannot be read back: {}", entry.path().string(), std::strerror(errno)));
        written.push_back({name, *fingerprint});
    }
    return written;
}

/// The folder as checked at the start, as far as this output's names go: a file that appeared
/// or changed while the work ran is as much the user's as one that was there before.
void FolderOutput::recheckFolder() const
{
    for (const auto& entry : fs::directory_iterator(m_folder)) {
        const std::string name = entry.path().filename().string();
        if (!m_owns(name))
            continue;
        const auto seen = m_owned.find(name);
        if (seen == m_owned.end() || stampOf(entry.path()) != seen->second)
            throw BadOutput(fmt::format("{}: appeared or changed while pba worked, and this output writes files of "
                                        "that name: nothing was written; move it away, or give --out another folder",
                                        entry.path().string()));
    }
}

/// The renames, between two manifests: the first lists the old and the new bytes of every name
/// (so a crash half way leaves only files pba knows as its own), the second only what is there
/// at the end.
void FolderOutput::publish(const std::vector<ManifestEntry>& written)
{
    // Other outputs' files in the same folder, still there, as another run may have left them.
    const OutputManifest kept = stillThere(m_folder, readManifest(m_folder), m_owns);
    OutputManifest during = kept, after = kept;
    for (const ManifestEntry& e : m_manifest.entries)
        if (m_owned.count(e.name))
            during.entries.push_back(e);
    for (const ManifestEntry& e : written) {
        during.entries.push_back(e);
        after.entries.push_back(e);
    }
    publishBetween(m_folder, during, [&] {
        for (const ManifestEntry& e : written) {
            std::error_code ec;
            fs::rename(path() / e.name, m_folder / e.name, ec);
            if (ec)
                throw WriteError(fmt::format("{}: cannot be replaced: {}", (m_folder / e.name).string(), ec.message()));
        }
        for (const auto& [name, stamp] : m_owned)
            if (!after.listsName(name)) {
                std::error_code ec;
                fs::remove(m_folder / name, ec); // stale: pba's, unchanged, and not of this run
            }
    }, after);
}

void FolderOutput::commit()
{
    if (!syncTree(path()))
        throw WriteError(fmt::format("{}: write failed: {}", m_folder.string(), std::strerror(errno)));
    const std::vector<ManifestEntry> written = newFiles();
    const auto signalsWait = deferSignals();
    const ManifestLock lock(m_folder);
    recheckFolder();
    publish(written);
    syncToDisk(m_folder, true); // the renames themselves, on the disk
    m_made.keep = true;
}

} // namespace pba::io
