#include "surface/stage_clock.h"
#include "surface/refiner.h"

#include "geometry/point_lattice.h"

#include "closed_ball/grid_cell_check.h"
#include "closed_ball/voronoi_cell_disks.h"
#include "closed_ball/voxel_bound.h"

#include <isodel/errors.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace isodel::mesher {
namespace {

using Clock = std::chrono::steady_clock;

/// Adds the seconds of its scope to \p total (MeshStats::refinement_seconds).
struct StepTimer {
    double& total;
    Clock::time_point t0 = Clock::now();
    ~StepTimer() { total += seconds_since(t0); }
};

bool by_id(Vertex_handle a, Vertex_handle b) { return a->info().id < b->info().id; }

/// The crossed cells whose centre \p near accepts (all without a filter): the crease samples
/// a block of partitioned meshing checks.
std::vector<openvdb::Coord> near_cells(const octree::SampleField& field, std::vector<openvdb::Coord> cells,
                                       const CandidateFilter& near)
{
    if (!near) return cells;
    cells.erase(std::remove_if(cells.begin(), cells.end(),
                               [&](const openvdb::Coord& c) {
                                   const openvdb::Vec3d w = field.index_to_world(c.asVec3d() + openvdb::Vec3d(0.5));
                                   return !near(Point(w[0], w[1], w[2]));
                               }),
                cells.end());
    return cells;
}

bool geometric(Violation kind)
{
    return kind == Violation::Epsilon || kind == Violation::Hausdorff || kind == Violation::FacetAngle;
}

} // namespace

const Refiner::Check Refiner::kLaterChecks[4] = {&Refiner::facet_loops, &Refiner::cell_disks,
                                                 &Refiner::hausdorff_distances, &Refiner::facet_angles};

Refiner::Refiner(Delaunay& dt, const RefinerInput& in, std::vector<openvdb::Coord> crossed_cells,
                 const MeshOptions& options, MeshStats& stats, std::uint32_t next_id, Interrupter* interrupter)
    : dt_(dt), in_(in), options_(options), st_(stats), interrupter_(interrupter), next_id_(next_id),
      // Generous: the corpus's worst case (Marschner-Lobb at eps 0.1 voxel, crease cascades)
      // needs some 57 x |E|.
      max_points_(options.max_points ? options.max_points : 100 * stats.e_points + 1000000),
      // The optional facet angle refinement has its own bound: E-point clusters make graded
      // refinement, which need not reach a high angle.
      max_angle_points_(2 * stats.e_points + 10000),
      // Segment walks count unit cells: a leaf of level l spans 2^l of them per axis.
      max_cells_walk_((4 * (in.adaptive ? 27 : stats.bound_n) + 16) << (in.adaptive ? in.adaptive->max_level() : 0)),
      hash_cell_(0.25 * in.field->min_voxel_edge()), lattice_step_(lattice_step(in.field->min_voxel_edge())),
      hausdorff_(*in.field, in.eps, near_cells(*in.field, std::move(crossed_cells), in.near),
                 options.snap ? in.snap_radius : 0.0)
{
    cache_.set_far_distance(in.eps); // the eps criterion's class (FacetCache::Flagged::far)
    hausdorff_.set_filter(in.keep);
    if (in.near) {
        cache_.set_region(in.near);
        loops_.set_region(in.near);
    }
    if (in.keep) loops_.set_keep(in.keep);
    // Theorem 3 is checked, not assumed: all of G at first.
    for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v)
        if (v->info().kind == PointKind::Grid && is_near(v)) grid_pending_.push_back(v);
    for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v)
        if (v->info().on_surface() && is_near(v)) disk_pending_.push_back(v);
    std::sort(disk_pending_.begin(), disk_pending_.end(), by_id);
    auto& steps = st_.refinement_seconds;
    for (const char* k : {"grid_cells", "facet_records", "violation_scan", "facet_loops", "cell_disks", "hausdorff",
                          "creases", "insertion", "voxel_bound_n"})
        steps[k] = 0;
    if (options_.facet_angle_deg > 0) steps["facet_angle"] = 0;
}

void Refiner::log(const char* format, ...) const
{
    if (!interrupter_) return;
    char line[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(line, sizeof line, format, args);
    va_end(args);
    interrupter_->log(line);
}

void Refiner::record_voxel_bound(Vertex_handle v, int cells, bool edge_point)
{
    // A block measures its own points only: the collar's are a neighbour's, and points next to
    // the box's faces lack the points beyond it.
    if (in_.keep && !in_.keep(v->point())) return;
    int& max_cells = edge_point ? st_.max_cells_e : st_.max_cells_n;
    const int bound = edge_point ? st_.bound_e : st_.bound_n;
    if (cells < 0 || cells > bound) over_bound_.push_back(v);
    if (cells > max_cells) max_cells = cells;
}

void Refiner::measure_voxel_bound()
{
    // Theorem 2, measured in parallel; the verdicts in vertex order. N points get the N bound.
    std::vector<Vertex_handle> measured;
    // Geometry points are there before the loop only as seeds (a later run's or a merge's):
    // they are measured too.
    for (auto v = dt_.finite_vertices_begin(); v != dt_.finite_vertices_end(); ++v)
        if (v->info().kind == PointKind::Edge || v->info().kind == PointKind::Topology ||
            v->info().kind == PointKind::Snapped || v->info().kind == PointKind::Geometry)
            measured.push_back(v);
    const std::vector<int> counts = voronoi_cell_counts(dt_, measured, *in_.field, in_.leaves);
    for (std::size_t i = 0; i < measured.size(); ++i)
        record_voxel_bound(measured[i], counts[i], measured[i]->info().kind == PointKind::Edge);
}

void Refiner::repair_bound_holes()
{
    StepTimer timer{st_.refinement_seconds["insertion"]};
    std::sort(over_bound_.begin(), over_bound_.end(), by_id);
    over_bound_.erase(std::unique(over_bound_.begin(), over_bound_.end()), over_bound_.end());
    std::vector<Point> add;
    auto acc = in_.g_mask->get().getAccessor();
    const auto& r = in_.layer_radius;
    for (const auto& v : over_bound_) {
        const auto q = in_.field->world_to_index({v->point().x(), v->point().y(), v->point().z()});
        const openvdb::Coord c(int(std::floor(q[0])), int(std::floor(q[1])), int(std::floor(q[2])));
        for (int z = c.z() - r[2]; z <= c.z() + 1 + r[2]; ++z)
            for (int y = c.y() - r[1]; y <= c.y() + 1 + r[1]; ++y)
                for (int x = c.x() - r[0]; x <= c.x() + 1 + r[0]; ++x) {
                    const openvdb::Coord g(x, y, z);
                    if (acc.isValueOn(g)) continue;
                    acc.setValueOn(g);
                    const openvdb::Vec3d w = in_.field->index_to_world(g.asVec3d());
                    add.emplace_back(w[0], w[1], w[2]);
                }
    }
    st_.bound_repairs += add.size();
    for (const Point& p : add) {
        const Vertex_handle v = cache_.insert(dt_, p, VertexInfo{next_id_, PointKind::Grid});
        if (v == Vertex_handle()) continue;
        ++next_id_;
        grid_pending_.push_back(v);
        loops_.touched(v);
    }
    over_bound_.clear();
}

InsertionResult Refiner::insert_batch(const std::vector<Candidate>& candidates, Violation kind)
{
    auto& steps = st_.refinement_seconds;
    InsertionResult ins;
    {
        StepTimer timer{steps["insertion"]};
        // Every candidate on the point lattice (geometry/point_lattice.h) before it is placed.
        std::vector<Candidate> placed = candidates;
        for (Candidate& c : placed) c.p = on_lattice(c.p, lattice_step_);
        ins = insert_candidates(dt_, cache_, std::move(placed), next_id_, hash_cell_);
    }
    std::vector<int> counts;
    {
        StepTimer timer{steps["voxel_bound_n"]};
        counts = voronoi_cell_counts(dt_, ins.inserted, *in_.field, in_.leaves);
    }
    // The new vertices go to the later checks: the loop scanner, the disk certificates, the
    // point counts and the voxel bound (Theorem 2, the N bound).
    for (std::size_t i = 0; i < ins.inserted.size(); ++i) {
        const Vertex_handle v = ins.inserted[i];
        loops_.touched(v);
        disk_pending_.push_back(v);
        if (kind == Violation::FacetAngle) ++st_.n_facet_angle;
        ++(geometric(kind) ? st_.n_geometry : st_.n_topology);
        record_voxel_bound(v, counts[i], false);
    }
    return ins;
}

std::size_t Refiner::insert_received(const std::vector<std::pair<Point, PointKind>>& points)
{
    StepTimer timer{st_.refinement_seconds["insertion"]};
    std::size_t added = 0;
    auto acc = in_.g_mask->get().getAccessor();
    // The deferred grid points are checked again: the neighbours' points may have fixed them.
    grid_pending_.insert(grid_pending_.end(), grid_deferred_.begin(), grid_deferred_.end());
    grid_deferred_.clear();
    for (const auto& [p, kind] : points) {
        const Vertex_handle v = cache_.insert(dt_, p, VertexInfo{next_id_, kind});
        if (v == Vertex_handle()) continue;
        ++next_id_;
        ++added;
        loops_.touched(v);
        if (kind == PointKind::Grid) {
            // A neighbour's voxel-bound repair: Theorem 3 is checked for it here too.
            const auto q = in_.field->world_to_index({p.x(), p.y(), p.z()});
            acc.setValueOn(openvdb::Coord(int(std::lround(q[0])), int(std::lround(q[1])), int(std::lround(q[2]))));
            if (is_near(v)) grid_pending_.push_back(v);
        } else if (is_near(v)) {
            disk_pending_.push_back(v);
        }
    }
    return added;
}

std::vector<const FacetCache::Entry*> Refiner::restricted_facets() const
{
    std::vector<const FacetCache::Entry*> restricted;
    for (const auto& e : cache_.active())
        if (e.crossings == 1) restricted.push_back(&e); // the cache holds the near facets only
    return restricted;
}

std::vector<Candidate> Refiner::grid_cell_candidates()
{
    std::vector<Candidate> found = grid_cell_violations(dt_, *in_.field, grid_pending_, max_cells_walk_);
    if (!in_.keep) return found;
    // A violation whose point is another block's waits, off the pending list, until points come
    // in from the neighbours (insert_received): its Voronoi cell changes only then, or by this
    // block's own points, which cannot fix it (it is not theirs to fix).
    std::vector<Candidate> kept;
    std::vector<Vertex_handle> still;
    for (std::size_t i = 0; i < found.size(); ++i) {
        if (in_.keep(found[i].p)) {
            kept.push_back(found[i]);
            still.push_back(grid_pending_[i]);
        } else {
            grid_deferred_.push_back(grid_pending_[i]);
        }
    }
    grid_pending_.swap(still);
    return kept;
}

ViolationReport Refiner::grid_cells_and_facets(double& update_seconds)
{
    const auto t0 = Clock::now();
    auto& steps = st_.refinement_seconds;
    ViolationReport rep;
    // Theorem 3 (grid cells) first, before the facet table's first scan: these rounds insert
    // most of N, and with the table in place each round would recompute the records of every
    // facet they made. A grid cell's check reads no record, and its segment walks have their
    // own bound, so voxel-bound holes can wait.
    if (!cache_.scanned()) {
        StepTimer timer{steps["grid_cells"]};
        rep.candidates = grid_cell_candidates();
    }
    if (rep.candidates.empty()) {
        bool unbounded;
        {
            StepTimer timer{steps["facet_records"]};
            cache_.update(dt_, *in_.field, max_cells_walk_);
            unbounded = !cache_.flagged().overflow.empty();
        }
        update_seconds = seconds_since(t0);
        // Then: voxel-bound holes, Theorem 3 again, the ViolationFinder's classes.
        StepTimer timer{steps["grid_cells"]};
        if (!unbounded) rep.candidates = grid_cell_candidates();
    }
    if (!rep.candidates.empty()) {
        rep.kind = Violation::GridCell;
        return rep;
    }
    StepTimer timer{steps["violation_scan"]};
    return violations_.find(cache_, in_.keep);
}

ViolationReport Refiner::facet_loops()
{
    // Loops inside Voronoi facets (CBP_VF, second clause).
    const auto t0 = Clock::now();
    ViolationReport rep;
    rep.candidates = loops_.scan(dt_, *in_.field, max_cells_walk_);
    st_.refinement_seconds["facet_loops"] += seconds_since(t0);
    log("  loops %.2f ms", 1e3 * seconds_since(t0));
    filter_candidates(rep.candidates, in_.keep);
    if (!rep.candidates.empty()) rep.kind = Violation::FacetLoop;
    return rep;
}

ViolationReport Refiner::cell_disks()
{
    // CBP_VC's last clause: no handle inside one Voronoi cell.
    const auto t0 = Clock::now();
    ViolationReport rep;
    VoronoiCellDiskStats ds;
    rep.candidates = voronoi_cell_disk_violations(dt_, *in_.field, disk_pending_, in_.slab_h_world, &ds);
    st_.refinement_seconds["cell_disks"] += seconds_since(t0);
    log("  disks %.2f ms: %zu certified, %zu by chi, %zu unresolved, %zu violated, %zu directions",
        1e3 * seconds_since(t0), ds.certified, ds.sampled, ds.unresolved, rep.candidates.size(), ds.directions);
    filter_candidates(rep.candidates, in_.keep);
    if (!rep.candidates.empty()) rep.kind = Violation::VoronoiCellDisk;
    return rep;
}

ViolationReport Refiner::hausdorff_distances()
{
    auto& steps = st_.refinement_seconds;
    const auto t0 = Clock::now();
    ViolationReport rep;
    const std::vector<const FacetCache::Entry*> restricted = restricted_facets();
    rep.candidates = hausdorff_.violations(restricted);
    steps["hausdorff"] += seconds_since(t0);
    log("  hausdorff %.2f ms", 1e3 * seconds_since(t0));
    filter_candidates(rep.candidates, in_.keep);
    if (rep.candidates.empty()) {
        const auto tc = Clock::now();
        rep.candidates = hausdorff_.crease_violations(restricted);
        steps["creases"] += seconds_since(tc);
        log("  crease %.2f ms", 1e3 * seconds_since(tc));
        filter_candidates(rep.candidates, in_.keep);
    }
    if (!rep.candidates.empty()) rep.kind = Violation::Hausdorff;
    return rep;
}

ViolationReport Refiner::facet_angles()
{
    ViolationReport rep;
    if (options_.facet_angle_deg <= 0 || st_.facet_angle_stop != FacetAngleStop::Off) return rep;
    StepTimer timer{st_.refinement_seconds["facet_angle"]};
    // Optional triangle quality, last: every guarantee holds here, so stopping it at its bound
    // leaves a certified mesh (facet_angle_stop says why it stopped).
    rep.candidates = facet_angle_violations(restricted_facets(), options_.facet_angle_deg, in_.keep);
    if (rep.candidates.empty()) st_.facet_angle_stop = FacetAngleStop::Met;
    else if (st_.n_facet_angle >= max_angle_points_) st_.facet_angle_stop = FacetAngleStop::PointBound;
    else rep.kind = Violation::FacetAngle;
    if (rep.kind == Violation::None) rep.candidates.clear();
    return rep;
}

std::size_t Refiner::follow_voronoi_edge_cascade()
{
    // Splitting a Voronoi edge makes new Voronoi edges next to the new point, which may cross
    // Sigma twice again (near creases, one at a time for many rounds). Following the cascade on
    // the facets the insertions changed (FacetCache::recent) costs O(changes) a step instead of a
    // full round's O(|active facets|); the next full round checks everything again. Bounded by
    // the point bound.
    auto& steps = st_.refinement_seconds;
    std::size_t cascade = 0;
    while (over_bound_.empty() && st_.n_geometry + st_.n_topology <= max_points_) {
        {
            StepTimer timer{steps["facet_records"]};
            cache_.update(dt_, *in_.field, max_cells_walk_);
        }
        std::vector<Candidate> more;
        {
            StepTimer timer{steps["violation_scan"]};
            more = voronoi_edge_violations(cache_.recent(), in_.keep);
        }
        if (more.empty()) break;
        const InsertionResult next = insert_batch(more, Violation::VoronoiEdge);
        if (next.inserted.empty()) break;
        cascade += next.inserted.size();
        if (interrupter_ && interrupter_->wasInterrupted()) throw Cancelled("interrupted");
    }
    return cascade;
}

bool Refiner::run(bool stop_without_progress)
{
    auto& steps = st_.refinement_seconds;
    double t_topology = 0, t_refine = 0;
    bool certified = true;
    InterruptScope scope(interrupter_, "closed_ball");
    for (;;) {
        const auto tr = Clock::now();
        if (!over_bound_.empty()) repair_bound_holes();
        if (++st_.rounds > options_.max_rounds) {
            std::ostringstream os;
            os << "refinement stopped by the round bound (--max-rounds " << options_.max_rounds
               << "): guarantees not certified";
            throw GuaranteeViolated(os.str());
        }
        double t_update = 0;
        ViolationReport rep = grid_cells_and_facets(t_update);
        log("round %d: %s x%zu active=%zu computed=%zu", st_.rounds, to_string(rep.kind), rep.candidates.size(),
            cache_.active_count(), cache_.computed_last_update());
        for (const Check check : kLaterChecks) {
            if (rep.kind != Violation::None) break;
            scope.check(); // each check may scan every restricted facet
            rep = (this->*check)();
        }
        if (rep.kind == Violation::None) {
            t_refine += seconds_since(tr); // the last round: every check passed
            break;
        }
        if (rep.kind == Violation::Unbounded) {
            // Surface facets whose Voronoi edge left the bound: repair around their vertices.
            for (const auto& e : cache_.active())
                if (e.overflow)
                    for (const auto& v : facet_vertices(e.facet))
                        if (v->info().on_surface() && (!in_.keep || in_.keep(v->point()))) over_bound_.push_back(v);
            if (st_.bound_repairs > 10 * st_.g_points + 1000)
                throw GuaranteeViolated("voxel bound repairs did not converge (bound: 10 |G| + 1000 grid points)");
            t_topology += seconds_since(tr);
            continue;
        }
        const double t_checks = seconds_since(tr) - t_update;
        const double insertion_before = steps["insertion"];
        scope.check();
        const InsertionResult ins = insert_batch(rep.candidates, rep.kind);
        const double t_insert = steps["insertion"] - insertion_before;
        const std::size_t cascade = rep.kind == Violation::VoronoiEdge ? follow_voronoi_edge_cascade() : 0;
        (geometric(rep.kind) ? t_refine : t_topology) += seconds_since(tr);
        log("round %d: %s %zu inserted (+%zu cascade), %.2f ms (update %.2f, checks %.2f, insert %.2f)", st_.rounds,
            to_string(rep.kind), ins.inserted.size(), cascade, 1e3 * seconds_since(tr), 1e3 * t_update, 1e3 * t_checks,
            1e3 * t_insert);
        if (st_.n_geometry + st_.n_topology > max_points_) {
            std::ostringstream os;
            os << "refinement stopped by the point bound (" << max_points_ << " inserted points) while fixing "
               << to_string(rep.kind) << ": guarantees not certified";
            throw GuaranteeViolated(os.str());
        }
        // A block sees its neighbours' points only through the exchange: a violation next to
        // its seam may wait for them (partitioned_meshing.h).
        if (ins.inserted.empty() && stop_without_progress) {
            certified = false;
            break;
        }
        if (ins.inserted.empty() && rep.kind == Violation::FacetAngle) {
            st_.facet_angle_stop = FacetAngleStop::NoProgress; // its candidates are vertices already
            continue;
        }
        if (ins.inserted.empty()) {
            std::ostringstream os;
            os << "no progress fixing " << to_string(rep.kind) << " (" << rep.candidates.size()
               << " violations, all candidates already vertices)";
            throw GuaranteeViolated(os.str());
        }
        scope.check();
    }
    st_.seconds["closed_ball"] = t_topology;
    st_.seconds["refine"] = t_refine;
    return certified;
}

} // namespace isodel::mesher
