#include "mesher/initial_delaunay.h"

#include <CGAL/Spatial_lock_grid_3.h>

#include <tbb/global_control.h>

namespace isodel::mesher {
namespace {

using ParallelTds = CGAL::Triangulation_data_structure_3<Vb, Cb, CGAL::Parallel_tag>;
using ParallelDelaunay = CGAL::Delaunay_triangulation_3<K, ParallelTds>;

// copy_tds's converters: a vertex keeps its point and info; a cell starts afresh (no facet marks:
// the facet cache has no record yet, cell_base.h).
struct ConvertVertex {
    Tds::Vertex operator()(const ParallelTds::Vertex& src) const
    {
        Tds::Vertex v(src.point());
        v.info() = src.info();
        return v;
    }
    void operator()(const ParallelTds::Vertex&, Tds::Vertex&) const {}
};
struct ConvertCell {
    Tds::Cell operator()(const ParallelTds::Cell&) const { return Tds::Cell(); }
    void operator()(const ParallelTds::Cell&, Tds::Cell&) const {}
};

// Below this many points (a tenth of a second of sequential insertion) the lock grid and the copy
// are not worth setting up. Not tuned: the meshes are the same either way.
constexpr std::size_t kParallelMin = 20000;

} // namespace

void build_initial_delaunay(Delaunay& dt, const std::vector<std::pair<Point, VertexInfo>>& points)
{
    dt.clear();
    const std::size_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    if (threads < 2 || points.size() < kParallelMin) {
        dt.insert(points.begin(), points.end());
        return;
    }
    CGAL::Bbox_3 box = points.front().first.bbox();
    for (const auto& p : points) box += p.first.bbox();
    ParallelDelaunay::Lock_data_structure locks(box, 50); // 50^3 lock cells, as CGAL's examples
    const ParallelDelaunay pdt(points.begin(), points.end(), &locks);
    dt.set_infinite_vertex(dt.tds().copy_tds(pdt.tds(), pdt.infinite_vertex(), ConvertVertex(), ConvertCell()));
}

} // namespace isodel::mesher
