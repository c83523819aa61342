#pragma once
// What a user wrote (a name, a key, a path, a line of an OBJ file), as it may appear in an error
// message: every message is one line, so control characters are escaped, and a long string is
// cut so that a 1 MB name cannot flood a terminal or a log.
#include <cstddef>
#include <string>
#include <string_view>

namespace pba::scene_detail {

/// Names, keys, values, words of a file: long enough to recognise, short enough for one line.
inline constexpr std::size_t kShownLength = 80;
/// Paths are longer than names (a scene's folder), and cut later.
inline constexpr std::size_t kShownPathLength = 240;
/// No cut: only the escaping.
inline constexpr std::size_t kWhole = std::string_view::npos;

/// `text` with control characters escaped (\n, \t, \r, \x01, \u0085 for the C1 controls of
/// UTF-8) and, past `limit` bytes, its start followed by "... (N bytes)". A cut never splits a
/// UTF-8 character or an escape.
std::string oneLine(std::string_view text, std::size_t limit = kShownLength);

/// The same, but keeping the end of a long `text`: "(N bytes) ...tail". For text whose end
/// is where the trouble is (the token a parser stopped in).
std::string oneLineTail(std::string_view text, std::size_t limit = kShownLength);

} // namespace pba::scene_detail
