#include "contact/separating_axis.hpp"

#include <vector>

namespace pba::contact {

namespace {

/// Edges closer to parallel than this (the sine of their angle) have no axis of their own: the
/// faces beside them give it, and their cross product is too short to normalise well.
constexpr double kParallelSine = 1e-6;

/// Whether arcs AB (A's edge between its faces' normals a and b) and CD (B's edge between the
/// negated normals c and d) cross on the unit sphere. bxa = b x a, dxc = d x c: the planes of the
/// arcs. C and D lie on opposite sides of AB's plane, A and B on opposite sides of CD's, and the
/// last test keeps the arcs from being antipodal (the two great circles cross twice).
bool arcsCross(double cba, double dba, double adc, double bdc)
{
    return cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0;
}

/// The separation along the common normal of A's edge (from pA along dA) and B's (from pB along
/// dB, in A's frame), the normal turned to point away from A's centre (the origin of A's frame,
/// inside A); -infinity for a parallel pair.
EdgeQuery edgeAxis(const dvec3& pA, const dvec3& dA, const dvec3& pB, const dvec3& dB)
{
    dvec3 n = glm::cross(dA, dB);
    const double length2 = glm::dot(n, n);
    EdgeQuery q;
    if (!(length2 > kParallelSine * kParallelSine * glm::dot(dA, dA) * glm::dot(dB, dB)))
        return q;
    n /= std::sqrt(length2);
    if (glm::dot(n, pA) < 0.0)
        n = -n;
    q.separation = glm::dot(n, pB - pA);
    q.normal = n;
    return q;
}

/// Whether an edge pair may separate the shapes further than `best`, from its unnormalised
/// normal n (|n|^2 = length2) and dot(n, pB - pA) = d turned away from A: d / |n| > best,
/// decided without the square root for the common case of two negative separations. Generous
/// by a part in 1e9, so that rounding never drops a pair the exact comparison would keep.
bool mayBeat(double d, double length2, double best)
{
    if (d >= 0.0)
        return true;
    if (best >= 0.0)
        return false;
    return d * d < best * best * length2 * (1.0 + 1e-9);
}

/// Unit axis i crossed with v, without the products by zero.
dvec3 axisCross(int i, const dvec3& v)
{
    return i == 0 ? dvec3(0.0, -v.z, v.y) : i == 1 ? dvec3(v.z, 0.0, -v.x) : dvec3(-v.y, v.x, 0.0);
}

/// Two boxes' edge pairs in closed form: for A's axis i and B's axis j, the common normal n,
/// turned towards B's centre, separates them by |n.t| less both boxes' extents along n
/// (sum |n_k| h_k in each box's frame). That is the separation of the pair of edges the two
/// boxes reach furthest along n and -n: the only pair in those directions whose arcs cross on
/// the Gauss map (a box's Minkowski sum with a box has a face for every such pair), which the
/// general search would find the same. The edges are named only for the pair kept
/// (boxEdgeNames).
EdgeQuery boxAxisPair(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, int i, int j)
{
    const dmat3& r = bInA.rotation;
    const dvec3 n = axisCross(i, r[j]);
    // In B's frame, A's axis i (row i of r) crossed with B's axis j.
    const dvec3 nInB = -axisCross(j, dvec3(r[0][i], r[1][i], r[2][i]));
    const double length2 = glm::dot(n, n);
    EdgeQuery q;
    if (!(length2 > kParallelSine * kParallelSine))
        return q;
    const double inverse = 1.0 / std::sqrt(length2);
    const double centre = glm::dot(n, bInA.position) * inverse;
    q.separation = std::abs(centre) -
                   (glm::dot(glm::abs(n), a.boxHalfExtents) + glm::dot(glm::abs(nInB), b.boxHalfExtents)) * inverse;
    q.normal = (centre < 0.0 ? -inverse : inverse) * n;
    return q;
}

/// The edges of an edge query between boxes, from the axes it was made of: A's edge along axis
/// i on the side its normal points to, B's along its axis j on the opposite side.
void boxEdgeNames(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, int i, int j, EdgeQuery& q)
{
    const auto corner = [](const dvec3& towards, int along) {
        std::uint32_t v = 0;
        for (int k = 0; k < 3; ++k)
            if (k != along && towards[k] > 0.0)
                v |= 1u << k;
        return v;
    };
    const std::uint32_t tailA = corner(q.normal, i), tailB = corner(-(glm::transpose(bInA.rotation) * q.normal), j);
    q.edgeA = a.edgeBetween(tailA, tailA | 1u << i);
    q.edgeB = b.edgeBetween(tailB, tailB | 1u << j);
}

/// The axis a box's edge runs along: the one bit its two corners differ in.
int boxEdgeDirection(const ConvexPolyhedron& box, std::uint32_t edge)
{
    const std::uint32_t differ = box.edges[edge].tail ^ box.edges[edge].head;
    return differ == 1u ? 0 : differ == 2u ? 1 : 2;
}

EdgeQuery queryBoxEdges(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, double stopAbove)
{
    EdgeQuery best;
    int bestI = 0, bestJ = 0;
    for (int k = 0; k < 9; ++k) {
        const EdgeQuery q = boxAxisPair(a, b, bInA, k / 3, k % 3);
        if (q.separation > best.separation) {
            best = q;
            bestI = k / 3, bestJ = k % 3;
            if (q.separation > stopAbove)
                break;
        }
    }
    if (best.separation > -INFINITY)
        boxEdgeNames(a, b, bInA, bestI, bestJ, best);
    return best;
}

} // namespace

double faceSeparation(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, std::uint32_t face)
{
    const ConvexPolyhedron::Face& f = a.faces[face];
    // B's vertex deepest below the plane is its support along -normal, found in B's frame.
    const dvec3 normalInB = glm::transpose(bInA.rotation) * f.normal;
    const dvec3& deepest = b.vertices[b.support(-normalInB)];
    return glm::dot(normalInB, deepest) + glm::dot(f.normal, bInA.position) - f.offset;
}

FaceQuery queryFaces(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, double stopAbove)
{
    FaceQuery best;
    for (std::uint32_t i = 0; i < a.faces.size(); ++i) {
        const double s = faceSeparation(a, b, bInA, i);
        if (s > best.separation) {
            best = {s, i};
            if (s > stopAbove)
                break;
        }
    }
    return best;
}

EdgeQuery edgePair(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, std::uint32_t edgeA,
                   std::uint32_t edgeB)
{
    if (a.isBox() && b.isBox()) {
        const int i = boxEdgeDirection(a, edgeA), j = boxEdgeDirection(b, edgeB);
        EdgeQuery q = boxAxisPair(a, b, bInA, i, j);
        if (q.separation > -INFINITY)
            boxEdgeNames(a, b, bInA, i, j, q);
        return q;
    }
    // The same products as queryEdges, in the same order, so that both agree to the last bit.
    const ConvexPolyhedron::Edge &ea = a.edges[edgeA], &eb = b.edges[edgeB];
    const dvec3 bxa = glm::cross(a.faces[ea.rightFace].normal, a.faces[ea.leftFace].normal);
    const dvec3 left = bInA.rotation * b.faces[eb.leftFace].normal, right = bInA.rotation * b.faces[eb.rightFace].normal;
    const dvec3 dxc = glm::cross(right, left);
    const double cba = -glm::dot(left, bxa), dba = -glm::dot(right, bxa);
    const double adc = glm::dot(a.faces[ea.leftFace].normal, dxc), bdc = glm::dot(a.faces[ea.rightFace].normal, dxc);
    if (!arcsCross(cba, dba, adc, bdc))
        return {};
    const dvec3 pA = a.vertices[ea.tail], pB = bInA.apply(b.vertices[eb.tail]);
    EdgeQuery q = edgeAxis(pA, a.vertices[ea.head] - pA, pB, bInA.apply(b.vertices[eb.head]) - pB);
    q.edgeA = edgeA;
    q.edgeB = edgeB;
    return q;
}

EdgeQuery queryEdges(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Transform& bInA, double stopAbove)
{
    if (a.isBox() && b.isBox())
        return queryBoxEdges(a, b, bInA, stopAbove);
    // B's vertices, face normals and edges' arc planes in A's frame, and each A edge's arc plane
    // against every B normal, once: a pair then costs two look-ups in the common case that it
    // is pruned, and a square root only when it may be the best.
    thread_local std::vector<dvec3> verticesB, normalsB, arcPlanesB;
    thread_local std::vector<double> sidesB;
    verticesB.resize(b.vertices.size());
    normalsB.resize(b.faces.size());
    sidesB.resize(b.faces.size());
    arcPlanesB.resize(b.edges.size());
    for (std::size_t j = 0; j < b.vertices.size(); ++j)
        verticesB[j] = bInA.apply(b.vertices[j]);
    for (std::size_t j = 0; j < b.faces.size(); ++j)
        normalsB[j] = bInA.rotation * b.faces[j].normal;
    for (std::size_t l = 0; l < b.edges.size(); ++l)
        arcPlanesB[l] = glm::cross(normalsB[b.edges[l].rightFace], normalsB[b.edges[l].leftFace]);
    EdgeQuery best;
    for (std::uint32_t i = 0; i < a.edges.size(); ++i) {
        const ConvexPolyhedron::Edge& ea = a.edges[i];
        const dvec3 &na = a.faces[ea.leftFace].normal, &nb = a.faces[ea.rightFace].normal;
        const dvec3 bxa = glm::cross(nb, na);
        const dvec3 pA = a.vertices[ea.tail], dA = a.vertices[ea.head] - pA;
        for (std::size_t j = 0; j < b.faces.size(); ++j)
            sidesB[j] = glm::dot(normalsB[j], bxa);
        for (std::uint32_t l = 0; l < b.edges.size(); ++l) {
            const ConvexPolyhedron::Edge& eb = b.edges[l];
            const double cba = -sidesB[eb.leftFace], dba = -sidesB[eb.rightFace];
            if (!(cba * dba < 0.0))
                continue;
            if (!arcsCross(cba, dba, glm::dot(na, arcPlanesB[l]), glm::dot(nb, arcPlanesB[l])))
                continue;
            const dvec3 pB = verticesB[eb.tail], dB = verticesB[eb.head] - pB;
            const dvec3 n = glm::cross(dA, dB);
            const double d = glm::dot(n, pB - pA);
            if (!mayBeat(glm::dot(n, pA) < 0.0 ? -d : d, glm::dot(n, n), best.separation))
                continue;
            EdgeQuery q = edgeAxis(pA, dA, pB, dB);
            if (q.separation > best.separation) {
                q.edgeA = i;
                q.edgeB = l;
                best = q;
                if (q.separation > stopAbove)
                    return best;
            }
        }
    }
    return best;
}

} // namespace pba::contact
