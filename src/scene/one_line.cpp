#include "one_line.hpp"

#include <deque>

#include <fmt/format.h>

namespace pba::scene_detail {

namespace {

bool isContinuation(unsigned char c) { return (c & 0xc0) == 0x80; }

/// The character of `text` at byte `i` (a whole UTF-8 sequence) as it is shown, in `piece`;
/// returns the byte after it.
std::size_t nextPiece(std::string_view text, std::size_t i, std::string& piece)
{
    const auto c = static_cast<unsigned char>(text[i]);
    const auto next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0u;
    if (c == '\n' || c == '\t' || c == '\r') {
        piece = c == '\n' ? "\\n" : c == '\t' ? "\\t" : "\\r";
        return i + 1;
    }
    if (c < 0x20 || c == 0x7f) {
        piece = fmt::format("\\x{:02x}", c);
        return i + 1;
    }
    if (c == 0xc2 && next >= 0x80 && next <= 0x9f) { // U+0080..U+009F: NEL, CSI, ...
        piece = fmt::format("\\u{:04x}", next);
        return i + 2;
    }
    std::size_t length = 1; // a UTF-8 lead byte and its continuation bytes stay together
    while (c >= 0xc0 && length < 4 && i + length < text.size() &&
           isContinuation(static_cast<unsigned char>(text[i + length])))
        ++length;
    piece.assign(text.substr(i, length));
    return i + length;
}

} // namespace

std::string oneLine(std::string_view text, std::size_t limit)
{
    std::string out, piece;
    for (std::size_t i = 0; i < text.size();) {
        i = nextPiece(text, i, piece);
        if (limit != kWhole && out.size() + piece.size() > limit)
            return fmt::format("{}... ({} bytes)", out, text.size());
        out += piece;
    }
    return out;
}

std::string oneLineTail(std::string_view text, std::size_t limit)
{
    if (limit == kWhole || text.size() <= limit / 4) // an escape shows a byte as at most 4
        return oneLine(text, kWhole);
    // A shown piece is never shorter than its bytes: the tail shown lies in the last `limit` bytes.
    std::size_t start = text.size() > limit ? text.size() - limit : 0;
    while (start > 0 && start < text.size() && isContinuation(static_cast<unsigned char>(text[start])))
        ++start;
    std::deque<std::string> pieces;
    std::size_t shown = 0;
    std::string piece;
    for (std::size_t i = start; i < text.size();) {
        i = nextPiece(text, i, piece);
        shown += piece.size();
        pieces.push_back(piece);
    }
    bool cut = start > 0;
    while (shown > limit) {
        shown -= pieces.front().size();
        pieces.pop_front();
        cut = true;
    }
    std::string tail;
    for (const std::string& p : pieces)
        tail += p;
    return cut ? fmt::format("({} bytes) ...{}", text.size(), tail) : tail;
}

} // namespace pba::scene_detail
