#include "contact/polyhedron_contact.hpp"

#include <algorithm>
#include <array>
#include <type_traits>
#include <utility>
#include <vector>

#include "contact/manifold_reduction.hpp"

namespace pba::contact {

namespace {

/// A vertex of the incident face as the reference face's side planes clip it, in the reference
/// frame. It carries its own id and what the polygon's edge leaving it lies on: an incident edge,
/// or (after a clip) a side plane of the reference face, so that the point a later plane cuts
/// from that edge can be named.
struct ClipVertex {
    dvec3 position;
    std::uint32_t refFeature, incFeature; ///< makeFeatureId's halves: kind << 14 | index
    int side;              ///< the outgoing edge lies on this side plane (loop position) ...
    std::uint32_t incEdge; ///< ... or, when side < 0, on this incident edge
};

/// Room for `n` values: on the stack up to kOnStack (a box's or a prism's faces fit), else in
/// `heap`, a block the thread keeps, so that no call allocates once the thread has warmed up.
/// T is left uninitialised (trivially constructible), so the stack room costs nothing to make.
template <class T, std::size_t kOnStack>
class Scratch {
public:
    Scratch(std::size_t n, std::vector<T>& heap)
    {
        if (n > kOnStack) {
            heap.resize(n);
            m_data = heap.data();
        }
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    T* data() { return m_data ? m_data : m_stack.data(); }

private:
    static_assert(std::is_trivially_default_constructible_v<T>);
    std::array<T, kOnStack> m_stack;
    T* m_data = nullptr;
};

constexpr std::size_t kOnStack = 56;

/// One shape's half of a feature id (makeFeatureId's low half: B's place).
constexpr std::uint32_t half(Feature kind, std::uint32_t index)
{
    return makeFeatureId(Feature::Vertex, 0, kind, index);
}

std::uint32_t pairId(std::uint32_t refFeature, std::uint32_t incFeature, Reference which)
{
    return which == Reference::A ? (refFeature << 16) | incFeature : (incFeature << 16) | refFeature;
}

/// Writes to `x` the point where the polygon's edge from `from` to `to` crosses side plane `k`
/// (distances `dFrom` and `dTo` inside it, of opposite signs), named after the features that
/// cross there, and what the polygon's edge leaving it lies on: leaving the inside, it runs
/// along the plane to where it comes back in; coming back in, it goes on along the edge it
/// crossed on.
void crossing(const ConvexPolyhedron& ref, const ConvexPolyhedron::Face& face, std::uint32_t incFace, int k,
              const ClipVertex& from, const ClipVertex& to, double dFrom, double dTo, ClipVertex& x)
{
    x.position = from.position + (dFrom / (dFrom - dTo)) * (to.position - from.position);
    x.side = dFrom > 0.0 ? k : from.side;
    x.incEdge = from.incEdge;
    if (from.side < 0) {
        x.refFeature = half(Feature::Edge, ref.faceEdges[face.first + static_cast<std::uint32_t>(k)]);
        x.incFeature = half(Feature::Edge, from.incEdge);
        return;
    }
    // An edge along an earlier side plane meets this one at the reference face's vertex between
    // them (two side planes that are not neighbours meet only outside the face).
    const auto m = static_cast<int>(face.count), earlier = from.side;
    const int corner = (earlier + 1) % m == k ? k : (k + 1) % m == earlier ? earlier : k;
    x.refFeature = half(Feature::Vertex, ref.faceVertices[face.first + static_cast<std::uint32_t>(corner)]);
    x.incFeature = half(Feature::Face, incFace);
}

/// Sutherland-Hodgman: writes the part of polygon `in` (n vertices) inside side plane k of the
/// reference face to `out` (room for n + 1), and returns its count.
std::size_t clipBySide(const ConvexPolyhedron& ref, const ConvexPolyhedron::Face& face, std::uint32_t incFace, int k,
                       const ClipVertex* in, std::size_t n, ClipVertex* out)
{
    const auto m = face.count;
    const dvec3& tail = ref.vertices[ref.faceVertices[face.first + static_cast<std::uint32_t>(k)]];
    const dvec3& head = ref.vertices[ref.faceVertices[face.first + (static_cast<std::uint32_t>(k) + 1) % m]];
    // The face is on the left of each of its edges seen from outside: inward is normal x edge.
    const dvec3 inward = glm::cross(face.normal, head - tail);
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const ClipVertex &from = in[i], &to = in[i + 1 == n ? 0 : i + 1];
        const double dFrom = glm::dot(inward, from.position - tail), dTo = glm::dot(inward, to.position - tail);
        if (dFrom >= 0.0) {
            out[count] = from;
            if (dFrom == 0.0 && dTo < 0.0)
                out[count].side = k; // on the plane already: from here the polygon runs along it
            ++count;
        }
        // A vertex exactly on the plane is kept as it is, so only a strict crossing makes a point.
        if ((dFrom > 0.0 && dTo < 0.0) || (dFrom < 0.0 && dTo > 0.0))
            crossing(ref, face, incFace, k, from, to, dFrom, dTo, out[count++]);
    }
    return count;
}

/// The face of `inc` whose normal is most anti-parallel to `normalInInc` (the first on a tie).
std::uint32_t incidentFace(const ConvexPolyhedron& inc, const dvec3& normalInInc)
{
    std::uint32_t best = 0;
    double bestDot = INFINITY;
    for (std::uint32_t j = 0; j < inc.faces.size(); ++j) {
        const double d = glm::dot(inc.faces[j].normal, normalInInc);
        if (d < bestDot) {
            bestDot = d;
            best = j;
        }
    }
    return best;
}

/// A manifold point from its two surface points, each in its own body's frame.
ManifoldPoint makePoint(const Transform& ta, const dvec3& anchorA, const Transform& tb, const dvec3& anchorB,
                        double separation, std::uint32_t id)
{
    return {anchorA, anchorB, 0.5 * (ta.apply(anchorA) + tb.apply(anchorB)), separation, id};
}

/// The closest points of segments p + s d and q + t e, s and t in [0, 1] (Ericson, Real-Time
/// Collision Detection, 5.1.9); the edges here are never parallel, but a zero-length or
/// parallel pair still gets finite points.
std::pair<dvec3, dvec3> closestOnSegments(const dvec3& p, const dvec3& d, const dvec3& q, const dvec3& e)
{
    const dvec3 r = p - q;
    const double a = glm::dot(d, d), b = glm::dot(d, e), c = glm::dot(e, e), f = glm::dot(e, r), g = glm::dot(d, r);
    const double denom = a * c - b * b;
    double s = denom > 0.0 ? std::clamp((b * f - c * g) / denom, 0.0, 1.0) : 0.0;
    double t = c > 0.0 ? (b * s + f) / c : 0.0;
    if (t < 0.0 || t > 1.0) {
        t = std::clamp(t, 0.0, 1.0);
        s = a > 0.0 ? std::clamp((b * t - g) / a, 0.0, 1.0) : 0.0;
    }
    return {p + s * d, q + t * e};
}

} // namespace

Manifold faceContact(const ConvexPolyhedron& ref, const Transform& refPose, const ConvexPolyhedron& inc,
                     const Transform& incPose, std::uint32_t face, Reference which, double margin)
{
    const ConvexPolyhedron::Face& f = ref.faces[face];
    const Transform incInRef = relativeTransform(refPose, incPose);
    const std::uint32_t incFace = incidentFace(inc, glm::transpose(incInRef.rotation) * f.normal);
    const ConvexPolyhedron::Face& g = inc.faces[incFace];

    // Clipping by each of the reference face's sides adds at most one vertex.
    const std::size_t room = std::size_t{f.count} + g.count;
    thread_local std::vector<ClipVertex> heapPolygon, heapClipped;
    Scratch<ClipVertex, kOnStack> polygonRoom(room, heapPolygon), clippedRoom(room, heapClipped);
    ClipVertex *polygon = polygonRoom.data(), *clipped = clippedRoom.data();
    std::size_t n = g.count;
    for (std::uint32_t j = 0; j < g.count; ++j) {
        const std::uint32_t v = inc.faceVertices[g.first + j];
        ClipVertex& c = polygon[j];
        c.position = incInRef.apply(inc.vertices[v]);
        c.refFeature = half(Feature::Face, face);
        c.incFeature = half(Feature::Vertex, v);
        c.side = -1;
        c.incEdge = inc.faceEdges[g.first + j];
    }
    for (int k = 0; k < static_cast<int>(f.count) && n > 0; ++k) {
        n = clipBySide(ref, f, incFace, k, polygon, n, clipped);
        std::swap(polygon, clipped);
    }

    thread_local std::vector<ClipPoint> heapPoints;
    Scratch<ClipPoint, kOnStack> pointsRoom(n, heapPoints);
    ClipPoint* points = pointsRoom.data();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double separation = glm::dot(f.normal, polygon[i].position) - f.offset;
        if (separation <= margin) {
            ClipPoint& p = points[kept++];
            p.position = polygon[i].position;
            p.separation = separation;
            p.id = pairId(polygon[i].refFeature, polygon[i].incFeature, which);
        }
    }
    const int count =
        reduceManifold(std::span{points, kept}, f.normal, [](const ClipPoint& p) { return p.position; });

    Manifold m;
    const dvec3 normal = refPose.rotation * f.normal;
    m.normal = which == Reference::A ? normal : -normal;
    m.count = count;
    for (int k = 0; k < count; ++k) {
        const ClipPoint& p = points[static_cast<std::size_t>(k)];
        const dvec3 onRef = p.position - p.separation * f.normal, onInc = incInRef.applyInverse(p.position);
        m.points[static_cast<std::size_t>(k)] =
            which == Reference::A ? makePoint(refPose, onRef, incPose, onInc, p.separation, p.id)
                                  : makePoint(incPose, onInc, refPose, onRef, p.separation, p.id);
    }
    return m;
}

Manifold edgeContact(const ConvexPolyhedron& a, const Transform& ta, const ConvexPolyhedron& b, const Transform& tb,
                     const EdgeQuery& query, double margin)
{
    Manifold m;
    if (!(query.separation <= margin) || query.separation == -INFINITY) // none found, or too far
        return m;
    const Transform bInA = relativeTransform(ta, tb);
    const ConvexPolyhedron::Edge &ea = a.edges[query.edgeA], &eb = b.edges[query.edgeB];
    const dvec3 pA = a.vertices[ea.tail], pB = bInA.apply(b.vertices[eb.tail]);
    const auto [onA, onB] = closestOnSegments(pA, a.vertices[ea.head] - pA, pB, bInA.apply(b.vertices[eb.head]) - pB);
    m.normal = ta.rotation * query.normal;
    m.count = 1;
    m.points[0] = makePoint(ta, onA, tb, bInA.applyInverse(onB), query.separation,
                            makeFeatureId(Feature::Edge, query.edgeA, Feature::Edge, query.edgeB));
    return m;
}

} // namespace pba::contact
