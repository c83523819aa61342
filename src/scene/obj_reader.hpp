#pragma once
// The triangles of an OBJ file (Wavefront): its `v` and `f` lines, polygons as fans, texture
// and normal indices ignored, negative indices counting back from the last vertex. Every other
// statement (vt, vn, o, g, s, usemtl, ...) is skipped; what a v or f line holds is read whole,
// and anything it cannot read is refused naming the line.
#include <cstdint>
#include <string_view>
#include <vector>

#include "pba/math.hpp"

namespace pba::scene_detail {

struct ObjMesh {
    std::vector<dvec3> vertices;
    std::vector<std::uint32_t> triangles;
};

/// A line of an OBJ file may be this long (a polygon of a thousand corners fits).
inline constexpr std::size_t kMaxObjLineBytes = 64 * 1024;

/// The mesh of an OBJ file's text. std::runtime_error "line N: reason" (quoting at most a short,
/// escaped word of the line: the file may be anyone's), or "has no faces".
ObjMesh parseObj(std::string_view text);

} // namespace pba::scene_detail
