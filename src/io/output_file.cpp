#include "io/output_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "io/output_manifest.hpp"

namespace pba::io {

namespace {

namespace fs = std::filesystem;

/// What the signal watcher removes and stops; guarded by its mutex (the watcher is a thread,
/// not a signal handler, so it may lock and allocate).
struct Registry {
    std::mutex mutex;
    std::vector<fs::path> temporaries;
    std::vector<int> children;
    std::vector<fs::path> madeFolders;
};

Registry& registry()
{
    static Registry r;
    return r;
}

/// Held by a multi-rename commit, and by the signal watcher before it cleans up (deferSignals).
std::mutex& commitMutex()
{
    static std::mutex m;
    return m;
}

std::string describe(const fs::path& p) { return p.string(); }

/// A temporary folder is moved aside before it is emptied: a thread still writing files into it
/// by name can no longer add one behind remove_all's back.
void removeTemporary(const fs::path& p)
{
    fs::path gone = p;
    gone += ".gone";
    std::error_code moved, ignored;
    fs::rename(p, gone, moved);
    fs::remove_all(moved ? p : gone, ignored);
}

void forget(std::vector<fs::path>& list, const fs::path& p)
{
    list.erase(std::remove(list.begin(), list.end(), p), list.end());
}


/// The folder an output goes into must exist, or be one folder short of it: `pba-out/x.png` in a
/// fresh clone makes pba-out (Temporary does, once the work is done and writing starts), while a
/// missing folder above that (`typo/pba-out/x.png`) is more likely a mistake than a wish.
void requireParentFolder(const fs::path& requested, const fs::path& target)
{
    const fs::path parent = folderOf(target);
    std::error_code ec;
    if (fs::is_directory(parent, ec))
        return;
    if (fs::exists(parent, ec))
        throw BadOutput(fmt::format("{}: cannot be written: {} is not a folder", describe(requested), parent.string()));
    if (!fs::is_directory(folderOf(parent), ec))
        throw BadOutput(fmt::format("{}: cannot be written: the folder {} does not exist (a missing last folder is "
                                    "made, not a path of them)", describe(requested), folderOf(parent).string()));
}

} // namespace

fs::path folderOf(const fs::path& file) { return file.parent_path().empty() ? fs::path(".") : file.parent_path(); }

bool syncToDisk(const fs::path& p, bool directory)
{
    const int fd = ::open(p.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
    if (fd < 0)
        return false;
    const bool ok = ::fsync(fd) == 0 || errno == EINVAL; // some file systems cannot sync folders
    ::close(fd);
    return ok;
}

bool syncTree(const fs::path& folder)
{
    std::error_code ec;
    for (const auto& entry : fs::recursive_directory_iterator(folder, ec))
        if (entry.is_regular_file() && !syncToDisk(entry.path(), false))
            return false;
    return !ec && syncToDisk(folder, true);
}

fs::path resolveOutputFile(const fs::path& requested)
{
    if (requested.empty())
        throw BadOutput("--out: the path is empty");
    // `x.csv/` names a folder: refused here, before any work, not after it when the rename fails.
    if (!requested.has_filename() || requested.filename() == "." || requested.filename() == "..")
        throw BadOutput(fmt::format("{}: names a folder (it ends in '/'), expected a file path", describe(requested)));
    if (requested.filename() == kManifestName)
        throw BadOutput(fmt::format("{}: is the name of the list pba keeps of its files in a folder: choose another "
                                    "name", describe(requested)));
    std::error_code ec;
    fs::path target = requested;
    // Follow links one by one (a link may name a file that does not exist yet).
    for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
        const fs::path next = fs::read_symlink(target, ec);
        if (ec || hops == 40)
            throw BadOutput(fmt::format("{}: cannot follow the link", describe(requested)));
        target = next.is_absolute() ? next : (folderOf(target) / next).lexically_normal();
    }
    const fs::file_status status = fs::status(target, ec);
    if (fs::is_directory(status))
        throw BadOutput(fmt::format("{}: is a directory, expected a file path", describe(requested)));
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw BadOutput(fmt::format("{}: is not a regular file (a device, FIFO or socket): give a file path",
                                    describe(requested)));
    requireParentFolder(requested, target);
    requireReplaceable(target, requested);
    return target;
}

fs::path resolveOutputFolder(const fs::path& requested)
{
    if (requested.empty())
        throw BadOutput("--out: the path is empty");
    std::error_code ec;
    const fs::path named = requested.has_filename() ? requested : requested.parent_path(); // "out/" is "out"
    fs::path target = fs::weakly_canonical(fs::absolute(named, ec), ec); // absolute: a new folder has a parent
    if (ec)
        throw BadOutput(fmt::format("{}: cannot be resolved: {}", describe(requested), ec.message()));
    const fs::file_status status = fs::status(target, ec);
    if (fs::exists(status) && !fs::is_directory(status))
        throw BadOutput(fmt::format("{}: exists and is not a folder", describe(requested)));
    requireParentFolder(requested, target);
    return target;
}

Temporary::Temporary(fs::path target, Kind kind) : m_target(std::move(target)), m_kind(kind)
{
    std::error_code made;
    if (const fs::path parent = folderOf(m_target); !fs::is_directory(parent, made)) {
        // The one missing folder requireParentFolder let through, removed again with the
        // temporary if nothing else went into it.
        if (fs::create_directory(parent, made)) {
            m_madeFolder = parent;
            registerMadeFolder(parent);
        }
        if (!fs::is_directory(parent, made))
            throw BadOutput(fmt::format("{}: cannot be written: the folder {} cannot be made: {}", describe(m_target),
                                        parent.string(), made ? made.message() : "it is not a folder"));
    }
    // NAME.tmp-PID beside the target; a name near the file system's limit of 255 bytes is cut
    // so that the temporary's still fits (a legal 255-byte name could not be written).
    constexpr std::size_t kNameMax = 255;
    const std::string suffix = fmt::format(".tmp-{}", ::getpid());
    std::string name = m_target.filename().string();
    if (name.size() + suffix.size() > kNameMax)
        name.resize(kNameMax - suffix.size());
    m_temporary = m_target.parent_path() / (name + suffix);
    {
        std::lock_guard lock(registry().mutex);
        registry().temporaries.push_back(m_temporary);
    }
    std::error_code ec;
    fs::remove_all(m_temporary, ec); // a leftover of an earlier process with the same id
    if (kind == Kind::Folder && !fs::create_directory(m_temporary, ec))
        throw BadOutput(fmt::format("{}: cannot be written: {}", describe(m_target), ec.message()));
}

Temporary::~Temporary()
{
    std::error_code ignored;
    if (!m_committed) {
        fs::remove_all(m_temporary, ignored);
        if (m_madeFolder)
            fs::remove(*m_madeFolder, ignored); // only if empty: nothing of anyone's goes
    }
    if (m_madeFolder)
        unregisterMadeFolder(*m_madeFolder);
    std::lock_guard lock(registry().mutex);
    forget(registry().temporaries, m_temporary);
}

/// A finished file is one the user named, to be listed in its folder's manifest, unless it is
/// the manifest itself or goes into a folder that is itself a temporary (a folder output's
/// staging folder, published as a whole; a scratch folder).
bool Temporary::listedWhenCommitted() const
{
    if (m_kind != Kind::File || m_target.filename() == kManifestName)
        return false;
    const fs::path folder = folderOf(m_target).lexically_normal();
    std::lock_guard lock(registry().mutex);
    return std::none_of(registry().temporaries.begin(), registry().temporaries.end(),
                        [&](const fs::path& p) { return p.lexically_normal() == folder; });
}

void Temporary::commit()
{
    const bool synced = m_kind == Kind::File ? syncToDisk(m_temporary, false) : syncTree(m_temporary);
    if (!synced)
        throw WriteError(fmt::format("{}: write failed: {}", describe(m_target), std::strerror(errno)));
    if (listedWhenCommitted()) {
        const auto signalsWait = deferSignals(); // the manifests and the rename, all or none
        publishListed(m_temporary, m_target, m_target);
    } else {
        // A folder is never swapped for an existing one, which would delete whatever the user
        // kept in it: rename() refuses a target folder that holds anything.
        std::error_code ec;
        fs::rename(m_temporary, m_target, ec);
        if (ec)
            throw WriteError(fmt::format("{}: cannot be replaced: {}", describe(m_target), ec.message()));
    }
    m_committed = true;
    syncToDisk(folderOf(m_target), true); // the rename itself, on the disk
}

bool writeAll(int fd, const void* bytes, std::size_t size)
{
    const char* p = static_cast<const char*>(bytes);
    while (size > 0) {
        const ssize_t n = ::write(fd, p, size);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        p += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

void writeFile(const fs::path& path, std::string_view bytes)
{
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        throw WriteError(fmt::format("{}: cannot be written: {}", describe(path), std::strerror(errno)));
    const bool written = writeAll(fd, bytes.data(), bytes.size());
    const int error = errno;
    const bool closed = ::close(fd) == 0;
    if (!written || !closed)
        throw WriteError(fmt::format("{}: write failed: {}", describe(path), std::strerror(written ? errno : error)));
}

void writeFileAtomically(const fs::path& target, std::string_view bytes)
{
    Temporary temporary(target, Temporary::Kind::File);
    writeFile(temporary.path(), bytes);
    temporary.commit();
}

void registerChild(int pid)
{
    std::lock_guard lock(registry().mutex);
    registry().children.push_back(pid);
}

void unregisterChild(int pid)
{
    std::lock_guard lock(registry().mutex);
    auto& list = registry().children;
    list.erase(std::remove(list.begin(), list.end(), pid), list.end());
}

void registerMadeFolder(const fs::path& folder)
{
    std::lock_guard lock(registry().mutex);
    registry().madeFolders.push_back(folder);
}

void unregisterMadeFolder(const fs::path& folder)
{
    std::lock_guard lock(registry().mutex);
    forget(registry().madeFolders, folder);
}

std::unique_lock<std::mutex> deferSignals() { return std::unique_lock(commitMutex()); }

void cleanUpOnSignals()
{
    sigset_t set;
    sigemptyset(&set);
    for (int signal : {SIGINT, SIGTERM, SIGHUP})
        sigaddset(&set, signal);
    ::pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread([set] {
        int signal = 0;
        while (::sigwait(&set, &signal) != 0) {
        }
        const std::lock_guard commit(commitMutex()); // a commit under way ends first
        // Held until the program dies: a thread whose write fails as its temporary goes then
        // waits in that Temporary's destructor, and cannot report the failure instead of the signal.
        const std::lock_guard lock(registry().mutex);
        for (int pid : registry().children)
            ::kill(pid, SIGTERM);
        for (const fs::path& p : registry().temporaries)
            removeTemporary(p);
        // Innermost first; remove() leaves a folder that holds anything.
        std::error_code ignored;
        for (auto p = registry().madeFolders.rbegin(); p != registry().madeFolders.rend(); ++p)
            fs::remove(*p, ignored);
        // Die of the signal, so the shell sees what stopped the program.
        ::signal(signal, SIG_DFL);
        ::pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
        ::raise(signal);
        ::_exit(128 + signal);
    }).detach();
}

} // namespace pba::io
