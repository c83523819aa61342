#pragma once
// `.pba-output`: the list pba keeps in a folder output of the files it wrote there, each with
// its size and a hash of its bytes. It is how pba tells its own files (which a later run may
// replace, or remove once stale) from the user's, which it never touches: a file that is not
// listed, or no longer holds the bytes listed, is the user's.
#include <cstdint>
#include <filesystem>
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

} // namespace pba::io
