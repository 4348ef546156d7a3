// Grid -> triangle mesh: marching cubes without a case table.
//
// In each cell, the surface's boundary on every cube face is a set of segments between edge
// crossings; walking a face's corners counter-clockwise seen from outside the cell, each "entry"
// crossing (outside -> inside corner) is joined to the next "exit" crossing. This separates the
// inside corners of an ambiguous face, and the neighbouring cell, which walks the same face the other
// way, makes the same segments reversed: the surface is crack-free and consistently oriented. The
// segments of a cell chain into loops (every crossing has one outgoing and one incoming segment),
// and each loop is fanned into triangles.
#include "ellicast/codec/decoder.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace ellicast {
namespace {

// Corner c of a cell has offset (c & 1, (c >> 1) & 1, (c >> 2) & 1).
// Faces: corners counter-clockwise about the outward normal.
constexpr int kFaces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};

struct CubeEdge {
    int a, b;  // corners, a < b (they differ in one bit)
};

struct Tables {
    int edge_of[8][8];       // corner pair -> edge id 0..11, -1 if not an edge
    CubeEdge edges[12];
    int face_mask[12];       // faces (bits) an edge lies on
    Tables() {
        for (auto& row : edge_of)
            for (int& e : row) e = -1;
        int n = 0;
        for (int a = 0; a < 8; ++a)
            for (int bit = 0; bit < 3; ++bit) {
                int b = a | (1 << bit);
                if (b == a) continue;
                edges[n] = {a, b};
                edge_of[a][b] = edge_of[b][a] = n;
                ++n;
            }
        for (int e = 0; e < 12; ++e) {
            face_mask[e] = 0;
            for (int f = 0; f < 6; ++f) {
                bool ha = false, hb = false;
                for (int c : kFaces[f]) ha |= c == edges[e].a, hb |= c == edges[e].b;
                if (ha && hb) face_mask[e] |= 1 << f;
            }
        }
    }
};
const Tables& tables() {
    static const Tables t;
    return t;
}

double min_angle_cos(const OpenMesh::Vec3d& a, const OpenMesh::Vec3d& b, const OpenMesh::Vec3d& c) {
    // Largest cosine among the three angles (= smallest angle).
    auto cosang = [](const OpenMesh::Vec3d& p, const OpenMesh::Vec3d& q, const OpenMesh::Vec3d& r) {
        OpenMesh::Vec3d u = q - p, v = r - p;
        double l = u.norm() * v.norm();
        return l > 0 ? OpenMesh::dot(u, v) / l : 1.0;
    };
    return std::max({cosang(a, b, c), cosang(b, c, a), cosang(c, a, b)});
}

}  // namespace

DecoderTriMesh marching_cubes(const EllipsoidGrid& grid) {
    DecoderTriMesh mesh;
    mesh.request_vertex_status();
    mesh.request_edge_status();
    mesh.request_face_status();
    if (grid.empty()) return mesh;
    const Tables& T = tables();
    const int nx = grid.nodes[0], ny = grid.nodes[1], nz = grid.nodes[2];
    const double h = grid.cell;
    std::unordered_map<uint64_t, int> vertex_of_edge;  // (node index * 3 + axis) -> vertex
    vertex_of_edge.reserve(size_t(nx) * ny * 4);

    auto node_pos = [&](int i, int j, int k) {
        return OpenMesh::Vec3d(grid.origin[0] + i * h, grid.origin[1] + j * h, grid.origin[2] + k * h);
    };
    std::vector<OpenMesh::VertexHandle> face_vertices;
    std::vector<int> loop;
    std::vector<OpenMesh::Vec3d> loop_pos;
    std::vector<int> loop_faces;

    for (int k = 0; k + 1 < nz; ++k)
        for (int j = 0; j + 1 < ny; ++j)
            for (int i = 0; i + 1 < nx; ++i) {
                float v[8];
                int mask = 0;
                for (int c = 0; c < 8; ++c) {
                    v[c] = grid.value[grid.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))];
                    if (v[c] > 0) mask |= 1 << c;
                }
                if (mask == 0 || mask == 255) continue;
                bool in[8];
                for (int c = 0; c < 8; ++c) in[c] = (mask >> c) & 1;
                // next[e] = edge that follows crossing e in its loop
                int next[12];
                for (int& e : next) e = -1;
                for (int f = 0; f < 6; ++f) {
                    const int* q = kFaces[f];
                    int entries[2], exits[2], ne = 0, nxit = 0, pos_en[2], pos_ex[2];
                    for (int s = 0; s < 4; ++s) {
                        int a = q[s], b = q[(s + 1) & 3];
                        if (in[a] == in[b]) continue;
                        int e = T.edge_of[a][b];
                        if (!in[a]) entries[ne] = e, pos_en[ne++] = s;
                        else exits[nxit] = e, pos_ex[nxit++] = s;
                    }
                    // Join each entry with the next exit counter-clockwise.
                    for (int x = 0; x < ne; ++x) {
                        int best = -1, best_d = 5;
                        for (int y = 0; y < nxit; ++y) {
                            int d = (pos_ex[y] - pos_en[x] + 4) & 3;
                            if (d > 0 && d < best_d) best_d = d, best = y;
                        }
                        next[entries[x]] = exits[best];
                    }
                }
                bool used[12] = {};
                for (int start = 0; start < 12; ++start) {
                    if (next[start] < 0 || used[start]) continue;
                    loop.clear();
                    for (int e = start; !used[e]; e = next[e]) {
                        used[e] = true;
                        loop.push_back(e);
                    }
                    if (loop.size() < 3) continue;  // cannot happen with consistent segments
                    loop_pos.clear();
                    face_vertices.clear();
                    for (int e : loop) {
                        const CubeEdge& ce = T.edges[e];
                        int ai = i + (ce.a & 1), aj = j + ((ce.a >> 1) & 1), ak = k + ((ce.a >> 2) & 1);
                        int axis = (ce.a ^ ce.b) == 1 ? 0 : ((ce.a ^ ce.b) == 2 ? 1 : 2);
                        uint64_t key = uint64_t(grid.index(ai, aj, ak)) * 3 + axis;
                        auto it = vertex_of_edge.find(key);
                        OpenMesh::VertexHandle vh;
                        if (it == vertex_of_edge.end()) {
                            double va = v[ce.a], vb = v[ce.b];
                            double t = va / (va - vb);
                            t = std::clamp(t, 0.05, 0.95);
                            OpenMesh::Vec3d pa = node_pos(ai, aj, ak);
                            pa[axis] += t * h;
                            vh = mesh.add_vertex(pa);
                            vertex_of_edge.emplace(key, vh.idx());
                        } else {
                            vh = OpenMesh::VertexHandle(it->second);
                        }
                        face_vertices.push_back(vh);
                        loop_pos.push_back(mesh.point(vh));
                    }
                    const int m = int(loop.size());
                    if (m == 3) {
                        mesh.add_face(face_vertices[0], face_vertices[1], face_vertices[2]);
                        continue;
                    }
                    // Fan from the apex whose diagonals never join two crossings of one cube face (such a
                    // diagonal could also be made by the neighbouring cell) and whose worst angle is best.
                    int apex = -1;
                    double apex_cos = 2;
                    for (int a = 0; a < m; ++a) {
                        bool ok = true;
                        for (int d = 2; d <= m - 2 && ok; ++d)
                            ok = (T.face_mask[loop[a]] & T.face_mask[loop[(a + d) % m]]) == 0;
                        if (!ok) continue;
                        double worst = -1;
                        for (int d = 1; d + 1 < m; ++d)
                            worst = std::max(worst, min_angle_cos(loop_pos[a], loop_pos[(a + d) % m],
                                                                  loop_pos[(a + d + 1) % m]));
                        if (worst < apex_cos) apex_cos = worst, apex = a;
                    }
                    if (apex >= 0) {
                        for (int d = 1; d + 1 < m; ++d)
                            mesh.add_face(face_vertices[apex], face_vertices[(apex + d) % m],
                                          face_vertices[(apex + d + 1) % m]);
                    } else {
                        // Every apex would risk a shared diagonal: fan around the loop's centroid.
                        OpenMesh::Vec3d c(0, 0, 0);
                        for (const auto& p : loop_pos) c += p;
                        auto centre = mesh.add_vertex(c / m);
                        for (int d = 0; d < m; ++d)
                            mesh.add_face(centre, face_vertices[d], face_vertices[(d + 1) % m]);
                    }
                }
            }
    return mesh;
}

}  // namespace ellicast
