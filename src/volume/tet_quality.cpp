#include "volume/tet_quality.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace isodel::mesher {
namespace {

using V3 = std::array<double, 3>;
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const V3& a) { return std::sqrt(dot(a, a)); }

constexpr double kPi = 3.14159265358979323846;

} // namespace

double signed_tet_volume(const V3& a, const V3& b, const V3& c, const V3& d)
{
    return dot(sub(b, a), cross(sub(c, a), sub(d, a))) / 6.0;
}

double enclosed_volume(const SurfaceMesh& mesh)
{
    if (mesh.vertices.empty()) return 0;
    const V3& o = mesh.vertices[0];
    double v = 0;
    for (const auto& t : mesh.triangles)
        v += signed_tet_volume(o, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    return v;
}

namespace {

/// What measure_tet_quality() gathers over a run of tets.
struct QualityPart {
    std::size_t tets_inside = 0, tets_outside = 0, tets_touching_surface = 0, tets_below_10deg = 0;
    double volume_inside = 0, volume_outside = 0;
    double min_dihedral_deg = 180, max_dihedral_deg = 0, max_radius_edge = 0;
    double min_dihedral_deg_off_surface = 180, max_radius_edge_off_surface = 0;
    std::array<std::size_t, 18> histogram{};
};

void measure_tets(const TetMesh& mesh, std::size_t surface_vertices, std::size_t begin, std::size_t end, QualityPart& st)
{
    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                         {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    for (std::size_t t = begin; t < end; ++t) {
        const V3* p[4];
        for (int j = 0; j < 4; ++j) p[j] = &mesh.vertices[std::size_t(mesh.tets[t][j])];
        const double vol = signed_tet_volume(*p[0], *p[1], *p[2], *p[3]);
        (mesh.tet_region[t] == 1 ? st.volume_inside : st.volume_outside) += vol;
        (mesh.tet_region[t] == 1 ? st.tets_inside : st.tets_outside) += 1;
        double shortest = INFINITY, tet_min = 180;
        for (const auto& e : kEdges) {
            // Dihedral angle at edge (e0, e1): the angle between the normals e x (p2 - p0) and
            // e x (p3 - p0), a quarter turn about e of the two faces' in-plane directions.
            const V3 ev = sub(*p[e[1]], *p[e[0]]);
            shortest = std::min(shortest, norm(ev));
            const V3 n1 = cross(ev, sub(*p[e[2]], *p[e[0]]));
            const V3 n2 = cross(ev, sub(*p[e[3]], *p[e[0]]));
            const double c = std::clamp(dot(n1, n2) / (norm(n1) * norm(n2)), -1.0, 1.0);
            const double deg = std::acos(c) * 180.0 / kPi;
            tet_min = std::min(tet_min, deg);
            st.min_dihedral_deg = std::min(st.min_dihedral_deg, deg);
            st.max_dihedral_deg = std::max(st.max_dihedral_deg, deg);
            st.histogram[std::min<std::size_t>(17, std::size_t(deg / 10.0))]++;
        }
        // Circumradius from the vertex-relative formula (Shewchuk, "Lecture notes on Delaunay
        // mesh generation", Sec. 1.10): |a|^2 (b x c) + |b|^2 (c x a) + |c|^2 (a x b) / (2 a.(b x c)).
        const V3 a = sub(*p[1], *p[0]), b = sub(*p[2], *p[0]), c = sub(*p[3], *p[0]);
        const V3 bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
        const double den = 2 * dot(a, bc);
        V3 r;
        for (int k = 0; k < 3; ++k) r[k] = (dot(a, a) * bc[k] + dot(b, b) * ca[k] + dot(c, c) * ab[k]) / den;
        const double re = norm(r) / shortest;
        st.max_radius_edge = std::max(st.max_radius_edge, re);
        st.tets_below_10deg += tet_min < 10;
        bool touches = false;
        for (int j = 0; j < 4; ++j) touches |= std::size_t(mesh.tets[t][j]) < surface_vertices;
        if (touches) {
            ++st.tets_touching_surface;
        } else {
            st.min_dihedral_deg_off_surface = std::min(st.min_dihedral_deg_off_surface, tet_min);
            st.max_radius_edge_off_surface = std::max(st.max_radius_edge_off_surface, re);
        }
    }
}

} // namespace

void measure_tet_quality(const TetMesh& mesh, std::size_t surface_vertices, TetStats& st)
{
    // In parallel over fixed runs of tets, folded in run order: the volume sums round the same
    // way whatever the thread count. (Parallel because a large mesh has millions of tets.)
    constexpr std::size_t kRun = std::size_t(1) << 15;
    std::vector<QualityPart> parts((mesh.tets.size() + kRun - 1) / kRun);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, parts.size(), 1), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            measure_tets(mesh, surface_vertices, i * kRun, std::min(mesh.tets.size(), (i + 1) * kRun), parts[i]);
    });
    // Folded straight into st, from the identities of each statistic (a part's own defaults).
    const QualityPart none;
    st.vertices = mesh.vertices.size();
    st.tets_inside = st.tets_outside = st.tets_touching_surface = st.tets_below_10deg = 0;
    st.volume_inside = st.volume_outside = 0;
    st.min_dihedral_deg = none.min_dihedral_deg;
    st.max_dihedral_deg = none.max_dihedral_deg;
    st.max_radius_edge = none.max_radius_edge;
    st.min_dihedral_deg_off_surface = none.min_dihedral_deg_off_surface;
    st.max_radius_edge_off_surface = none.max_radius_edge_off_surface;
    st.dihedral_histogram.assign(none.histogram.size(), 0);
    for (const QualityPart& p : parts) {
        st.tets_inside += p.tets_inside;
        st.tets_outside += p.tets_outside;
        st.tets_touching_surface += p.tets_touching_surface;
        st.tets_below_10deg += p.tets_below_10deg;
        st.volume_inside += p.volume_inside;
        st.volume_outside += p.volume_outside;
        st.min_dihedral_deg = std::min(st.min_dihedral_deg, p.min_dihedral_deg);
        st.max_dihedral_deg = std::max(st.max_dihedral_deg, p.max_dihedral_deg);
        st.max_radius_edge = std::max(st.max_radius_edge, p.max_radius_edge);
        st.min_dihedral_deg_off_surface = std::min(st.min_dihedral_deg_off_surface, p.min_dihedral_deg_off_surface);
        st.max_radius_edge_off_surface = std::max(st.max_radius_edge_off_surface, p.max_radius_edge_off_surface);
        for (std::size_t b = 0; b < p.histogram.size(); ++b) st.dihedral_histogram[b] += p.histogram[b];
    }
    if (mesh.tets.empty()) st.min_dihedral_deg = 0;
}

} // namespace isodel::mesher
