// DELSURFMESH (paper Fig. 3), the data flow visible top-down:
//   samples --edge_crossings--> E,  crossed cells --protective_layer--> G,
//   Del(E u G) --closed ball (VE, grid vertex, VF, VC, VF loops)--> --eps refinement--> Del(E u G u N)|Sigma.
// On an adaptive grid the same flow runs with E on leaf edges and G from the leaves
// (adaptive_points.h), F read through the grid's exact resampling. Steps 1-2 are
// initial_points.cpp; the public entry points (and --certify) are mesh_isosurface.cpp.
#include "mesher/closed_ball.h"
#include "mesher/delaunay.h"
#include "mesher/facet_loops.h"
#include "mesher/grid_cell_check.h"
#include "mesher/hausdorff_refinement.h"
#include "mesher/initial_delaunay.h"
#include "mesher/initial_points.h"
#include "mesher/mesh_field.h"
#include "mesher/point_insertion.h"
#include "mesher/restricted_facets.h"
#include "mesher/surface_extraction.h"
#include "mesher/volume_mesh.h"
#include "mesher/voronoi_cell_disks.h"
#include "mesher/voxel_bound.h"
#include "octree/protective_layer.h"
#include "octree/sample_field.h"

#include <isodel/errors.h>
#include <isodel/mesh.h>

#include <tbb/global_control.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>

namespace isodel {
using namespace mesher;
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Adds the seconds of its scope to \p total (MeshStats::refinement_seconds).
struct StepTimer {
    double& total;
    Clock::time_point t0 = Clock::now();
    ~StepTimer() { total += since(t0); }
};

std::size_t peak_memory_bytes()
{
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return std::size_t(ru.ru_maxrss) * 1024;
}

mesher::Point to_point(const openvdb::Vec3d& p) { return {p[0], p[1], p[2]}; }

} // namespace

namespace mesher {

Inside inside_side(const openvdb::FloatGrid& grid, const MeshOptions& options)
{
    if (options.inside) return *options.inside;
    return grid.getGridClass() == openvdb::GRID_LEVEL_SET ? Inside::Below : Inside::Above;
}

MeshResult mesh_field(const FieldRun& run, const MeshOptions& options, Interrupter* interrupter)
{
    const auto t_start = Clock::now();
    MeshResult result;
    MeshStats& st = result.stats;

    if (!(options.eps >= 0) || !(options.eps_voxels > 0) || !std::isfinite(options.eps))
        throw InvalidInput("eps must be positive and finite");
    std::unique_ptr<tbb::global_control> threads;
    if (options.threads > 0)
        threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        std::size_t(options.threads));

    const octree::AdaptiveGrid* adaptive = run.adaptive;
    st.effective_isovalue = run.field->effective_isovalue();
    std::unique_ptr<octree::AdaptiveGrid::Reader> leaves;
    if (adaptive) leaves = std::make_unique<octree::AdaptiveGrid::Reader>(*adaptive);
    const double eps_user = options.eps > 0 ? options.eps : options.eps_voxels * run.field->min_voxel_edge();
    st.eps_world = eps_user;
    // The surface meshed is Sigma' (octree/face_slabs.h): slabs of half-width h = eps/50 around
    // the grid planes blunt the knife-edge creases, and M within eps - slab_shift of Sigma'
    // keeps Sigma within eps of M (slab_shift <= 0.035 eps).
    octree::SampleField field = *run.field;
    field.set_face_slabs(field.face_slabs_for_eps_world(eps_user));
    const octree::FaceSlabs& slabs = field.face_slabs();
    const double slab_shift = field.face_slab_shift();
    const double eps = eps_user - slab_shift;
    const double snap_radius = options.snap ? 0.5 * eps : 0.0; // snap_edge_points.h: eps / 2

    // Steps 1-2: E and G (initial_points.h).
    auto t0 = Clock::now();
    InitialPoints ip = initial_points(field, adaptive, leaves.get(), options.snap, snap_radius, run.seeds, st, interrupter);
    std::vector<std::pair<Point, VertexInfo>>& initial = ip.points;
    octree::ProtectiveLayer& layer = ip.layer;
    std::vector<openvdb::Coord>& crossed_cells = ip.crossed_cells;
    std::unique_ptr<openvdb::MaskGrid> g_mask = std::move(ip.g_mask);
    st.seconds["points"] = since(t0);
    if (st.e_points == 0 && run.inserted) return result; // a block Sigma misses
    if (st.e_points == 0) throw InvalidInput("the level set is empty: no grid edge crosses the isovalue");

    // Step 3: Del(E u G), spatially sorted insertion.
    t0 = Clock::now();
    Delaunay dt;
    {
        InterruptScope scope(interrupter, "delaunay");
        build_initial_delaunay(dt, initial);
        scope.check(100);
    }
    std::uint32_t next_id = std::uint32_t(initial.size());
    const std::uint32_t first_inserted = next_id;
    initial.clear();
    initial.shrink_to_fit();
    st.seconds["delaunay"] = since(t0);

    // Theorem 2, measured: cells met by the Voronoi cells of E points (and of N points, which
    // get the N bound), in parallel; the verdicts in vertex order.
    auto record = [&](Vertex_handle v, int n, int& max_cells, int bound, std::vector<Vertex_handle>& over) {
        if (n < 0 || n > bound) over.push_back(v);
        if (n > max_cells) max_cells = n;
    };
    std::vector<Vertex_handle> over_bound;
    const auto t_measure = Clock::now();
    {
        std::vector<Vertex_handle> measured;
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
            if (v->info().kind == PointKind::Edge || v->info().kind == PointKind::Topology ||
                v->info().kind == PointKind::Snapped)
                measured.push_back(v);
        const std::vector<int> counts = voronoi_cell_counts(dt, measured, field, leaves.get());
        for (std::size_t i = 0; i < measured.size(); ++i)
            if (measured[i]->info().kind == PointKind::Edge)
                record(measured[i], counts[i], st.max_cells_e, st.bound_e, over_bound);
            else record(measured[i], counts[i], st.max_cells_n, st.bound_n, over_bound);
    }
    st.seconds["voxel_bound"] = since(t_measure);
    // Grid points whose Voronoi cell may meet Sigma (Theorem 3, checked): all of G at first.
    std::vector<Vertex_handle> grid_pending;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        if (v->info().kind == PointKind::Grid) grid_pending.push_back(v);
    // Surface vertices whose Voronoi cell is not yet certified to meet Sigma in a disk.
    std::vector<Vertex_handle> disk_pending;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        if (v->info().on_surface()) disk_pending.push_back(v);
    std::sort(disk_pending.begin(), disk_pending.end(),
              [](Vertex_handle a, Vertex_handle b) { return a->info().id < b->info().id; });

    // A Voronoi cell that leaves its bound is a hole in G: add the grid points of the trap block
    // around the point's cell, never search further.
    auto repair = [&](const std::vector<Vertex_handle>& verts) {
        std::vector<Point> add;
        auto acc = g_mask->getAccessor();
        const auto& r = layer.radius;
        for (const auto& v : verts) {
            const auto q = field.world_to_index({v->point().x(), v->point().y(), v->point().z()});
            const openvdb::Coord c(int(std::floor(q[0])), int(std::floor(q[1])), int(std::floor(q[2])));
            for (int z = c.z() - r[2]; z <= c.z() + 1 + r[2]; ++z)
                for (int y = c.y() - r[1]; y <= c.y() + 1 + r[1]; ++y)
                    for (int x = c.x() - r[0]; x <= c.x() + 1 + r[0]; ++x) {
                        const openvdb::Coord g(x, y, z);
                        if (acc.isValueOn(g)) continue;
                        acc.setValueOn(g);
                        add.push_back(to_point(field.index_to_world(g.asVec3d())));
                    }
        }
        return add;
    };

    // Steps 4-5: closed ball property, then eps refinement, one violation class per round.
    t0 = Clock::now();
    const std::size_t max_points =
        // Generous: Marschner-Lobb at eps 0.1 voxel needs 849600 = 57 x |E| (crease cascades).
        options.max_points ? options.max_points : 100 * st.e_points + 1000000;
    // Segment walks count unit cells: a leaf of level l spans 2^l of them per axis.
    const int max_cells_walk = (4 * (adaptive ? 27 : st.bound_n) + 16) << (adaptive ? adaptive->max_level() : 0);
    const double hash_cell = 0.25 * field.min_voxel_edge();
    FacetCache cache;
    cache.set_far_distance(eps); // the eps criterion's class (FacetCache::Flagged::far)
    // A snapped grid point is within snap_radius of Sigma, and Sigma' within slab_shift of it.
    HausdorffRefinement hausdorff(field, eps, std::move(crossed_cells), options.snap ? snap_radius + slab_shift : 0.0);
    hausdorff.set_filter(run.keep);
    FacetLoopScanner loops;
    ViolationFinder violations;
    // Optional facet angle refinement: its own bound (E-point clusters make graded refinement).
    const std::size_t max_angle_points = 2 * st.e_points + 10000;
    double t_topology = 0, t_refine = 0;
    auto& steps = st.refinement_seconds;
    for (const char* k : {"grid_cells", "facet_records", "violation_scan", "facet_loops", "cell_disks", "hausdorff",
                          "creases", "insertion", "voxel_bound_n"})
        steps[k] = 0;
    if (options.facet_angle_deg > 0) steps["facet_angle"] = 0;
    const std::size_t n_before_loops = st.n_topology + st.n_geometry;
    // Inserts one class's candidates and hands the new vertices to the later checks: the loop
    // scanner, the disk certificates, the point counts and the voxel bound (Theorem 2).
    auto insert_batch = [&](const std::vector<Candidate>& candidates, Violation kind) {
        InsertionResult ins;
        {
            StepTimer timer{steps["insertion"]};
            ins = insert_candidates(dt, cache, candidates, next_id, hash_cell);
        }
        std::vector<int> counts;
        {
            StepTimer timer{steps["voxel_bound_n"]};
            counts = voronoi_cell_counts(dt, ins.inserted, field, leaves.get());
        }
        const bool geometric = kind == Violation::Epsilon || kind == Violation::Hausdorff || kind == Violation::FacetAngle;
        for (std::size_t i = 0; i < ins.inserted.size(); ++i) {
            const Vertex_handle v = ins.inserted[i];
            loops.touched(v);
            disk_pending.push_back(v);
            if (kind == Violation::FacetAngle) ++st.n_facet_angle;
            ++(geometric ? st.n_geometry : st.n_topology);
            record(v, counts[i], st.max_cells_n, st.bound_n, over_bound);
        }
        return ins;
    };
    {
        InterruptScope scope(interrupter, "closed_ball");
        for (;;) {
            const auto tr = Clock::now();
            if (!over_bound.empty()) {
                // Grid points where the last round found a Voronoi cell out of its bound.
                StepTimer timer{steps["insertion"]};
                std::sort(over_bound.begin(), over_bound.end(),
                          [](Vertex_handle a, Vertex_handle b) { return a->info().id < b->info().id; });
                over_bound.erase(std::unique(over_bound.begin(), over_bound.end()), over_bound.end());
                const auto add = repair(over_bound);
                st.bound_repairs += add.size();
                for (const Point& p : add) {
                    const Vertex_handle v = cache.insert(dt, p, VertexInfo{next_id, PointKind::Grid});
                    if (v == Vertex_handle()) continue;
                    ++next_id;
                    grid_pending.push_back(v);
                    loops.touched(v);
                }
                over_bound.clear();
            }
            if (++st.rounds > options.max_rounds) {
                std::ostringstream os;
                os << "refinement stopped by the round bound (--max-rounds " << options.max_rounds
                   << "): guarantees not certified";
                throw GuaranteeViolated(os.str());
            }
            ViolationReport rep;
            double t_update = 0;
            // Theorem 3 (grid cells) first, before the facet table's first scan: these rounds
            // insert most of N (80 k of the 85 k topology points of a 128^3 protein), and with
            // the table in place each round recomputed the records of every facet they made:
            // 4.9 M records, then 2.9 M in one scan after them. A grid cell's check reads no
            // record, and its segment walks have their own bound, so voxel-bound holes can wait.
            if (!cache.scanned()) {
                StepTimer timer{steps["grid_cells"]};
                rep.candidates = grid_cell_violations(dt, field, grid_pending, max_cells_walk);
                filter_candidates(rep.candidates, run.keep);
            }
            if (rep.candidates.empty()) {
                bool unbounded;
                {
                    StepTimer timer{steps["facet_records"]};
                    cache.update(dt, field, max_cells_walk);
                    unbounded = !cache.flagged().overflow.empty();
                }
                t_update = since(tr);
                // Then: voxel-bound holes, Theorem 3 again, the ViolationFinder's classes; the
                // later checks run only when the earlier ones found nothing.
                StepTimer timer{steps["grid_cells"]};
                if (!unbounded) rep.candidates = grid_cell_violations(dt, field, grid_pending, max_cells_walk);
                filter_candidates(rep.candidates, run.keep);
            }
            if (!rep.candidates.empty()) {
                rep.kind = Violation::GridCell;
            } else {
                StepTimer timer{steps["violation_scan"]};
                rep = violations.find(cache, run.keep);
            }
            if (std::getenv("ISODEL_TRACE"))
                std::fprintf(stderr, "round %d: %s x%zu active=%zu computed=%zu\n", st.rounds,
                             to_string(rep.kind), rep.candidates.size(), cache.active_count(),
                             cache.computed_last_update());
            if (rep.kind == Violation::None) {
                // Loops inside Voronoi facets (CBP_VF, second clause): once the cheaper checks pass.
                const auto tl = Clock::now();
                rep.candidates = loops.scan(dt, field, max_cells_walk);
                steps["facet_loops"] += since(tl);
                if (std::getenv("ISODEL_TRACE")) std::fprintf(stderr, "  loops %.2f ms\n", 1e3 * since(tl));
                filter_candidates(rep.candidates, run.keep);
                if (!rep.candidates.empty()) rep.kind = Violation::FacetLoop;
            }
            if (rep.kind == Violation::None) {
                // CBP_VC's last clause: no handle inside one Voronoi cell (voronoi_cell_disks.h).
                const auto td = Clock::now();
                VoronoiCellDiskStats ds;
                rep.candidates = voronoi_cell_disk_violations(dt, field, disk_pending, slabs.h * field.min_voxel_edge(), &ds);
                steps["cell_disks"] += since(td);
                if (std::getenv("ISODEL_TRACE"))
                    std::fprintf(stderr, "  disks %.2f ms: %zu certified, %zu by chi, %zu unresolved, %zu violated\n",
                                 1e3 * since(td), ds.certified, ds.sampled, ds.unresolved, rep.candidates.size());
                filter_candidates(rep.candidates, run.keep);
                if (!rep.candidates.empty()) rep.kind = Violation::VoronoiCellDisk;
            }
            if (rep.kind == Violation::None) {
                const auto th = Clock::now();
                std::vector<const FacetCache::Entry*> restricted;
                for (const auto& e : cache.active())
                    if (e.crossings == 1) restricted.push_back(&e);
                rep.candidates = hausdorff.violations(restricted);
                steps["hausdorff"] += since(th);
                if (std::getenv("ISODEL_TRACE")) std::fprintf(stderr, "  hausdorff %.2f ms\n", 1e3 * since(th));
                filter_candidates(rep.candidates, run.keep);
                if (rep.candidates.empty()) {
                    const auto tc = Clock::now();
                    rep.candidates = hausdorff.crease_violations(restricted);
                    steps["creases"] += since(tc);
                    if (std::getenv("ISODEL_TRACE")) std::fprintf(stderr, "  crease %.2f ms\n", 1e3 * since(tc));
                    filter_candidates(rep.candidates, run.keep);
                }
                if (!rep.candidates.empty()) rep.kind = Violation::Hausdorff;
            }
            if (rep.kind == Violation::None && options.facet_angle_deg > 0 && st.facet_angle_stop.empty()) {
                StepTimer timer{steps["facet_angle"]};
                // Optional triangle quality, last: every guarantee holds here, so stopping it at
                // its bound leaves a certified mesh (facet_angle_stop says why it stopped).
                std::vector<const FacetCache::Entry*> restricted;
                for (const auto& e : cache.active())
                    if (e.crossings == 1) restricted.push_back(&e);
                rep.candidates = facet_angle_violations(restricted, options.facet_angle_deg, run.keep);
                if (rep.candidates.empty()) st.facet_angle_stop = "met";
                else if (st.n_facet_angle >= max_angle_points) st.facet_angle_stop = "point bound";
                else rep.kind = Violation::FacetAngle;
            }
            if (rep.kind == Violation::None) {
                t_refine += since(tr); // the last round: every check passed
                break;
            }
            if (rep.kind == Violation::Unbounded) {
                // Surface facets whose Voronoi edge left the bound: repair around their vertices.
                for (const auto& e : cache.active())
                    if (e.overflow)
                        for (const auto& v : facet_vertices(e.facet))
                            if (v->info().on_surface()) over_bound.push_back(v);
                if (st.bound_repairs > 10 * st.g_points + 1000)
                    throw GuaranteeViolated("voxel bound repairs did not converge");
                t_topology += since(tr);
                continue;
            }
            const double t_checks = since(tr) - t_update;
            const double insertion_before = steps["insertion"];
            const InsertionResult ins = insert_batch(rep.candidates, rep.kind);
            const double t_insert = steps["insertion"] - insertion_before;
            // CBP_VE cascades are local: splitting a Voronoi edge makes new Voronoi edges next
            // to the new point, which may cross Sigma twice again (near creases, one at a time
            // for hundreds of rounds). Follow the cascade on the facets the insertions changed
            // (FacetCache::recent) instead of paying a full round, O(|active facets|), per step;
            // the next full round re-checks everything. Bounded by the point bound.
            std::size_t cascade = 0;
            while (rep.kind == Violation::VoronoiEdge && over_bound.empty() &&
                   st.n_geometry + st.n_topology <= max_points) {
                {
                    StepTimer timer{steps["facet_records"]};
                    cache.update(dt, field, max_cells_walk);
                }
                std::vector<Candidate> more;
                {
                    StepTimer timer{steps["violation_scan"]};
                    more = voronoi_edge_violations(cache.recent(), run.keep);
                }
                if (more.empty()) break;
                const InsertionResult next = insert_batch(more, Violation::VoronoiEdge);
                if (next.inserted.empty()) break;
                cascade += next.inserted.size();
                scope.check();
            }
            (rep.kind == Violation::Epsilon || rep.kind == Violation::Hausdorff || rep.kind == Violation::FacetAngle
                 ? t_refine
                 : t_topology) += since(tr);
            if (std::getenv("ISODEL_TRACE"))
                std::fprintf(stderr, "round %d: %s %zu inserted (+%zu cascade), %.2f ms (update %.2f, checks %.2f, insert %.2f)\n",
                             st.rounds, to_string(rep.kind), ins.inserted.size(), cascade, 1e3 * since(tr),
                             1e3 * t_update, 1e3 * t_checks, 1e3 * t_insert);
            if (st.n_geometry + st.n_topology > max_points) {
                std::ostringstream os;
                os << "refinement stopped by the point bound (" << max_points
                   << " inserted points) while fixing " << to_string(rep.kind) << ": guarantees not certified";
                throw GuaranteeViolated(os.str());
            }
            // A block (partitioned meshing) stops here: near its keep boundary some violations
            // are a neighbour's, and the candidates left may be vertices already; the merge's
            // own loop checks everything again.
            if (ins.inserted.empty() && run.inserted) break;
            if (ins.inserted.empty() && rep.kind == Violation::FacetAngle) {
                st.facet_angle_stop = "no progress"; // its candidates are vertices already
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
    }
    st.seconds["closed_ball"] = t_topology;
    st.seconds["refine"] = t_refine;
    if (!run.seeds.empty()) st.partition.seam_points = st.n_topology + st.n_geometry - n_before_loops;
    if (run.inserted) {
        std::vector<std::pair<std::uint32_t, SeedPoint>> n;
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
            const PointKind k = v->info().kind;
            if (v->info().id >= first_inserted && (k == PointKind::Topology || k == PointKind::Geometry))
                n.push_back({v->info().id, SeedPoint{{v->point().x(), v->point().y(), v->point().z()}, k}});
        }
        std::sort(n.begin(), n.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& [id, p] : n) run.inserted->push_back(p);
        st.seconds["total"] = since(t_start);
        return result;
    }

    const auto t_extract = Clock::now();
    result.surface = extract_surface(dt, cache);
    if (options.keep_points) {
        std::vector<std::pair<std::uint32_t, Point>> all;
        all.reserve(dt.number_of_vertices());
        for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) all.emplace_back(v->info().id, v->point());
        std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        result.points.reserve(all.size());
        for (const auto& [id, p] : all) result.points.push_back({p.x(), p.y(), p.z()});
    }
    st.vertices = result.surface.vertices.size();
    st.triangles = result.surface.triangles.size();
    st.components = surface_topology(result.surface);
    st.seconds["extract"] = since(t_extract);
    if (options.tets != TetRegion::None) {
        // DELVOLMESH (Section 4.1): fill the region(s) with G', keeping M (src/mesher/volume_mesh.h).
        t0 = Clock::now();
        VolumeMeshParams vp;
        vp.region = options.tets;
        vp.max_cells_walk = max_cells_walk;
        vp.next_id = &next_id;
        vp.interrupter = interrupter;
        vp.adaptive = leaves.get();
        vp.improve = options.improve_tets;
        result.tets = build_volume_mesh(dt, cache, field, *g_mask, result.surface, vp, st.tets);
        st.seconds["tets"] = since(t0);
    }
    st.seconds["total"] = since(t_start);
    st.peak_memory_bytes = peak_memory_bytes();
    return result;
}

} // namespace mesher
} // namespace isodel
