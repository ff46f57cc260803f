#include "sylva/core/sources/objects/MeshSimplifier.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

namespace sylva {

namespace {

struct Traits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    VertexAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
    FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
    EdgeAttributes(OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

// The geometry welded by position and texture coordinates into an OpenMesh mesh; each
// vertex keeps the colour of the first original vertex there and its texture coordinates
// (properties). Where a texture seam runs (one position, several texture coordinates) the
// two sides are separate vertices: both are locked, so the decimater never moves or
// removes them and the seam stays closed in every level.
struct Welded {
    Mesh mesh;
    OpenMesh::VPropHandleT<std::uint32_t> color;
    OpenMesh::VPropHandleT<glm::vec2> uv;
    std::vector<glm::dvec3> points;  // the welded positions, for the error
};

void weld(const MeshGeometry& geometry, Welded& out) {
    out.mesh.add_property(out.color);
    out.mesh.add_property(out.uv);
    using Key = std::tuple<float, float, float, float, float>;
    std::map<Key, Mesh::VertexHandle> byCorner;
    std::map<std::tuple<float, float, float>, int> cornersAt;  // distinct uvs per position
    std::vector<Mesh::VertexHandle> handles(geometry.vertices.size());
    for (std::size_t i = 0; i < geometry.vertices.size(); ++i) {
        const MeshVertex& v = geometry.vertices[i];
        const Key key{v.position.x, v.position.y, v.position.z, v.uv.x, v.uv.y};
        auto found = byCorner.find(key);
        if (found == byCorner.end()) {
            const Mesh::VertexHandle h =
                out.mesh.add_vertex(Mesh::Point(v.position.x, v.position.y, v.position.z));
            out.mesh.property(out.color, h) = v.color;
            out.mesh.property(out.uv, h) = v.uv;
            out.points.emplace_back(v.position);
            found = byCorner.emplace(key, h).first;
            ++cornersAt[{v.position.x, v.position.y, v.position.z}];
        }
        handles[i] = found->second;
    }
    for (const auto& [key, handle] : byCorner)
        if (cornersAt[{std::get<0>(key), std::get<1>(key), std::get<2>(key)}] > 1)
            out.mesh.status(handle).set_locked(true);  // a texture seam
    for (std::size_t t = 0; t + 2 < geometry.indices.size(); t += 3) {
        const Mesh::VertexHandle a = handles[geometry.indices[t]],
                                 b = handles[geometry.indices[t + 1]],
                                 c = handles[geometry.indices[t + 2]];
        if (a != b && b != c && a != c)
            out.mesh.add_face(a, b, c);  // an invalid handle (non-manifold) leaves the face out
    }
}

double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::dvec3& c) {
    // Ericson, Real-Time Collision Detection §5.1.5: the closest point by Voronoi regions.
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return glm::length(p - a);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return glm::length(p - b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return glm::length(p - (a + ab * (d1 / (d1 - d3))));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return glm::length(p - c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return glm::length(p - (a + ac * (d2 / (d2 - d6))));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const double denominator = 1.0 / (va + vb + vc);
    return glm::length(p - (a + ab * (vb * denominator) + ac * (vc * denominator)));
}

// The largest distance of `points` (an even sample of at most 4,096) from the triangles.
double largestDistance(const std::vector<glm::dvec3>& points, const MeshGeometry& level) {
    const std::size_t step = std::max<std::size_t>(1, points.size() / 4096);
    double largest = 0.0;
    for (std::size_t i = 0; i < points.size(); i += step) {
        double nearest = INFINITY;
        for (std::size_t t = 0; t + 2 < level.indices.size(); t += 3)
            nearest = std::min(nearest,
                               pointTriangleDistance(
                                   points[i], glm::dvec3(level.vertices[level.indices[t]].position),
                                   glm::dvec3(level.vertices[level.indices[t + 1]].position),
                                   glm::dvec3(level.vertices[level.indices[t + 2]].position)));
        largest = std::max(largest, nearest);
    }
    return largest;
}

// The mesh as drawable geometry: surviving vertices, recomputed normals, their colours.
MeshGeometry toGeometry(Welded& welded) {
    Mesh& mesh = welded.mesh;
    mesh.garbage_collection();
    mesh.update_face_normals();
    mesh.update_vertex_normals();
    MeshGeometry out;
    out.vertices.reserve(mesh.n_vertices());
    for (const Mesh::VertexHandle v : mesh.vertices()) {
        const Mesh::Point& p = mesh.point(v);
        Mesh::Normal n = mesh.normal(v);
        const double length = n.norm();
        MeshVertex vertex;
        vertex.position = glm::vec3(float(p[0]), float(p[1]), float(p[2]));
        vertex.normal = length > 0.0 ? glm::vec3(float(n[0] / length), float(n[1] / length),
                                                 float(n[2] / length))
                                     : glm::vec3(0.0f, 0.0f, 1.0f);
        vertex.color = mesh.property(welded.color, v);
        vertex.uv = mesh.property(welded.uv, v);
        out.vertices.push_back(vertex);
    }
    for (const Mesh::FaceHandle f : mesh.faces())
        for (const Mesh::VertexHandle v : mesh.fv_range(f))
            out.indices.push_back(std::uint32_t(v.idx()));
    return out;
}

}  // namespace

// One decimation step: `geometry` welded and reduced to about `target` faces (a fresh
// mesh and decimater per step: OpenMesh counts deleted faces until garbage collection,
// so a second decimate_to_faces on the same mesh would overshoot).
MeshGeometry decimate(const MeshGeometry& geometry, std::size_t target) {
    Welded welded;
    weld(geometry, welded);
    // The normal-flipping module compares each collapse against the stored face normals
    // and computes them itself only when the mesh has none; ours has them (Traits), so
    // they must be filled here: uninitialized, they made the levels vary from run to run.
    welded.mesh.update_face_normals();
    using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
    Decimater decimater(welded.mesh);
    OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
    OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flipping;
    decimater.add(quadric);
    decimater.add(flipping);
    if (!decimater.initialize())
        return {};
    decimater.decimate_to_faces(0, target);
    return toGeometry(welded);
}

std::vector<SimplifiedGeometry> simplifyLevels(const MeshGeometry& geometry) {
    std::vector<SimplifiedGeometry> levels;
    if (geometry.indices.size() / 3 < kSimplifyMinimumTriangles)
        return levels;
    Welded original;
    weld(geometry, original);
    const MeshGeometry* previous = &geometry;  // read before the next push_back
    std::size_t faces = original.mesh.n_faces();
    // Each level a quarter of the previous one's faces, down to a few dozen.
    while (faces / 4 >= 32) {
        SimplifiedGeometry level;
        level.geometry = decimate(*previous, faces / 4);
        const std::size_t reached = level.geometry.indices.size() / 3;
        if (reached == 0 || reached * 10 > faces * 9)
            break;  // the decimater is stuck (boundaries, flips): no further level
        level.errorMetres = largestDistance(original.points, level.geometry);
        if (!levels.empty())
            level.errorMetres = std::max(level.errorMetres, levels.back().errorMetres);
        levels.push_back(std::move(level));
        previous = &levels.back().geometry;
        faces = reached;
    }
    return levels;
}

}  // namespace sylva
