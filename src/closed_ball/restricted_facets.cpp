#include "closed_ball/restricted_facets.h"

#include "delaunay/circumcenter.h"
#include "delaunay/vertex_star.h"
#include "octree/segment_walk.h"

#include <algorithm>
#include <stdexcept>
#include <cstdio>
#include <cstdlib>
#include <iterator>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

namespace isodel::mesher {
namespace {

Point to_point(const openvdb::Vec3d& p) { return {p[0], p[1], p[2]}; }

/// Only such facets are recorded: a Voronoi edge dual to a facet of grid points alone never
/// meets Sigma (Theorem 3 keeps G's Voronoi cells off it).
bool has_surface_vertex(const Facet& f)
{
    const auto vs = facet_vertices(f);
    return vs[0]->info().on_surface() || vs[1]->info().on_surface() || vs[2]->info().on_surface();
}

/// Marks both cells of a facet whose record enters the table (cell_base.h).
void mark(const Facet& f)
{
    f.first->mark_facet(f.second);
    const Cell_handle n = f.first->neighbor(f.second);
    n->mark_facet(n->index(f.first));
}

} // namespace

FacetRecord compute_facet_record(const Delaunay& dt, const Facet& f,
                                 const octree::SampleField::Reader& reader, int max_cells)
{
    FacetRecord rec;
    Cell_handle c0 = f.first;
    Cell_handle c1 = c0->neighbor(f.second);
    if (dt.is_infinite(c0) || dt.is_infinite(c1)) {
        rec.overflow = true;
        return rec;
    }
    // Walk the Voronoi edge in a canonical direction (from the cell whose apex has the smaller
    // id): the record then does not depend on which of the two cells represents the facet, and
    // so not on the triangulation's storage order (determinism).
    if (c0->vertex(f.second)->info().id > c1->vertex(c1->index(c0))->info().id) std::swap(c0, c1);
    const Point a = robust_circumcenter(c0);
    const Point b = robust_circumcenter(c1);
    const auto& field = reader.field();
    const auto ia = field.world_to_index(to_vdb(a));
    const auto ib = field.world_to_index(to_vdb(b));
    const octree::SegmentCrossings sc = octree::segment_crossings(reader, ia, ib, max_cells);
    if (sc.overflow) {
        rec.overflow = true;
        return rec;
    }
    rec.crossings = std::uint16_t(std::min<std::size_t>(sc.t.size(), 65535));
    const auto vs = facet_vertices(f);
    if (sc.t.empty()) return rec;
    const Point cc = CGAL::circumcenter(vs[0]->point(), vs[1]->point(), vs[2]->point());
    double best = -1;
    for (double t : sc.t) {
        const Point p = to_point(field.index_to_world(ia + t * (ib - ia)));
        const double d = std::sqrt(CGAL::squared_distance(p, cc));
        if (d > best) {
            best = d;
            rec.surface_point = p;
        }
    }
    rec.distance = best;
    rec.outward = sc.inside_at_start ? (b - a) : (a - b);
    return rec;
}

Vertex_handle FacetCache::insert(Delaunay& dt, const Point& p, VertexInfo info, Cell_handle hint)
{
    Delaunay::Locate_type lt;
    int li, lj;
    const Cell_handle loc = dt.locate(p, lt, li, lj, hint);
    if (lt == Delaunay::VERTEX) return Vertex_handle();
    // Scratch buffers kept across calls: no allocation per inserted point.
    auto& [conflicts, boundary, internal] = scratch_;
    conflicts.clear();
    boundary.clear();
    internal.clear();
    dt.find_conflicts(p, loc, std::back_inserter(boundary), std::back_inserter(conflicts), std::back_inserter(internal));
    // The facets the insertion replaces: each one once (an internal facet is shared by two
    // conflict cells), and a boundary facet too, since its other cell is replaced.
    // Only facets marked in their cell (cell_base.h) may have a record: a recorded facet is
    // marked on both its cells, and each facet here has a cell in the conflict region, so
    // looking at that side is enough. The others, ~60 per point and nearly all of them, need
    // no key and no lookup.
    for (const auto* facets : {&boundary, &internal})
        for (const Facet& f : *facets)
            if (f.first->facet_marked(f.second)) {
                const FacetKey k = facet_key(f);
                if (map_.erase(k)) changed_.push_back(k);
            }
    // In dimension 3, Delaunay insertion is exactly "star the conflict region" (what
    // dt.insert does after finding the same region again): reuse the region found above.
    const Vertex_handle v = dt.dimension() == 3 && !boundary.empty()
                                ? dt.insert_in_hole(p, conflicts.begin(), conflicts.end(), boundary.front().first,
                                                    boundary.front().second)
                                : dt.insert(p, lt, loc, li, lj);
    v->info() = info;
    inserted_.push_back(v);
    if (by_id_ready_) {
        if (by_id_.size() <= info.id) by_id_.resize(std::max<std::size_t>(std::size_t(info.id) + 1, 2 * by_id_.size()));
        by_id_[info.id] = v;
    }
    return v;
}

Cell_handle FacetCache::cell_near(const Delaunay& dt, std::uint32_t id)
{
    if (!by_id_ready_) {
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
            if (by_id_.size() <= v->info().id) by_id_.resize(std::size_t(v->info().id) + 1);
            by_id_[v->info().id] = v;
        }
        by_id_ready_ = true;
    }
    return id < by_id_.size() && by_id_[id] != Vertex_handle() ? by_id_[id]->cell() : Cell_handle();
}

void FacetCache::remove(Delaunay& dt, const std::vector<Vertex_handle>& vertices)
{
    std::vector<Vertex_handle> link;
    std::vector<Cell_handle> cells;
    for (const Vertex_handle& v : vertices) {
        cells.clear();
        dt.incident_cells(v, std::back_inserter(cells));
        for (const Cell_handle& c : cells)
            for (int j = 0; j < 4; ++j) {
                const Facet f(c, j);
                if (scanned_ && !dt.is_infinite(f) && has_surface_vertex(f)) {
                    const FacetKey k = facet_key(f);
                    if (map_.erase(k)) changed_.push_back(k);
                }
                const Vertex_handle w = c->vertex(j);
                if (w != v && !dt.is_infinite(w)) link.push_back(w);
            }
        if (by_id_ready_ && v->info().id < by_id_.size()) by_id_[v->info().id] = Vertex_handle();
        dt.remove(v);
    }
    // A vertex removed later in the batch may be in an earlier one's link, or among the points
    // inserted since the last update: drop those handles (compared, never dereferenced; no
    // vertex is created meanwhile, so no slot is reused). The rest go in id order, so the
    // facets update() finds do not depend on memory layout.
    std::vector<Vertex_handle> gone(vertices);
    std::sort(gone.begin(), gone.end());
    const auto removed = [&](const Vertex_handle& w) { return std::binary_search(gone.begin(), gone.end(), w); };
    inserted_.erase(std::remove_if(inserted_.begin(), inserted_.end(), removed), inserted_.end());
    if (!scanned_) return; // the first update() scans everything anyway
    link.erase(std::remove_if(link.begin(), link.end(), removed), link.end());
    std::sort(link.begin(), link.end(), [](const Vertex_handle& a, const Vertex_handle& b) { return a->info().id < b->info().id; });
    link.erase(std::unique(link.begin(), link.end()), link.end());
    inserted_.insert(inserted_.end(), link.begin(), link.end());
}

/// update()'s shared state: the facets whose records are still to compute, the active entries
/// computed so far (in the order they entered the table), and a field reader per thread.
/// Only records that some check reads are kept: those of facets whose Voronoi edge crosses
/// Sigma or left its bound. The others would only be erased again by the insertion that
/// destroys them: every facet considered belongs to a cell created since the last update, so
/// none of them was known before, and a stored zero record would never be looked up; most
/// facets are such, so keeping them would be a sizeable part of the peak memory. So records
/// are computed into the to-do list, in parallel, and only the active ones enter the table
/// (serially, in to-do order).
struct FacetCache::UpdateRun {
    struct Todo {
        Facet facet;
        FacetKey key;
        FacetRecord record;
    };
    UpdateRun(const Delaunay& triangulation, const octree::SampleField& field, int max_cells_)
        : dt(triangulation), max_cells(max_cells_),
          readers([f = &field] { return octree::SampleField::Reader(*f); })
    {
    }
    const Delaunay& dt;
    const int max_cells;
    std::vector<Todo> todo;
    std::vector<Entry> added;
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers;
};

/// The first scan's current run of cells, and per task of the run the records it keeps and the
/// facets it counted. Runs of kCells cells are flushed into the table in order, which bounds
/// the transient lists; a task walks the facets of kTask cells.
struct FacetCache::CellRun {
    static constexpr std::size_t kCells = std::size_t(1) << 20, kTask = 2048;
    std::vector<Cell_handle> cells;
    std::vector<std::vector<UpdateRun::Todo>> kept;
    std::vector<std::size_t> counted;
};

bool FacetCache::in_region(const Facet& f) const
{
    if (!region_) return true;
    for (const auto& v : facet_vertices(f))
        if (region_(v->point())) return true;
    return false;
}

void FacetCache::update(const Delaunay& dt, const octree::SampleField& field, int max_cells)
{
    const bool initial = !scanned_;
    UpdateRun run(dt, field, max_cells);
    computed_ = 0;
    if (initial) {
        scan_every_facet(run);
        scanned_ = true;
    } else {
        scan_around_inserted(run);
    }
    inserted_.clear();
    record_todo(run);
    apply_changes(run.added);
}

void FacetCache::record_todo(UpdateRun& run)
{
    const Delaunay& dt = run.dt;
    const int max_cells = run.max_cells;
    auto& todo = run.todo;
    auto& readers = run.readers;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          auto& reader = readers.local();
                          for (std::size_t i = r.begin(); i != r.end(); ++i)
                              todo[i].record = compute_facet_record(dt, todo[i].facet, reader, max_cells);
                      });
    computed_ += todo.size();
    for (const UpdateRun::Todo& t : todo) {
        // No entry in changed_ for a recomputed key: it is not in the table, so any old
        // entry of it was erased by insert(), which listed it there.
        if (t.record.crossings == 0 && !t.record.overflow) continue;
        run.added.push_back(enter(t.facet, t.key, t.record));
    }
    todo.clear();
}

void FacetCache::scan_every_facet(UpdateRun& run)
{
    // Every facet once, in the order of dt.finite_facets() (a cell's facet i when its
    // neighbour there is not stored before it), a run of cells per task: the walk itself
    // runs in parallel, and a task keeps only the records some check reads (CellRun).
    // (The first scan covers every facet of Del(E u G), the largest walk of a run: done
    // serially it would leave every other thread idle.)
    const Delaunay& dt = run.dt;
    CellRun batch;
    batch.cells.reserve(std::min<std::size_t>(CellRun::kCells, dt.number_of_cells() + 8));
    // Only a 3D triangulation has Voronoi edges between cells: E u G always spans 3D (G is
    // the 4 x 4 x 4 block of samples around every crossed cell).
    if (dt.dimension() == 3) {
        for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
            batch.cells.push_back(c);
            if (batch.cells.size() == CellRun::kCells) record_cell_run(run, batch);
        }
        record_cell_run(run, batch);
    }
}

void FacetCache::record_cell_run(UpdateRun& run, CellRun& batch)
{
    constexpr std::size_t kTask = CellRun::kTask;
    const Delaunay& dt = run.dt;
    const int max_cells = run.max_cells;
    auto& readers = run.readers;
    auto& cells = batch.cells;
    auto& kept = batch.kept;
    auto& counted = batch.counted;
    const std::size_t tasks = (cells.size() + kTask - 1) / kTask;
    kept.assign(tasks, {});
    counted.assign(tasks, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tasks, 1), [&](const auto& r) {
        auto& reader = readers.local();
        for (std::size_t t = r.begin(); t != r.end(); ++t)
            for (std::size_t k = t * kTask; k < std::min(cells.size(), (t + 1) * kTask); ++k) {
                const Cell_handle& c = cells[k];
                for (int i = 0; i < 4; ++i) {
                    if (c->neighbor(i) < c) continue; // found from its neighbour
                    const Facet f(c, i);
                    if (dt.is_infinite(f) || !has_surface_vertex(f) || !in_region(f)) continue;
                    ++counted[t];
                    FacetRecord rec = compute_facet_record(dt, f, reader, max_cells);
                    if (rec.crossings == 0 && !rec.overflow) continue;
                    kept[t].push_back({f, facet_key(f), rec});
                }
            }
    });
    for (std::size_t t = 0; t < tasks; ++t) {
        computed_ += counted[t];
        for (const UpdateRun::Todo& x : kept[t]) run.added.push_back(enter(x.facet, x.key, x.record));
    }
    cells.clear();
}

void FacetCache::scan_around_inserted(UpdateRun& run)
{
    // The facets of the cells around the inserted points, a chunk of points at a time. The
    // stars are gathered in parallel (gather_star: no shared visit marks), each facet is kept
    // once (sorted by key, then by the order found) and skipped when its record is known.
    const Delaunay& dt = run.dt;
    auto& todo = run.todo;
    constexpr std::size_t kChunk = std::size_t(1) << 14;
    struct Found {
        FacetKey key;
        std::uint32_t order;
        Facet facet;
    };
    std::vector<std::vector<Found>> per_vertex;
    std::vector<Found> found;
    std::vector<char> known;
    for (std::size_t first = 0; first < inserted_.size(); first += kChunk) {
        const std::size_t end = std::min(first + kChunk, inserted_.size());
        per_vertex.assign(end - first, {});
        for_each_star(inserted_, first, end, [&](std::size_t i, const std::vector<Cell_handle>& cells) {
            for (const Cell_handle& c : cells)
                for (int j = 0; j < 4; ++j) {
                    // A facet through v is in two cells of the star: take it from one
                    // (either: compute_facet_record walks the edge canonically).
                    if (j != c->index(inserted_[i]) && c->neighbor(j) < c) continue;
                    const Facet f(c, j);
                    if (!dt.is_infinite(f) && has_surface_vertex(f) && in_region(f))
                        per_vertex[i - first].push_back({facet_key(f), 0, f});
                }
        });
        found.clear();
        for (auto& list : per_vertex)
            for (Found& f : list) {
                f.order = std::uint32_t(found.size());
                found.push_back(f);
            }
        tbb::parallel_sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
            return a.key < b.key || (a.key == b.key && a.order < b.order);
        });
        found.erase(std::unique(found.begin(), found.end(), [](const Found& a, const Found& b) { return a.key == b.key; }),
                    found.end());
        known.assign(found.size(), 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, found.size(), 1024), [&](const auto& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) known[i] = map_.contains(found[i].key);
        });
        for (std::size_t i = 0; i < found.size(); ++i)
            if (!known[i]) todo.push_back({found[i].facet, found[i].key, FacetRecord()});
        record_todo(run);
    }
}

void FacetCache::apply_changes(std::vector<Entry>& added)
{
    // The active list changes by the changed keys (destroyed or recomputed facets) and the
    // recomputed active facets. Merging them into the sorted list costs O(|active|), so it is
    // done only when active() is next read (merge_pending): the closed-ball rounds read the
    // flagged classes and the stars, the cascade of CBP_VE steps recent(); the Hausdorff
    // check, extraction and the tets phase read active().
    const auto by_key = [](const Entry& a, const Entry& b) { return a.key < b.key; };
    tbb::parallel_sort(added.begin(), added.end(), by_key); // keys are unique: any sort gives one order
    tbb::parallel_sort(changed_.begin(), changed_.end());
    changed_.erase(std::unique(changed_.begin(), changed_.end()), changed_.end());
    // A pending entry whose key changed again is stale (its recomputation, if active, is in added).
    if (!pending_added_.empty())
        pending_added_.erase(std::remove_if(pending_added_.begin(), pending_added_.end(),
                                            [&](const Entry& e) {
                                                return std::binary_search(changed_.begin(), changed_.end(), e.key);
                                            }),
                             pending_added_.end());
    pending_added_.insert(pending_added_.end(), added.begin(), added.end());
    pending_changed_.insert(pending_changed_.end(), changed_.begin(), changed_.end());
    // The restricted stars follow the same changes: the changed keys leave, the recomputed
    // restricted facets come back.
    for (const FacetKey& k : changed_) unstar(k);
    for (const Entry& e : added)
        if (e.crossings == 1) star(e);
    update_flagged(added);
    changed_.clear();
    recent_.swap(added);
    // Most rounds never read active() (the checks read flagged() and the stars); merge a large
    // backlog anyway, since every update filters the pending entries against its changed keys.
    if (pending_added_.size() + pending_changed_.size() > (std::size_t(1) << 16)) merge_pending();
}

FacetCache::Entry FacetCache::entry(const FacetKey& key) const
{
    const Stored* st = map_.find(key);
    if (!st) throw std::logic_error("FacetCache::entry: no active facet with this key (read flagged() right after update())");
    return entry_of(*st, key);
}

FacetCache::Entry FacetCache::entry_of(const Stored& st, const FacetKey& key)
{
    const auto vs = facet_vertices(st.facet);
    const bool on = vs[0]->info().on_surface() && vs[1]->info().on_surface() && vs[2]->info().on_surface();
    return {st.facet, key, &st.record, st.record.crossings, st.record.overflow, on};
}

FacetCache::Entry FacetCache::enter(const Facet& f, const FacetKey& key, const FacetRecord& record)
{
    const Stored* st = map_.try_emplace(key, Stored{f, record}).first;
    mark(st->facet);
    return entry_of(*st, key);
}

void FacetCache::update_flagged(const std::vector<Entry>& added)
{
    // Both sorted: the changed keys leave each list in one merge walk, the recomputed facets of
    // each class are merged in (a recomputed key is one of the changed or a new one, so the
    // result has no duplicates).
    auto refresh = [&](std::vector<FacetKey>& keys, auto&& in_class) {
        if (!changed_.empty() && !keys.empty()) {
            auto c = changed_.cbegin();
            keys.erase(std::remove_if(keys.begin(), keys.end(),
                                      [&](const FacetKey& k) {
                                          while (c != changed_.cend() && *c < k) ++c;
                                          return c != changed_.cend() && *c == k;
                                      }),
                       keys.end());
        }
        const std::size_t n = keys.size();
        for (const Entry& e : added) // sorted by key
            if (in_class(e)) keys.push_back(e.key);
        std::inplace_merge(keys.begin(), keys.begin() + std::ptrdiff_t(n), keys.end());
    };
    refresh(flagged_.overflow, [](const Entry& e) { return e.overflow; });
    refresh(flagged_.multiple, [](const Entry& e) { return !e.overflow && e.crossings > 1; });
    refresh(flagged_.grid_vertex, [](const Entry& e) { return !e.overflow && e.crossings == 1 && !e.all_on_surface; });
    refresh(flagged_.far, [&](const Entry& e) {
        return !e.overflow && e.crossings == 1 && e.record->distance > far_distance_;
    });
}

void FacetCache::merge_pending() const
{
    if (pending_changed_.empty() && pending_added_.empty()) return;
    const auto by_key = [](const Entry& a, const Entry& b) { return a.key < b.key; };
    std::sort(pending_changed_.begin(), pending_changed_.end());
    if (!pending_changed_.empty() && !active_.empty()) {
        // Both sorted by key: one merge walk drops the changed entries.
        auto c = pending_changed_.begin();
        active_.erase(std::remove_if(active_.begin(), active_.end(),
                                     [&](const Entry& e) {
                                         while (c != pending_changed_.end() && *c < e.key) ++c;
                                         return c != pending_changed_.end() && !(e.key < *c);
                                     }),
                      active_.end());
    }
    std::sort(pending_added_.begin(), pending_added_.end(), by_key);
    // Merged in place from the back (as std::merge: on equal keys the active entry first). A
    // fresh array of every active facet per round would pay its page faults in every round,
    // and most rounds add only a handful of entries.
    const std::size_t n = active_.size();
    active_.resize(n + pending_added_.size());
    auto out = active_.end(), a = active_.begin() + std::ptrdiff_t(n);
    for (auto b = pending_added_.end(); b != pending_added_.begin();) {
        if (a != active_.begin() && by_key(*(b - 1), *(a - 1))) *--out = *--a;
        else *--out = *--b;
    }
    pending_changed_.clear();
    pending_added_.clear();
}

void FacetCache::unstar(const FacetKey& key)
{
    const auto by_key = [](const StarFacet& s, const FacetKey& k) { return s.key < k; };
    for (const std::uint32_t id : key.v) {
        if (id >= stars_.size()) continue;
        auto& st = stars_[id];
        const auto it = std::lower_bound(st.begin(), st.end(), key, by_key);
        if (it == st.end() || !(it->key == key)) continue;
        st.erase(it);
        touched_.push_back(id);
    }
}

void FacetCache::star(const Entry& e)
{
    const auto by_key = [](const StarFacet& s, const FacetKey& k) { return s.key < k; };
    const std::uint32_t top = e.key.v[2]; // keys are sorted: the largest id
    if (stars_.size() <= top) stars_.resize(std::size_t(top) + 1);
    if (points_.size() <= top) points_.resize(std::max<std::size_t>(std::size_t(top) + 1, 2 * points_.size()));
    for (const auto& v : facet_vertices(e.facet)) points_[v->info().id] = v->point();
    for (const std::uint32_t id : e.key.v) {
        auto& st = stars_[id];
        const auto it = std::lower_bound(st.begin(), st.end(), e.key, by_key);
        if (it != st.end() && it->key == e.key) continue;
        st.insert(it, StarFacet{e.key, e.record->surface_point});
        touched_.push_back(id);
    }
}

std::vector<std::uint32_t> FacetCache::take_touched_vertices()
{
    std::vector<std::uint32_t> out;
    out.swap(touched_);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

} // namespace isodel::mesher
