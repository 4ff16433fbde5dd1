// cbp_audit: how closely the mesher's final point set satisfies the closed ball property for the
// surface it meshes, Sigma' (octree/face_slabs.h, with the mesher's slabs for --eps-voxels; the
// slab width can be overridden with --slab H, 0 = the trilinear Sigma itself). A diagnostic for
// mesher work, not a certificate (`isodel verify` is that): it meshes the volume, rebuilds
// Del(E u G u N) of the final points with exact circumcentres, walks every finite Voronoi edge
// and samples every Voronoi facet on a RES x RES lattice.
//
//   cbp_audit INPUT --iso V [--inside above|below] [--eps-voxels E] [--slab H] [--res 40] [--cell-res 0] [--points OUT.xyz] [--show 10]
//
// Prints (index coordinates): Voronoi edges crossing Sigma' more than once (CBP_VE), facets whose
// boundary crosses Sigma' more than twice (CBP_VF) or whose interior holds a sampled island of
// the other sign (a loop), and facets of M whose Voronoi edge has an odd/even count that
// disagrees with M (parity). Only finite Voronoi edges and bounded facets within the voxel bound
// (extent <= 8 voxels) are examined. Any violation of Sigma' is a mesher defect (with --slab 0,
// the ones next to knife-edge creases are expected). The tool does not classify them: read the
// coordinates. Exit 0 when nothing is found.
// With --cell-res R > 0 it also counts the Euler characteristic of Sigma' in the Voronoi cell of
// every vertex of M at 1/R voxel and prints the cells with a handle (chi < 0). With --points it
// writes the final point set (x y z per line).
#include <isodel/mesh.h>
#include <isodel/volume.h>

#include "closed_ball/cell_surface_euler.h"
#include "octree/sample_field.h"
#include "octree/segment_walk.h"
#include "surface/final_points.h"

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
using P3 = K::Point_3;
using V3 = openvdb::Vec3d;

/// Circumcentres of nearly flat cells are ill-conditioned in doubles: construct them exactly.
P3 exact_circumcenter(const DT::Cell_handle& c)
{
    CGAL::Cartesian_converter<K, EK> to;
    CGAL::Cartesian_converter<EK, K> back;
    return back(CGAL::circumcenter(to(c->vertex(0)->point()), to(c->vertex(1)->point()), to(c->vertex(2)->point()),
                                   to(c->vertex(3)->point())));
}

int find_root(std::vector<int>& parent, int x)
{
    while (parent[x] != x)
        x = parent[x] = parent[parent[x]];
    return x;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: cbp_audit INPUT --iso V [--inside above|below] [--eps-voxels E] [--slab H] [--res 40] [--show 10]\n");
        return 2;
    }
    const std::string input = argv[1];
    double iso = 0, eps = 0.5, slab = -1;
    bool have_iso = false;
    int res = 40, show = 10, cell_res = 0;
    std::string points_out;
    std::string inside;
    try {
        for (int i = 2; i < argc; i += 2) {
            const std::string a = argv[i];
            if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
            const std::string v = argv[i + 1];
            try {
                if (a == "--iso")
                    iso = std::stod(v), have_iso = true;
                else if (a == "--eps-voxels")
                    eps = std::stod(v);
                else if (a == "--slab")
                    slab = std::stod(v);
                else if (a == "--inside")
                    inside = v;
                else if (a == "--res")
                    res = std::stoi(v);
                else if (a == "--points")
                    points_out = v;
                else if (a == "--cell-res")
                    cell_res = std::stoi(v);
                else if (a == "--show")
                    show = std::stoi(v);
                else
                    throw std::invalid_argument("unknown option " + a);
            }
            catch (const std::invalid_argument& e) {
                if (std::string(e.what()).rfind("sto", 0) != 0) throw;
                throw std::invalid_argument(a + ": not a number: " + v);
            }
        }
        if (!have_iso) throw std::invalid_argument("--iso is required");
        if (!inside.empty() && inside != "above" && inside != "below")
            throw std::invalid_argument("--inside must be above or below");
        if (!(eps > 0) || res < 2 || show < 0)
            throw std::invalid_argument("need --eps-voxels > 0, --res >= 2, --show >= 0");
    }
    catch (const std::exception& e) { // std::stoi/stod say only "stoi": name the problem
        std::fprintf(stderr, "cbp_audit: bad arguments: %s\n", e.what());
        return 2;
    }
    openvdb::initialize();
    try {
        const isodel::Volume vol = isodel::read_volume(input);
        isodel::MeshOptions mo;
        mo.isovalue = iso;
        const isodel::Inside side =
            inside.empty() ? vol.default_inside : (inside == "below" ? isodel::Inside::Below : isodel::Inside::Above);
        mo.inside = side;
        mo.eps_voxels = eps;
        std::vector<std::array<double, 3>> points;
        const auto r = isodel::mesher::mesh_keeping_points(*vol.grid, mo, points);
        std::printf("%s: M has %zu vertices, %zu triangles; %zu points in the final triangulation\n", input.c_str(),
                    r.surface.vertices.size(), r.surface.triangles.size(), points.size());
        if (!points_out.empty()) { // the final point set, for outside analysis (x y z per line)
            FILE* f = std::fopen(points_out.c_str(), "w");
            if (!f) throw std::runtime_error(points_out + ": cannot write");
            for (const auto& q : points)
                std::fprintf(f, "%.17g %.17g %.17g\n", q[0], q[1], q[2]);
            std::fclose(f);
        }
        isodel::octree::SampleField field(vol.grid, iso, side);
        field.set_face_slabs(slab >= 0 ? isodel::octree::FaceSlabs{slab}
                                       : field.face_slabs_for_eps_world(eps * field.min_voxel_edge()));
        const isodel::octree::SampleField::Reader reader(field);
        auto idx = [&](const P3& p) { return field.world_to_index(V3(p.x(), p.y(), p.z())); };

        std::vector<std::pair<P3, int>> pts;
        std::map<std::array<double, 3>, int> id_of;
        for (std::size_t i = 0; i < points.size(); ++i) {
            pts.push_back({P3(points[i][0], points[i][1], points[i][2]), int(i)});
            id_of[{points[i][0], points[i][1], points[i][2]}] = int(i);
        }
        const DT dt(pts.begin(), pts.end());
        std::set<std::array<int, 3>> in_mesh;
        for (const auto& t : r.surface.triangles) {
            std::array<int, 3> k{};
            for (int j = 0; j < 3; ++j) {
                const auto& v = r.surface.vertices[t[j]];
                const auto it = id_of.find({v[0], v[1], v[2]});
                k[j] = it == id_of.end() ? -1 : it->second;
            }
            std::sort(k.begin(), k.end());
            in_mesh.insert(k);
        }

        // Voronoi edges: crossings of Sigma' (exact roots per box), and parity against M.
        int ve = 0, parity = 0;
        for (auto f = dt.finite_facets_begin(); f != dt.finite_facets_end(); ++f) {
            const auto c = f->first;
            const auto n = c->neighbor(f->second);
            if (dt.is_infinite(c) || dt.is_infinite(n)) continue;
            const V3 a = idx(exact_circumcenter(c)), b = idx(exact_circumcenter(n));
            const auto x = isodel::octree::segment_crossings(reader, a, b, 1 << 20);
            std::array<int, 3> k{};
            for (int j = 0, m = 0; j < 4; ++j)
                if (j != f->second) k[m++] = c->vertex(j)->info();
            std::sort(k.begin(), k.end());
            if (x.t.size() > 1 && ++ve <= show) {
                const V3 p = a + x.t[0] * (b - a), q = a + x.t[1] * (b - a);
                std::printf("  CBP_VE: %zu crossings, first two at (%.5f %.5f %.5f) and (%.5f %.5f %.5f)\n", x.t.size(),
                            p[0], p[1], p[2], q[0], q[1], q[2]);
            }
            if (bool(x.t.size() % 2) != bool(in_mesh.count(k)) && ++parity <= show)
                std::printf("  parity: %zu crossings, in M %d, Voronoi edge (%.5f %.5f %.5f)-(%.5f %.5f %.5f)\n",
                            x.t.size(), int(in_mesh.count(k)), a[0], a[1], a[2], b[0], b[1], b[2]);
        }

        // Voronoi facets: boundary crossings, and islands of either sign in a sampled interior.
        int vf = 0, loops = 0, facets = 0;
        for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
            std::vector<V3> P;
            bool unbounded = false;
            auto cc = dt.incident_cells(*e), done = cc;
            do {
                if (dt.is_infinite(cc)) {
                    unbounded = true;
                    break;
                }
                P.push_back(idx(exact_circumcenter(cc)));
            } while (++cc != done);
            if (unbounded || P.size() < 3) continue;
            V3 centre(0.0);
            for (const auto& q : P)
                centre += q;
            centre *= 1.0 / double(P.size());
            double extent = 0;
            for (const auto& q : P)
                extent = std::max(extent, (q - centre).length());
            if (extent > 8 || extent == 0) continue; // beyond the voxel bound: not the mesher's business
            V3 N(0.0);
            for (std::size_t i = 0; i < P.size(); ++i)
                N += (P[i] - centre).cross(P[(i + 1) % P.size()] - centre);
            if (N.length() == 0) continue;
            N.normalize();
            int boundary = 0;
            for (std::size_t i = 0; i < P.size(); ++i)
                boundary +=
                    int(isodel::octree::segment_crossings(reader, P[i], P[(i + 1) % P.size()], 1 << 20).t.size());
            ++facets;
            if (boundary > 2 && ++vf <= show)
                std::printf("  CBP_VF: %d boundary crossings, facet centre (%.5f %.5f %.5f), extent %.2e\n", boundary,
                            centre[0], centre[1], centre[2], extent);
            V3 u = P[0] - centre;
            u.normalize();
            const V3 w = N.cross(u);
            const int s = res + 1;
            const double h = 2 * extent / res;
            std::vector<int> sign(std::size_t(s * s), -1), parent(std::size_t(s * s));
            for (int i = 0; i < s; ++i)
                for (int j = 0; j < s; ++j) {
                    const V3 q = centre + (-extent + i * h) * u + (-extent + j * h) * w;
                    bool in_polygon = true;
                    for (std::size_t m = 0; m < P.size() && in_polygon; ++m)
                        in_polygon = (P[(m + 1) % P.size()] - P[m]).cross(q - P[m]).dot(N) >= 0;
                    if (in_polygon) sign[std::size_t(i * s + j)] = isodel::octree::phi_at(reader, q) >= 0;
                }
            for (int i = 0; i < s * s; ++i)
                parent[std::size_t(i)] = i;
            for (int i = 0; i < s; ++i)
                for (int j = 0; j < s; ++j) {
                    const int a = i * s + j;
                    if (sign[std::size_t(a)] < 0) continue;
                    if (i + 1 < s && sign[std::size_t(a + s)] == sign[std::size_t(a)])
                        parent[std::size_t(find_root(parent, a))] = find_root(parent, a + s);
                    if (j + 1 < s && sign[std::size_t(a + 1)] == sign[std::size_t(a)])
                        parent[std::size_t(find_root(parent, a))] = find_root(parent, a + 1);
                }
            // An island: a component of samples that never touches the polygon's edge.
            std::vector<char> touches(std::size_t(s * s), 0);
            std::vector<int> size(std::size_t(s * s), 0);
            for (int i = 0; i < s; ++i)
                for (int j = 0; j < s; ++j) {
                    const int a = i * s + j;
                    if (sign[std::size_t(a)] < 0) continue;
                    const int root = find_root(parent, a);
                    ++size[std::size_t(root)];
                    const bool rim = i == 0 || j == 0 || i == s - 1 || j == s - 1 || sign[std::size_t(a - s)] < 0 ||
                                     sign[std::size_t(a + s)] < 0 || sign[std::size_t(a - 1)] < 0 ||
                                     sign[std::size_t(a + 1)] < 0;
                    if (rim) touches[std::size_t(root)] = 1;
                }
            for (int a = 0; a < s * s; ++a)
                if (sign[std::size_t(a)] >= 0 && find_root(parent, a) == a && !touches[std::size_t(a)] &&
                    size[std::size_t(a)] >= 2) {
                    if (++loops <= show) {
                        // The dual Delaunay edge, in index space (a grid point has integer coordinates).
                        const V3 ea = idx(e->first->vertex(e->second)->point()), eb = idx(e->first->vertex(e->third)->point());
                        std::printf("  CBP_VF loop: island of %d samples (%s), facet centre (%.5f %.5f %.5f), extent %.2e,"
                                    " dual edge (%.5f %.5f %.5f)-(%.5f %.5f %.5f)\n",
                                    size[std::size_t(a)], sign[std::size_t(a)] ? "inside" : "outside", centre[0],
                                    centre[1], centre[2], extent, ea[0], ea[1], ea[2], eb[0], eb[1], eb[2]);
                    }
                    break;
                }
        }
        // Voronoi cells of M's vertices: the Euler characteristic of Sigma' n Vor(p), sampled at
        // 1/CELL_RES voxel (closed_ball/cell_surface_euler.h). A disk has 1; chi < 0 is a handle,
        // which CBP_VC's one-cycle test cannot see.
        int vc = 0, cells = 0;
        std::set<int> on_mesh;
        for (const auto& k : in_mesh)
            for (const int id : k)
                on_mesh.insert(id);
        for (auto v = dt.finite_vertices_begin(); cell_res > 0 && v != dt.finite_vertices_end(); ++v) {
            if (!on_mesh.count(v->info())) continue;
            std::vector<DT::Cell_handle> inc;
            dt.incident_cells(v, std::back_inserter(inc));
            std::vector<DT::Vertex_handle> nb;
            dt.finite_adjacent_vertices(v, std::back_inserter(nb));
            bool unbounded = false;
            V3 lo(1e300), hi(-1e300);
            for (const auto& c : inc) {
                if (dt.is_infinite(c)) {
                    unbounded = true;
                    break;
                }
                const V3 q = idx(exact_circumcenter(c));
                lo = V3(std::min(lo[0], q[0]), std::min(lo[1], q[1]), std::min(lo[2], q[2]));
                hi = V3(std::max(hi[0], q[0]), std::max(hi[1], q[1]), std::max(hi[2], q[2]));
            }
            if (unbounded) continue;
            std::vector<V3> nbw;
            for (const auto& w : nb)
                nbw.push_back(V3(w->point().x(), w->point().y(), w->point().z()));
            const V3 pw(v->point().x(), v->point().y(), v->point().z());
            const isodel::mesher::VoronoiCellPlanes planes(field, pw, nbw);
            const int chi = isodel::mesher::sampled_euler_characteristic(reader, planes, lo, hi, cell_res);
            ++cells;
            if (chi < 0 && ++vc <= show) {
                const V3 pi = idx(v->point());
                std::printf("  CBP_VC: chi(Sigma n Vor) = %d at vertex %d (%.5f %.5f %.5f)\n", chi, v->info(), pi[0],
                            pi[1], pi[2]);
            }
        }
        std::printf("Voronoi cells of M's vertices sampled: %d; with a handle (chi < 0): %d\n", cells, vc);
        std::printf("Voronoi edges crossing Sigma more than once: %d; M facets with the wrong parity: %d\n", ve,
                    parity);
        std::printf("Voronoi facets sampled: %d; more than 2 boundary crossings: %d; with an interior loop: %d\n",
                    facets, vf, loops);
        return ve + vf + loops + parity + vc == 0 ? 0 : 1;
    }
    catch (const std::exception& e) {
        std::fprintf(stderr, "cbp_audit: %s\n", e.what());
        return 1;
    }
}
