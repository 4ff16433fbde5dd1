// isodel verify: certificates for the guarantees of `isodel mesh` on the user's own data
// (include/isodel/verify.h). Exit 0 only if every requested check passes, 1 otherwise.
#include "cli_common.h"

#include <isodel/errors.h>
#include <isodel/surface_mesh.h>
#include <isodel/verify.h>

#include "../../src/io/atomic_file.h" // internal, exported by libisodel

#include <iostream>
#include <optional>
#include <memory>

namespace isodel::cli {

void add_verify_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("verify", "Check a surface mesh against the level set it claims to mesh: "
                                             "topology, Hausdorff distance, Delaunay conformity, quality");
    struct Args {
        InputOptions in;
        std::string mesh, json, tets, inside;
        double iso = 0.0, eps = 0.0, eps_voxels = 0.0;
        int refine = 4, max_refine = 32, sigma_refine = 0;
        bool no_delaunay = false, no_self = false, strict = false, quiet = false;
    };
    auto a = std::make_shared<Args>();
    add_input_options(*cmd, a->in);
    cmd->add_option("--iso", a->iso, "Isovalue v")->required();
    cmd->add_option("--mesh", a->mesh, "Surface mesh to verify (.ply/.obj/.off/.stl)")->required();
    cmd->add_option("--eps", a->eps, "Hausdorff bound in world units");
    cmd->add_option("--eps-voxels", a->eps_voxels, "Hausdorff bound in smallest voxel edges");
    cmd->add_option("--inside", a->inside, "Which side is the solid (default: below for level sets, else above)")
        ->check(CLI::IsMember({"above", "below"}));
    cmd->add_option("--json", a->json, "Write the report as JSON");
    cmd->add_option("--refine", a->refine, "Reference topology refinement R (R and 2R are compared)");
    cmd->add_option("--max-refine", a->max_refine, "Keep doubling R up to this while the topology disagrees");
    cmd->add_option("--sigma-refine", a->sigma_refine, "Sub-lattice refinement for sampling Sigma (0 = auto)");
    cmd->add_option("--tets", a->tets, "Tetrahedral mesh (.mesh) to verify against --mesh: orientation, regions, "
                                       "boundary equal to M, volumes, dihedral angles");
    cmd->add_flag("--no-delaunay", a->no_delaunay, "Skip the Delaunay conformity check");
    cmd->add_flag("--no-self-intersections", a->no_self, "Skip the self-intersection check");
    cmd->add_flag("--strict-topology", a->strict, "An undetermined reference topology is a failure");
    cmd->add_flag("-q,--quiet", a->quiet, "Print only the final verdict");
    cmd->callback([a, &exit_code] {
        const Volume vol = read_input(a->in);
        const SurfaceMesh mesh = read_surface_mesh(a->mesh);
        const std::optional<TetMesh> tets = a->tets.empty() ? std::nullopt : std::optional<TetMesh>(read_tet_mesh(a->tets));
        VerifyOptions opt;
        opt.isovalue = a->iso;
        if (!a->inside.empty()) opt.inside = a->inside == "above" ? Inside::Above : Inside::Below;
        else opt.inside = vol.default_inside;
        opt.eps = a->eps;
        opt.eps_voxels = a->eps_voxels;
        opt.refine = a->refine;
        opt.max_refine = a->max_refine;
        opt.hausdorff_refine = a->sigma_refine;
        opt.check_delaunay = !a->no_delaunay;
        opt.check_self_intersections = !a->no_self;
        opt.require_determined_topology = a->strict;
        VerifyReport rep = verify_surface(*vol.grid, mesh, opt);
        if (tets) rep.tets = verify_tets(*tets, mesh);
        if (!a->json.empty()) {
            io::AtomicFile out(a->json);
            out.stream() << rep.to_json();
            out.commit();
        }
        if (a->quiet) std::cout << (rep.passed() ? "VERIFIED\n" : "NOT VERIFIED\n");
        else std::cout << rep.summary();
        exit_code = rep.passed() ? kOk : kFailed;
    });
}

} // namespace isodel::cli
