#pragma once
// `.pba-output`: the list pba keeps in every folder it writes an output into (a folder output, or
// the folder of a file output) of the files it wrote there, each with its size and a hash of its
// bytes, one a line (a name's '%' and control characters as %XX). It is how pba tells its own
// files (which a later run may replace, or remove once stale) from the user's, which it never
// touches: a file that is not listed, or no longer holds the bytes listed, is the user's.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace pba::io {

inline constexpr const char* kManifestName = ".pba-output";

/// What identifies a file's bytes: its size and their 64-bit FNV-1a hash (a check against
/// edits and mix-ups, not against forgery: the user owns the folder anyway).
struct Fingerprint {
    std::uintmax_t size = 0;
    std::uint64_t hash = 0;
    bool operator==(const Fingerprint&) const = default;
};

/// The fingerprint of a regular file; nothing if it cannot be read.
std::optional<Fingerprint> fingerprintOf(const std::filesystem::path& file);

struct ManifestEntry {
    std::string name; ///< a plain file name in the folder, no '/'
    Fingerprint fingerprint;
};

/// A name may be listed twice while a commit is under way: its old bytes and its new, either of
/// which is pba's (so a commit cut short by a crash leaves nothing pba disowns).
struct OutputManifest {
    std::vector<ManifestEntry> entries;

    bool lists(const std::string& name, const Fingerprint& fingerprint) const;
    bool listsName(const std::string& name) const;
    std::string text() const;
};

/// FOLDER/.pba-output, or an empty manifest if there is none. Throws BadOutput if it is not a
/// manifest pba wrote (another program's file of that name, or an edited one).
OutputManifest readManifest(const std::filesystem::path& folder);

/// Writes FOLDER/.pba-output completely or not at all (a temporary beside it, synced, renamed).
void writeManifest(const std::filesystem::path& folder, const OutputManifest& manifest);

/// Held while a folder's manifest is read, changed and written, and the files it lists renamed:
/// two pba processes writing into one folder would otherwise lose each other's entries. An
/// advisory lock on the folder itself (flock), so no lock file is left among the user's.
class ManifestLock {
public:
    explicit ManifestLock(const std::filesystem::path& folder);
    ManifestLock(const ManifestLock&) = delete;
    ManifestLock& operator=(const ManifestLock&) = delete;
    ~ManifestLock();

private:
    int m_fd = -1;
};

/// The entries of `manifest` whose files are still in `folder`, but for the names `skip` takes.
OutputManifest stillThere(const std::filesystem::path& folder, const OutputManifest& manifest,
                          const std::function<bool(const std::string&)>& skip);

/// Writes `during` (every name the folder may hold while `move` runs, with its old bytes and its
/// new), runs `move` (the renames onto the folder's names), then writes `after`: a crash half way,
/// or a failure to write `after`, leaves a list that is true, only longer.
void publishBetween(const std::filesystem::path& folder, const OutputManifest& during,
                    const std::function<void()>& move, const OutputManifest& after);

/// A file output the user named replaces only a file pba wrote: throws BadOutput, naming
/// `shown`, if `target` exists and its folder's manifest does not list it with the bytes it holds
/// (a file of the user's, or one of pba's edited since).
void requireReplaceable(const std::filesystem::path& target, const std::filesystem::path& shown);

/// Renames the finished file `made` onto `target` and lists it in the folder's manifest, under
/// the folder's lock, after checking again that `target` is absent or pba's: the file that was
/// there when the work began may have been replaced meanwhile. Between two manifests, the first
/// listing the old and the new bytes, so a crash half way leaves nothing pba disowns.
void publishListed(const std::filesystem::path& made, const std::filesystem::path& target,
                   const std::filesystem::path& shown);

} // namespace pba::io
