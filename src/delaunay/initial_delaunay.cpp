#include "delaunay/initial_delaunay.h"

#include <CGAL/Spatial_lock_grid_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace isodel::mesher {
namespace {

/// A vertex or cell base of the parallel build's triangulation plus its position in the copy
/// (copy_into), where CGAL's copy_tds looks every handle up in a hash map.
template <class Base>
class WithCopyIndex : public Base {
public:
    using Base::Base;
    template <class TDS2>
    struct Rebind_TDS {
        using Other = WithCopyIndex<typename Base::template Rebind_TDS<TDS2>::Other>;
    };
    std::uint32_t copy_index = 0;
};

// The build's cells need none of the mesher's cell caches (cell_base.h): copy_into makes fresh
// cells, and CGAL's plain cell keeps the parallel build's memory traffic down.
using ParallelTds = CGAL::Triangulation_data_structure_3<WithCopyIndex<Vb>,
                                                         WithCopyIndex<CGAL::Delaunay_triangulation_cell_base_3<K>>,
                                                         CGAL::Parallel_tag>;
using ParallelDelaunay = CGAL::Delaunay_triangulation_3<DelaunayTraits, ParallelTds>;

/// Makes \p dst a copy of \p src's triangulation, as CGAL's copy_tds does (vertices and cells
/// created in \p src's order, so \p dst stores them in the same order), but with the handle
/// maps as arrays indexed by copy_index and the pointers set in parallel. A vertex keeps its
/// point and info; a cell starts afresh (no facet marks: the facet cache has no record yet,
/// cell_base.h). copy_tds is serial, with a hash lookup per handle: on millions of cells it
/// would take back a noticeable part of what the parallel insertion saves.
/// Returns the copy of \p src's infinite vertex.
Vertex_handle copy_into(ParallelDelaunay& src, Delaunay& dst)
{
    ParallelTds& s = src.tds();
    Tds& d = dst.tds();
    d.clear();
    d.set_dimension(s.dimension());
    const int n_vertices = std::max(1, s.dimension() + 1); // vertex pointers per cell
    const int n_neighbors = std::max(0, s.dimension() + 1);
    if (s.number_of_cells() > std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("initial Delaunay: " + std::to_string(s.number_of_cells()) +
                                " cells, more than the copy's 32-bit indices hold");

    std::vector<ParallelTds::Vertex_handle> src_vertices;
    std::vector<Vertex_handle> vertices;
    src_vertices.reserve(s.number_of_vertices());
    vertices.reserve(s.number_of_vertices());
    for (auto v = s.vertices_begin(); v != s.vertices_end(); ++v) {
        v->copy_index = std::uint32_t(vertices.size());
        Tds::Vertex copy(v->point());
        copy.info() = v->info();
        src_vertices.push_back(v);
        vertices.push_back(d.create_vertex(copy));
    }
    std::vector<ParallelTds::Cell_handle> src_cells;
    std::vector<Cell_handle> cells;
    src_cells.reserve(s.number_of_cells());
    cells.reserve(s.number_of_cells());
    for (auto c = s.cells().begin(); c != s.cells_end(); ++c) {
        c->copy_index = std::uint32_t(cells.size());
        src_cells.push_back(c);
        cells.push_back(d.create_cell());
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 1 << 14), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const ParallelTds::Cell_handle c = src_cells[i];
            for (int j = 0; j < n_vertices; ++j) cells[i]->set_vertex(j, vertices[c->vertex(j)->copy_index]);
            for (int j = 0; j < n_neighbors; ++j) cells[i]->set_neighbor(j, cells[c->neighbor(j)->copy_index]);
        }
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices.size(), 1 << 14), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) vertices[i]->set_cell(cells[src_vertices[i]->cell()->copy_index]);
    });
    return vertices[src.infinite_vertex()->copy_index];
}

// Below this many points sequential insertion is quick, and the lock grid and the copy are not
// worth setting up. Not tuned: the meshes are the same either way.
constexpr std::size_t kParallelMin = 20000;
// The parallel insertion locks the cells of a kLockCells^3 grid over the points' box (as CGAL's
// examples); it pays only while the points spread over enough of them.
constexpr int kLockCells = 50;
constexpr std::size_t kParallelMinLockCells = 1000;
// How often the sequential insertion asks whether to stop: a cancel (Ctrl-C in Python) must not
// wait for the whole triangulation, the largest single step of a run.
constexpr std::size_t kPollPoints = 1 << 14;

/// How many cells of the lock grid over \p box hold a point.
std::size_t occupied_lock_cells(const std::vector<std::pair<Point, VertexInfo>>& points, const CGAL::Bbox_3& box)
{
    std::vector<std::uint32_t> cells;
    cells.reserve(points.size());
    for (const auto& [p, info] : points) {
        std::uint32_t key = 0;
        for (int a = 0; a < 3; ++a) {
            const double extent = box.max(a) - box.min(a);
            const int i = extent > 0 ? std::min(kLockCells - 1, int((p[a] - box.min(a)) / extent * kLockCells)) : 0;
            key = key * kLockCells + std::uint32_t(i);
        }
        cells.push_back(key);
    }
    std::sort(cells.begin(), cells.end());
    return std::size_t(std::unique(cells.begin(), cells.end()) - cells.begin());
}

/// CGAL's sequential insertion of a range (Delaunay_triangulation_3::insert_with_info): the same
/// spatial sort and the same chain of hints, so the same triangulation stored in the same order,
/// with \p scope polled every kPollPoints points.
void insert_sequentially(Delaunay& dt, const std::vector<std::pair<Point, VertexInfo>>& points,
                         const InterruptScope* scope)
{
    std::vector<std::size_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    using PointMap = CGAL::Pointer_property_map<Point>::type;
    std::vector<Point> xyz;
    xyz.reserve(points.size());
    for (const auto& p : points) xyz.push_back(p.first);
    CGAL::spatial_sort<CGAL::Sequential_tag>(
        order.begin(), order.end(),
        CGAL::Spatial_sort_traits_adapter_3<DelaunayTraits, PointMap>(CGAL::make_property_map(xyz), dt.geom_traits()));
    Vertex_handle hint;
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (scope && i % kPollPoints == 0) scope->check(i, order.size(), "points");
        hint = dt.insert(xyz[order[i]], hint);
        if (hint != Vertex_handle()) hint->info() = points[order[i]].second;
    }
}

} // namespace

void build_initial_delaunay(Delaunay& dt, const std::vector<std::pair<Point, VertexInfo>>& points,
                            const InterruptScope* scope)
{
    dt.clear();
    const std::size_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    if (threads < 2 || points.size() < kParallelMin) {
        insert_sequentially(dt, points, scope);
        return;
    }
    CGAL::Bbox_3 box = points.front().first.bbox();
    for (const auto& p : points) box += p.first.bbox();
    if (occupied_lock_cells(points, box) < kParallelMinLockCells) {
        // Sparse data (shapes far apart in a large box): the points fall into a few lock cells,
        // and threads that insert into the same cell only retry each other's work.
        insert_sequentially(dt, points, scope);
        return;
    }
    // One call, so CGAL orders the whole set (BRIO) for its threads: inserting in polled
    // rounds (slices of that order, or every n-th point) made this stage 1.5 to 3 times slower
    // on 2 threads. So a cancel is heard after it, at the caller's next poll.
    ParallelDelaunay::Lock_data_structure locks(box, kLockCells);
    ParallelDelaunay pdt(points.begin(), points.end(), &locks);
    dt.set_infinite_vertex(copy_into(pdt, dt));
}

} // namespace isodel::mesher
