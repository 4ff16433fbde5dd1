// The public entry points of DELSURFMESH (include/isodel/mesh.h): a dense or adaptive volume
// in, read as a SampleField; the run itself is mesh_field (mesh_field.cpp), or partitioned
// meshing's blocks and merge (partitioned_meshing.h); with MeshOptions::certify the surface is
// verified before it is returned.
#include "surface/stage_clock.h"
#include "surface/thread_limit.h"
#include "surface/final_points.h"
#include "surface/mesh_field.h"
#include "surface/partitioned_meshing.h"
#include "seeding/adaptive_points.h"
#include "octree/edge_crossings.h"
#include "octree/adaptive_vdb_format.h"
#include "octree/certified_coarsening.h"
#include "octree/seed_octree.h"
#include "octree/extended_level_set.h"
#include "octree/resample.h"
#include "octree/sample_field.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>
#include <isodel/mesh.h>
#include <isodel/verify.h>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>

namespace isodel {
using namespace mesher;
namespace {

using Clock = std::chrono::steady_clock;

MeshResult mesh_once(const octree::SampleField& field, const octree::AdaptiveGrid* adaptive,
                     const MeshOptions& options, Interrupter* interrupter, std::vector<std::array<double, 3>>* points)
{
    if (options.block_voxels > 0 || options.block_count > 0) {
        if (adaptive) throw InvalidInput("partitioned meshing (block_voxels, block_count) is for dense grids only");
        if (points)
            throw InvalidInput("partitioned meshing (block_voxels, block_count) does not keep the final point set");
        return mesh_partitioned(field, options, interrupter);
    }
    FieldRun run;
    run.field = &field;
    run.adaptive = adaptive;
    run.final_points = points;
    return mesh_field(run, options, interrupter);
}

/// Why \p r failed verification, in a few words.
std::string verify_failure(const VerifyReport& r)
{
    std::ostringstream os;
    auto genera = [](const auto& comps) {
        std::ostringstream g;
        g << comps.size() << " components, genus [";
        for (std::size_t i = 0; i < comps.size() && i < 8; ++i) g << (i ? " " : "") << comps[i].genus;
        g << (comps.size() > 8 ? " ...]" : "]");
        return g.str();
    };
    if (!r.mesh_ok()) os << "not a closed oriented manifold without self-intersections; ";
    if (!r.topology_ok()) os << "M has " << genera(r.mesh.components) << ", Sigma " << genera(r.reference.components) << "; ";
    if (!r.hausdorff_ok()) os << "Hausdorff " << std::max(r.hausdorff.mesh_to_surface.max_voxels, r.hausdorff.surface_to_mesh.max_voxels)
                              << " voxel > eps; ";
    if (!r.delaunay_ok()) os << r.delaunay.non_delaunay << " triangles not Delaunay; ";
    std::string s = os.str();
    if (s.size() >= 2) s.resize(s.size() - 2);
    return s;
}

// MeshOptions::certify: verifies \p r against {F = v} of \p grid within \p eps, or throws.
void certify_against(const openvdb::FloatGrid& grid, Inside inside, double eps, const MeshOptions& options,
                     MeshResult& r)
{
    const auto t0 = Clock::now();
    VerifyOptions vo;
    vo.isovalue = options.isovalue;
    vo.inside = inside;
    vo.eps = eps;
    const VerifyReport rep = verify_surface(grid, r.surface, vo);
    // Near-critical data whose reference topology no refinement settles: nothing to certify
    // against (isodel verify reports it as "undetermined").
    if (!rep.reference.determined)
        throw GuaranteeViolated("certify: the reference topology of Sigma stays undetermined (a saddle of F "
                                "too close to v for the verifier's refinements); the surface cannot be certified");
    if (!rep.passed()) throw GuaranteeViolated("certify: the mesh does not verify: " + verify_failure(rep));
    r.stats.certify_attempts = 1;
    r.stats.seconds["certify"] = seconds_since(t0);
    r.stats.seconds["total"] += r.stats.seconds["certify"];
}

MeshResult mesh_grid(const openvdb::FloatGrid& grid, const octree::AdaptiveGrid* adaptive, const MeshOptions& options,
                     Interrupter* interrupter, std::vector<std::array<double, 3>>* points = nullptr)
{
    // Options are checked before any work: a partitioned run checks them only at its merge.
    check_mesh_options(options);
    // Share the grid without copying it: the field keeps a non-owning pointer for the call.
    openvdb::FloatGrid::ConstPtr gptr(&grid, [](const openvdb::FloatGrid*) {});
    const Inside inside = inside_side(grid, options);
    const octree::SampleField field(gptr, options.isovalue, inside);
    MeshResult r = mesh_once(field, adaptive, options, interrupter, points);
    if (options.certify) certify_against(grid, inside, r.stats.eps_world, options, r);
    return r;
}

/// The input's own grid as an adaptive volume without coarse levels: what a run meshed on it
/// saves (MeshResult::adaptive_grid).
std::shared_ptr<AdaptiveVolume> input_grid_volume(const openvdb::FloatGrid& grid, const octree::SampleField& fine, int k)
{
    auto v = std::make_shared<AdaptiveVolume>();
    v->samples = openvdb::ConstPtrCast<openvdb::FloatGrid>(grid.copy()); // shallow: shares the tree
    v->domain = fine.domain();
    v->k = k;
    v->source = "isodel mesh --adaptive";
    return v;
}

/// The certified octree as an adaptive volume (MeshResult::adaptive_grid).
std::shared_ptr<AdaptiveVolume> octree_volume(const octree::AdaptiveGrid& g)
{
    auto v = std::make_shared<AdaptiveVolume>();
    // A shallow copy: a new grid object sharing the samples' tree, which it keeps alive.
    v->samples = openvdb::ConstPtrCast<openvdb::FloatGrid>(g.samples_ptr())->copy();
    v->levels = g.masks();
    v->domain = g.domain();
    v->k = g.k();
    v->source = "isodel mesh --adaptive";
    return v;
}

/// The crossings of the octree's leaf edges: the E points the mesher would start from on it
/// (seeding/initial_points.cpp takes the same ones).
std::size_t octree_edge_crossings(const octree::SampleField& coarse, const octree::AdaptiveGrid& g)
{
    const octree::EdgeCrossings e = octree::edge_crossings(coarse);
    const octree::AdaptiveGrid::Reader leaves(g);
    return std::size_t(std::count_if(e.points.begin(), e.points.end(),
                                     [&](const octree::EdgePoint& p) { return on_leaf_edge(leaves, p.lower, p.axis); }));
}

/// What every adaptive run reports and keeps, then MeshOptions::certify against the input.
MeshResult finish_adaptive(MeshResult r, AdaptiveStats a, std::shared_ptr<AdaptiveVolume> saved, double eps,
                           double t_grid, const openvdb::FloatGrid& grid, Inside inside, const MeshOptions& options)
{
    a.used = true;
    // Meshed on the input's grid, the mesher had the whole eps.
    if (!a.meshed_on_octree) a.eps_meshing_world = r.stats.eps_world;
    r.stats.adaptive = std::move(a);
    r.stats.eps_world = eps;
    r.adaptive_grid = std::move(saved);
    r.stats.seconds["adaptive_grid"] = t_grid;
    r.stats.seconds["total"] += t_grid;
    if (options.certify) certify_against(grid, inside, eps, options, r);
    return r;
}

// MeshOptions::adaptive: the certified grid (octree/certified_coarsening.h) spends at most
// adaptive_share x eps; the mesher gets the rest against the coarse Sigma, at the input's level
// v*. Then M ~ coarse Sigma ~ Sigma (isotopic) and d_H(M, Sigma) <= eps (docs/adaptive.md).
// Where the octree keeps Sigma's cells fine, the share it took buys nothing and the mesher,
// held to less than eps, adds points: below adaptive_min_saving fewer E points (bounded before
// building, counted after), the input's own grid is meshed with the whole eps, exactly as
// without adaptive. With AdaptiveField::Input the mesher reads the input with the whole eps and
// the seed octree (octree/seed_octree.h) gives only E and G, under the same saving rule.
MeshResult mesh_certified_adaptive(const openvdb::FloatGrid& grid, const MeshOptions& options, Interrupter* interrupter)
{
    const auto t0 = Clock::now();
    const ThreadLimit threads(options.threads); // the construction too, not only the mesher
    openvdb::FloatGrid::ConstPtr gptr(&grid, [](const openvdb::FloatGrid*) {});
    const Inside inside = inside_side(grid, options);
    const octree::SampleField fine(gptr, options.isovalue, inside);
    const double eps = options.eps > 0 ? options.eps : options.eps_voxels * fine.min_voxel_edge();
    octree::CoarseningBudget budget;
    budget.distance_world = options.adaptive_share * eps;
    budget.k = options.adaptive_k;
    budget.max_level = options.adaptive_max_level;
    MeshOptions mo = options;
    mo.adaptive = false;
    mo.certify = false;

    AdaptiveStats a;
    a.eps_coarsening_world = budget.distance_world;
    const octree::EdgeCrossings e = octree::edge_crossings(
        fine, [&](std::size_t, std::size_t) {
            if (interrupter && interrupter->wasInterrupted()) throw Cancelled("adaptive grid: interrupted");
        });
    a.e_uniform = a.e_octree = e.points.size();
    const double least_saved = options.adaptive_min_saving * double(a.e_uniform);
    // The certified octree is built only when a bound before building says it could remove
    // enough crossings (the seed octree of the Input field is counted after building instead).
    const auto coarse_may_pay = [&] {
        if (options.adaptive_min_saving == 0) return true;
        a.e_removable = octree::crossings_coarse_leaves_could_remove(fine, e.points, e.crossed_cells, budget);
        return double(a.e_removable) >= least_saved;
    };
    if (options.adaptive_field == AdaptiveField::Input) {
        // The mesher reads the input itself with the whole eps; the octree gives E and G only.
        a.eps_coarsening_world = 0;
        octree::SeedOctreeOptions so;
        so.k = budget.k;
        so.max_level = budget.max_level;
        const octree::AdaptiveGrid g = octree::seed_octree(fine, so, interrupter);
        if (g.max_level() > 0) a.e_octree = octree_edge_crossings(fine, g);
        a.meshed_on_octree = g.max_level() > 0 && (options.adaptive_min_saving == 0 ||
                                                   double(a.e_uniform) - double(a.e_octree) >= least_saved);
        if (a.meshed_on_octree) {
            const double t_grid = seconds_since(t0);
            mo.eps = eps;
            a.eps_meshing_world = eps;
            a.leaves_per_level = g.level_histogram();
            return finish_adaptive(mesh_once(fine, &g, mo, interrupter, nullptr), a,
                                   input_grid_volume(grid, fine, budget.k), eps, t_grid, grid, inside, options);
        }
    } else if (coarse_may_pay()) {
        // A narrow-band level set's clamped values would bound the cells at Sigma by the band's
        // half-width: coarse corners read distances extended beyond it (extended_level_set.h).
        const auto corners = octree::extend_level_set(grid, 1 << std::min(budget.max_level, 3));
        const octree::CertifiedGrid cg = octree::certified_coarsening(fine, budget, interrupter, corners);
        if (cg.grid.max_level() > 0) a.e_octree = octree_edge_crossings(*cg.field, cg.grid);
        a.meshed_on_octree = cg.grid.max_level() > 0 && (options.adaptive_min_saving == 0 ||
                                                         double(a.e_uniform) - double(a.e_octree) >= least_saved);
        a.cells_certified = cg.cells_certified;
        a.repair_rounds = cg.rounds;
        a.repair_splits = cg.splits;
        if (a.meshed_on_octree) {
            const double t_grid = seconds_since(t0);
            mo.eps = eps - cg.distance_world; // the coarse field, at the input's v*
            a.distance_world = cg.distance_world;
            a.eps_meshing_world = mo.eps;
            a.leaves_per_level = cg.grid.level_histogram();
            return finish_adaptive(mesh_once(*cg.field, &cg.grid, mo, interrupter, nullptr), a, octree_volume(cg.grid),
                                   eps, t_grid, grid, inside, options);
        }
    } // refused: the octree and the extended level set are freed before the input's grid is meshed
    a.leaves_per_level = octree::AdaptiveGrid(gptr, budget.k).level_histogram(); // the grid meshed and kept
    const double t_grid = seconds_since(t0);
    return finish_adaptive(mesh_once(fine, nullptr, mo, interrupter, nullptr), a, input_grid_volume(grid, fine, budget.k),
                           eps, t_grid, grid, inside, options);
}

} // namespace

void check_mesh_options(const MeshOptions& o)
{
    const auto refuse = [](const std::string& what) { throw InvalidInput(what); };
    const auto num = [](double x) {
        std::ostringstream s;
        s << x;
        return s.str();
    };
    if (!(o.eps >= 0) || !std::isfinite(o.eps)) refuse("eps must be positive and finite (got " + num(o.eps) + ")");
    if (o.eps == 0 && (!(o.eps_voxels > 0) || !std::isfinite(o.eps_voxels)))
        refuse("eps_voxels must be positive and finite (got " + num(o.eps_voxels) + ")");
    if (o.threads < 0) refuse("threads must be 0 (all) or positive (got " + std::to_string(o.threads) + ")");
    if (o.max_rounds < 1) refuse("max_rounds must be at least 1 (got " + std::to_string(o.max_rounds) + ")");
    if (o.block_voxels < 0 || (o.block_voxels > 0 && o.block_voxels < kMinBlockVoxels))
        refuse("block_voxels must be 0 (off) or at least " + std::to_string(kMinBlockVoxels) +
               " (smaller blocks mesh their collars over and over; got " + std::to_string(o.block_voxels) + ")");
    if (o.block_count < 0 || o.block_count > kMaxBlocks)
        refuse("block_count must be 0 (off) or in [1, " + std::to_string(int(kMaxBlocks)) + "] (got " +
               std::to_string(o.block_count) + ")");
    if (o.block_count > 0 && o.block_voxels > 0)
        refuse("block_count and block_voxels are two ways to cut the blocks: give one of them");
    const bool partitioned = o.block_voxels > 0 || o.block_count > 0;
    if (o.release_blocks && !partitioned)
        refuse("release_blocks needs block_voxels or block_count: without blocks there is nothing to release");
    // A triangle's smallest angle is at most 60 degrees: a larger bound can never be met.
    if (!(o.facet_angle_deg >= 0) || o.facet_angle_deg > 60)
        refuse("facet_angle_deg must be in [0, 60] (got " + num(o.facet_angle_deg) + ")");
    // A tetrahedron's dihedral angles cannot all exceed the regular one's, arccos(1/3).
    if (!(o.tet_min_dihedral_deg >= 0) || o.tet_min_dihedral_deg > 70)
        refuse("tet_min_dihedral_deg must be in [0, 70] (got " + num(o.tet_min_dihedral_deg) + ")");
    if (!(o.tet_max_dihedral_deg >= 71) || o.tet_max_dihedral_deg > 180)
        refuse("tet_max_dihedral_deg must be in [71, 180] (got " + num(o.tet_max_dihedral_deg) + ")");
    if (o.tets == TetRegion::None && (o.tet_min_dihedral_deg > 0 || o.tet_max_dihedral_deg < 180))
        refuse("tet_min_dihedral_deg and tet_max_dihedral_deg need tets: without them there is no tet to hold to the range");
    if (!(o.tet_grading > 0) || !std::isfinite(o.tet_grading))
        refuse("tet_grading must be a finite number > 0 (got " + num(o.tet_grading) + ")");
    if (!(o.tet_size >= 0) || !std::isfinite(o.tet_size))
        refuse("tet_size must be a finite number >= 0 (got " + num(o.tet_size) + ")");
    if (!(o.adaptive_share > 0 && o.adaptive_share < 1))
        refuse("adaptive_share must be in (0, 1) (got " + num(o.adaptive_share) + ")");
    if (o.adaptive_k < 1 || o.adaptive_k > 4) refuse("adaptive_k must be in [1, 4] (got " + std::to_string(o.adaptive_k) + ")");
    if (o.adaptive_max_level < 0 || o.adaptive_max_level > 15)
        refuse("adaptive_max_level must be in [0, 15] (got " + std::to_string(o.adaptive_max_level) + ")");
    if (!(o.adaptive_min_saving >= 0 && o.adaptive_min_saving < 1))
        refuse("adaptive_min_saving must be in [0, 1) (got " + num(o.adaptive_min_saving) + ")");
    if (o.adaptive && partitioned)
        refuse("adaptive meshing cannot be combined with partitioned meshing (block_voxels, block_count) yet");
    if (o.transport && !partitioned)
        refuse("a transport (several processes) needs block_voxels or block_count > 0");
    if (o.transport && o.tets != TetRegion::None)
        refuse("tetrahedra cannot be meshed by several processes yet (a transport with tets)");
    if (o.transport && o.certify) refuse("certify cannot be combined with several processes yet (a transport)");
}

MeshResult mesh_isosurface(const openvdb::FloatGrid& grid, const MeshOptions& options, Interrupter* interrupter)
{
    if (options.adaptive) {
        check_mesh_options(options);
        return mesh_certified_adaptive(grid, options, interrupter);
    }
    return mesh_grid(grid, nullptr, options, interrupter);
}

MeshResult mesh_isosurface(const AdaptiveVolume& volume, const MeshOptions& options, Interrupter* interrupter)
{
    if (!volume.samples) throw InvalidInput("adaptive volume without samples");
    if (options.adaptive)
        throw InvalidInput("adaptive meshing needs the original volume: this input is adaptive already (decimated); "
                           "mesh it without adaptive, or mesh the original");
    check_mesh_options(options);
    const auto t0 = Clock::now();
    const octree::AdaptiveGrid g = octree::to_adaptive_grid(volume);
    const openvdb::FloatGrid::Ptr dense = octree::resample_dense(g);
    const double t_resample = seconds_since(t0);
    MeshResult r = mesh_grid(*dense, g.max_level() > 0 ? &g : nullptr, options, interrupter);
    r.stats.seconds["resample"] = t_resample;
    r.stats.seconds["total"] += t_resample;
    return r;
}

MeshResult mesher::mesh_keeping_points(const openvdb::FloatGrid& grid, const MeshOptions& options,
                                       std::vector<std::array<double, 3>>& points, Interrupter* interrupter)
{
    return mesh_grid(grid, nullptr, options, interrupter, &points);
}

} // namespace isodel
