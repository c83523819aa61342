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
