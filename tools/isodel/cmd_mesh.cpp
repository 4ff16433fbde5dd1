// isodel mesh: read a volume, run DELSURFMESH (include/isodel/mesh.h), write the surface and
// optionally the statistics. Outputs are written atomically, after meshing succeeded.
#include "cli_common.h"
#include "mpi_transport.h"

#include "io/atomic_file.h"
#include "surface/block_ranks.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>
#include <isodel/mesh.h>

#include <chrono>
#include <exception>
#include <iostream>

namespace isodel::cli {
namespace {
struct MeshCliOptions {
    InputOptions in;
    std::string out, inside, tets, region = "inside", stats;
    double iso = 0, eps = 0, eps_voxels = 0.5;
    int threads = 0;
    int max_rounds = 2000;
    int blocks = 0;
    int block_count = 0;
    std::size_t max_points = 0;
    bool quiet = false;
    bool trace = false;
    bool snap = false;
    bool certify = false;
    bool release_blocks = false;
    bool no_improve = false;
    bool uniform_tets = false;
    double tet_size = 0, grading = 0.5;
    double facet_angle = 0;
    double tet_min_dihedral = 0, tet_max_dihedral = 180;
    bool adaptive = false;
    double adaptive_share = 0.5;
    int adaptive_k = 1, adaptive_max_level = 5;
    double adaptive_min_saving = 0.1;
    std::string adaptive_field = "coarse";
    std::string adaptive_grid;
};

/// The DELVOLMESH options (docs/tetrahedra.md).
void add_tet_options(CLI::App& cmd, MeshCliOptions& o)
{
    cmd.add_option("--tets", o.tets, "Also write a tetrahedral mesh (.mesh, .vtu, .msh)");
    cmd.add_option("--region", o.region, "Tetrahedra to keep: inside|outside|both")
        ->check(CLI::IsMember({"inside", "outside", "both"}));
    cmd.add_flag("--no-improve-tets", o.no_improve,
                 "Keep the Delaunay tetrahedra (no smoothing or flips; M and the regions are the same either way)");
    auto* size =
        cmd.add_option("--tet-size", o.tet_size,
                       "Largest spacing of the points added off M, world units (default 8 voxels; rounded down "
                       "to a power of two voxels): tets grow from voxel size at M to this far from it")
            ->check(CLI::NonNegativeNumber);
    auto* grading =
        cmd.add_option("--grading", o.grading,
                       "Growth of the point spacing per voxel of distance from the protective layer around M "
                       "(default 0.5)")
            ->check(CLI::PositiveNumber);
    cmd.add_option("--tet-min-dihedral", o.tet_min_dihedral,
                   "Tets with a face on M and, after the improvement, a dihedral angle under this many degrees "
                   "get a point of the level set inserted on that face and the run is repeated, every "
                   "guarantee checked again (up to 3 more runs; default 0: off, M as without --tets)")
        ->check(CLI::Range(0.0, 70.0));
    cmd.add_option("--tet-max-dihedral", o.tet_max_dihedral,
                   "... or over this many degrees (default 180: off)")
        ->check(CLI::Range(71.0, 180.0));
    cmd.add_flag("--uniform-tets", o.uniform_tets,
                 "Add every sample off M (one tet size, the voxel's) instead of graded spacing")
        ->excludes(size)
        ->excludes(grading);
}

} // namespace

void add_mesh_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("mesh", "Mesh the level set {F = iso} of a volume (DELSURFMESH)");
    auto o = std::make_shared<MeshCliOptions>();
    add_input_options(*cmd, o->in);
    cmd->add_option("-o,--output", o->out, "Output surface (.ply, .obj, .off, .stl)")->required();
    cmd->add_option("--iso", o->iso, "Isovalue")->required();
    cmd->add_option("--inside", o->inside, "Which side is inside: above|below (default from the grid class)")
        ->check(CLI::IsMember({"above", "below"}));
    auto* eps = cmd->add_option("--eps", o->eps, "Hausdorff bound in world units");
    cmd->add_option("--eps-voxels", o->eps_voxels, "Hausdorff bound in units of the smallest voxel edge (default 0.5)")
        ->excludes(eps);
    add_tet_options(*cmd, *o);
    cmd->add_option("--facet-angle", o->facet_angle,
                    "Also refine M's triangles to this smallest angle in degrees (0 = off; up to ~30), "
                    "after every guarantee holds")
        ->check(CLI::Range(0.0, 35.0));
    cmd->add_option("--threads", o->threads, "Threads (0 = all); the mesh does not depend on it");
    cmd->add_option("--stats", o->stats, "Write statistics as JSON");
    cmd->add_option("--max-rounds", o->max_rounds, "Bound on refinement rounds");
    cmd->add_option("--max-points", o->max_points, "Bound on inserted points (0 = automatic)");
    cmd->add_flag("--snap", o->snap,
                  "Snap the grid-edge crossings within eps/2 of a sample onto it, where at least three "
                  "gather (paper Section 5): fewer, better spaced points");
    cmd->add_option("--blocks", o->blocks,
                    "Partitioned meshing (paper Fig. 8): blocks of this many voxels per axis, meshed "
                    "concurrently with protective collars, then merged (dense grids; 0 = off, else at least 4)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--block-count", o->block_count,
                    "Partitioned meshing into this many blocks of about equal work (the grid-edge crossings), "
                    "slabs of the longest axes, instead of --blocks' cubes: one per process or thread wastes "
                    "the least on collars (0 = off)")
        ->check(CLI::NonNegativeNumber)
        ->excludes("--blocks");
    cmd->add_flag("--release-blocks", o->release_blocks,
                  "With --blocks or --block-count: hold one block per thread in memory, rebuilding a block from its points when "
                  "a neighbour's arrive (less memory per process, more time)");
    cmd->add_flag("--certify", o->certify,
                  "Verify the surface before writing it (topology against an independent computation, eps, "
                  "manifold, Delaunay); exit 1 and write nothing if it fails");
    cmd->add_flag("--adaptive", o->adaptive,
                  "Certified adaptive meshing: coarse cells where a certificate proves the coarse level set "
                  "isotopic to the input's and within a share of eps of it (docs/adaptive.md); the guarantees "
                  "hold against the input");
    cmd->add_option("--adaptive-share", o->adaptive_share,
                    "--adaptive: share of eps the coarsening may spend (default 0.5)")
        ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--adaptive-k", o->adaptive_k, "--adaptive: level difference of touching cells (default 1)")
        ->check(CLI::Range(1, 4));
    cmd->add_option("--adaptive-max-level", o->adaptive_max_level,
                    "--adaptive: coarsest cell, 2^level voxels (default 5)")
        ->check(CLI::Range(0, 15));
    cmd->add_option("--adaptive-min-saving", o->adaptive_min_saving,
                    "--adaptive: mesh the input's own grid with the whole eps when the octree removes less than "
                    "this share of its grid-edge crossings (default 0.1; 0: the octree whenever it has a coarse leaf)")
        ->check(CLI::Range(0.0, 0.999999));
    cmd->add_option("--adaptive-field", o->adaptive_field,
                    "--adaptive: the function meshed: coarse (the octree's interpolant, default) or input (the "
                    "input's own with the whole eps, the octree giving only E and G; docs/adaptive.md)")
        ->check(CLI::IsMember({"coarse", "input"}));
    cmd->add_option("--adaptive-grid", o->adaptive_grid,
                    "--adaptive: also write the grid meshed (.vdb, as isodel decimate writes: the certified "
                    "octree, or the input's own grid when the octree saved too little), so that "
                    "isodel verify can check the surface against its interpolant too");
    cmd->add_flag("--quiet", o->quiet, "No progress output");
    cmd->add_flag("--trace", o->trace, "Print the mesher's trace on stderr: one line per refinement round and check");
    cmd->callback([o, &exit_code] {
        // Refuse unknown output formats before doing any work.
        const std::string ext = io::extension_of(o->out);
        if (ext != ".ply" && ext != ".obj" && ext != ".off" && ext != ".stl")
            throw InvalidInput(o->out + ": unknown surface format '" + ext + "' (use .ply, .obj, .off or .stl)");
        if (!o->tets.empty() && !is_tet_mesh_path(o->tets))
            throw InvalidInput(o->tets + ": unknown tetrahedral mesh format '" + io::extension_of(o->tets) +
                               "' (use .mesh, .vtu or .msh)");
        MeshOptions mo;
        mo.isovalue = o->iso;
        mo.eps = o->eps;
        mo.eps_voxels = o->eps_voxels;
        mo.threads = o->threads;
        mo.max_rounds = o->max_rounds;
        mo.max_points = o->max_points;
        mo.snap = o->snap;
        mo.certify = o->certify;
        mo.block_voxels = o->blocks;
        mo.block_count = o->block_count;
        mo.release_blocks = o->release_blocks;
        if (!o->tets.empty())
            mo.tets = o->region == "both"      ? TetRegion::Both
                      : o->region == "outside" ? TetRegion::Outside
                                               : TetRegion::Inside;
        mo.improve_tets = !o->no_improve;
        mo.tet_spacing = o->uniform_tets ? TetSpacing::Uniform : TetSpacing::Graded;
        mo.tet_size = o->tet_size;
        mo.tet_grading = o->grading;
        mo.facet_angle_deg = o->facet_angle;
        mo.tet_min_dihedral_deg = o->tet_min_dihedral;
        mo.tet_max_dihedral_deg = o->tet_max_dihedral;
        mo.adaptive = o->adaptive;
        mo.adaptive_share = o->adaptive_share;
        mo.adaptive_k = o->adaptive_k;
        mo.adaptive_max_level = o->adaptive_max_level;
        mo.adaptive_min_saving = o->adaptive_min_saving;
        mo.adaptive_field = o->adaptive_field == "input" ? AdaptiveField::Input : AdaptiveField::Coarse;
        check_mesh_options(mo); // before any work
        if (!o->adaptive_grid.empty() && !mo.adaptive)
            throw InvalidInput("--adaptive-grid " + o->adaptive_grid +
                               ": needs --adaptive (the octree it writes is "
                               "the one --adaptive builds)");

        // mpirun -np N: the blocks spread over the processes (docs/partitioned.md); the first
        // process reports progress and writes the mesh.
        MpiSession& mpi = mpi_session();
        if (mpi.several()) {
            if (mo.block_voxels == 0 && mo.block_count == 0)
                throw InvalidInput("isodel mesh under mpirun with " + std::to_string(mpi.size()) +
                                   " processes needs --blocks B or --block-count N (the blocks are what the "
                                   "processes share)");
            mo.transport = mpi.transport();
            check_mesh_options(mo);
        }
        ProgressReporter progress(o->quiet || mpi.rank() != 0, o->trace && mpi.rank() == 0);
        const auto t0 = std::chrono::steady_clock::now();
        progress.start("read");
        Volume vol;
        std::exception_ptr read_failure;
        // Under mpirun a file that can be read in part (MRC, raw) is: each process reads its
        // slab and its blocks' boxes (mesh_isosurface_file), here only the header. Tetrahedra
        // and --certify need every sample.
        const bool read_in_part = mpi.several() && mo.tets == TetRegion::None && !mo.certify;
        try {
            if (read_in_part) {
                ReadOptions header = read_options(o->in);
                header.regions = std::vector<openvdb::CoordBBox>{};
                vol = read_volume(o->in.path, header);
            } else {
                vol = read_input(o->in);
            }
            if (!vol.partial) check_isovalue(vol, o->iso); // else mesh_isosurface_file checks it
        } catch (...) {
            read_failure = std::current_exception();
        }
        // Every process read the file: if one could not, all stop here rather than wait for it.
        mesher::BlockRanks(mo.transport).agree(read_failure);
        progress.end();
        const double t_read = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        mo.inside = o->inside.empty() ? vol.default_inside : (o->inside == "above" ? Inside::Above : Inside::Below);
        // An adaptive file (`isodel decimate`): mesh on its leaves (Property IV).
        if (vol.adaptive_levels > 1 && mo.adaptive)
            throw InvalidInput(o->in.path +
                               ": --adaptive needs the original volume, and this file is adaptive "
                               "already (isodel decimate); mesh it without --adaptive, or mesh the original");
        MeshResult res;
        try {
            res = vol.partial                ? mesh_isosurface_file(std::move(vol), read_options(o->in), mo, &progress)
                  : vol.adaptive_levels > 1 ? mesh_isosurface(load_adaptive(vol.path), mo, &progress)
                                            : mesh_isosurface(*vol.grid, mo, &progress);
        }
        catch (const GuaranteeViolated& e) {
            throw GuaranteeViolated(o->in.path + ": " + e.what()); // name the file (exit status 1)
        } catch (const InvalidInput& e) {
            // What this volume cannot take (exit status 2); a reader's message names the file already.
            const std::string what = e.what();
            throw InvalidInput(what.rfind(o->in.path + ": ", 0) == 0 ? what : o->in.path + ": " + what);
        }

        if (mpi.rank() != 0) return; // the first process holds the mesh and writes it
        const auto tw = std::chrono::steady_clock::now();
        progress.start("write");
        write_surface_mesh(o->out, res.surface);
        if (!o->tets.empty()) write_tet_mesh(o->tets, res.tets);
        if (!o->adaptive_grid.empty() && res.adaptive_grid) save_adaptive(o->adaptive_grid, *res.adaptive_grid);
        progress.end();
        res.stats.seconds["read"] = t_read;
        res.stats.seconds["write"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - tw).count();
        res.stats.seconds["total"] += t_read + res.stats.seconds["write"];
        if (!o->stats.empty()) {
            io::AtomicFile f(o->stats);
            f.stream() << to_json(res.stats);
            f.commit();
        }
        if (!o->quiet) {
            std::cerr << "isodel mesh: wrote " << o->out << " (" << res.stats.vertices << " vertices, "
                      << res.stats.triangles << " triangles, " << res.stats.components.size() << " components; genus";
            for (const auto& c : res.stats.components)
                std::cerr << ' ' << c.genus;
            std::cerr << ")";
            if (res.stats.certify_attempts > 0) std::cerr << ", verified";
            std::cerr << "\n";
            if (!o->tets.empty()) {
                const TetStats& t = res.stats.tets;
                std::cerr << "isodel mesh: wrote " << o->tets << " (" << t.vertices << " vertices, " << t.tets_inside
                          << " inside + " << t.tets_outside << " outside tetrahedra; volume inside " << t.volume_inside
                          << ", enclosed by the surface " << t.volume_enclosed_by_surface << ")\n  dihedral angles "
                          << t.min_dihedral_deg << " .. " << t.max_dihedral_deg << " deg, max radius-edge ratio "
                          << t.max_radius_edge << "; " << t.tets_below_10deg
                          << " tets under 10 deg\n  away from the surface (tets with no surface vertex): dihedral >= "
                          << t.min_dihedral_deg_off_surface << " deg, radius-edge <= " << t.max_radius_edge_off_surface
                          << "\n  improvement: smallest dihedral angle " << t.min_dihedral_deg_delaunay
                          << " deg before (Delaunay), " << t.vertices_moved << " vertices moved, " << t.vertices_removed
                          << " removed, " << t.vertices_inserted << " inserted, " << t.flips
                          << " flips\n  dihedral histogram (10 deg bins):";
                for (auto n : t.dihedral_histogram)
                    std::cerr << ' ' << n;
                std::cerr << "\n";
                if (res.stats.tet_sliver_stop != TetSliverStop::Off)
                    std::cerr << "  tets M pinned down: " << res.stats.n_tet_sliver << " points of the level set inserted in "
                              << res.stats.tet_sliver_runs << " more runs (" << to_string(res.stats.tet_sliver_stop)
                              << ")\n";
            }
        }
        exit_code = kOk;
    });
}

} // namespace isodel::cli
