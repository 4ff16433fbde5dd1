#pragma once
// Internal: the 3D Delaunay triangulation Del(E u G u N) the mesher maintains (CGAL, EPICK:
// exact predicates, so every combinatorial decision is exact; constructions such as
// circumcentres are double precision). CGAL types stay inside src/.
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <openvdb/math/Vec3.h>

#include "delaunay/cell_base.h"
#include "delaunay/delaunay_traits.h"

#include <array>
#include <cstdint>

namespace isodel::mesher {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Vector = K::Vector_3;

/// A CGAL point as an OpenVDB vector (the octree/ side's type).
inline openvdb::math::Vec3d to_vdb(const Point& p) { return {p.x(), p.y(), p.z()}; }

/// What a vertex is (paper notation).
enum class PointKind : std::uint8_t {
    Grid = 0,        ///< G: protective layer (and repairs of it)
    Edge = 1,        ///< E: crossing of Sigma with a grid edge
    Topology = 2,    ///< N inserted to enforce the closed ball property
    Geometry = 3,    ///< N inserted for the eps criterion
    Snapped = 4,     ///< a grid point that took the place of the E points near it (--snap)
};

struct VertexInfo {
    std::uint32_t id = 0; ///< insertion order: a deterministic key
    PointKind kind = PointKind::Grid;
    bool on_surface() const { return kind != PointKind::Grid; }
};

using Vb = CGAL::Triangulation_vertex_base_with_info_3<VertexInfo, K>;
using Cb = CellWithCaches<K>; // CGAL's Delaunay cell, the facet cache's marks, the Voronoi vertex and the region label (cell_base.h)
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
static_assert(sizeof(Tds::Cell) <=
                  sizeof(CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<K>>::Cell) + 24,
              "the facet marks, the region label bytes and the circumcentre cache should add 24 bytes to CGAL's cell (cell_base.h)");
using Delaunay = CGAL::Delaunay_triangulation_3<DelaunayTraits, Tds>; // EPICK's decisions (delaunay_traits.h)
using Vertex_handle = Delaunay::Vertex_handle;
using Cell_handle = Delaunay::Cell_handle;
using Facet = Delaunay::Facet;

/// A facet identified by its sorted vertex ids: independent of which cell it is seen from.
struct FacetKey {
    std::array<std::uint32_t, 3> v;
    bool operator==(const FacetKey& o) const { return v == o.v; }
    bool operator<(const FacetKey& o) const { return v < o.v; }
};
struct FacetKeyHash {
    std::size_t operator()(const FacetKey& k) const
    {
        std::uint64_t h = k.v[0];
        h = h * 0x9E3779B97F4A7C15ull ^ k.v[1];
        h = h * 0x9E3779B97F4A7C15ull ^ k.v[2];
        return std::size_t(h ^ (h >> 29));
    }
};

inline FacetKey facet_key(const Facet& f)
{
    FacetKey k;
    for (int j = 0; j < 3; ++j) k.v[j] = f.first->vertex((f.second + 1 + j) & 3)->info().id;
    std::sort(k.v.begin(), k.v.end());
    return k;
}

/// The facet's vertices in id order: every computation on a facet then rounds the same way
/// whichever cell represents it (determinism).
inline std::array<Vertex_handle, 3> facet_vertices(const Facet& f)
{
    std::array<Vertex_handle, 3> v{f.first->vertex((f.second + 1) & 3), f.first->vertex((f.second + 2) & 3),
                                   f.first->vertex((f.second + 3) & 3)};
    std::sort(v.begin(), v.end(), [](Vertex_handle a, Vertex_handle b) { return a->info().id < b->info().id; });
    return v;
}

} // namespace isodel::mesher
