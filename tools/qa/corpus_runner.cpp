// corpus_runner: meshes every volume of ../shared/data/manifest.json (entries with expect_error
// are skipped) at each requested eps, verifies each result with isodel::verify_surface, and prints
// one table: dataset, dims, eps, vertices, triangles, mesh time, verify time, and the verdicts
// (topology, Hausdorff, Delaunay; plus "M" = closed oriented manifold without self-intersections).
// The last line sums both times (a benchmark of the verifier as much as of the mesher).
//
//   corpus_runner [--data DIR] [--eps-voxels 0.5,0.1] [--filter SUBSTRING] [--formats vdb,mrc,inr]
//                 [--no-delaunay] [--threads N]
// Exit status 0 only if every row passes.
#include <isodel/errors.h>
#include <isodel/mesh.h>
#include <isodel/verify.h>
#include <isodel/volume.h>

#include "support/bench_support.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using isodel::bench::json_number;
using isodel::bench::json_string;
using isodel::bench::split;

// The shared data sit next to the repository: <repo>/../shared/data.
std::string default_data()
{
    std::string f = __FILE__;
    return f.substr(0, f.rfind("/tools/bench/")) + "/../shared/data";
}

const char* verdict(bool checked, bool ok) { return !checked ? "-" : ok ? "pass" : "FAIL"; }

} // namespace

int main(int argc, char** argv)
{
    std::string data = default_data(), filter;
    std::vector<double> eps_list{0.5, 0.1};
    std::vector<std::string> formats{"vdb", "mrc", "inr"};
    bool delaunay = true;
    int threads = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::cerr << "corpus_runner: " << a << " needs a value\n";
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--data") data = next();
        else if (a == "--eps-voxels") {
            eps_list.clear();
            for (const auto& e : split(next())) eps_list.push_back(std::stod(e));
        } else if (a == "--filter") filter = next();
        else if (a == "--formats") formats = split(next());
        else if (a == "--no-delaunay") delaunay = false;
        else if (a == "--threads") threads = std::stoi(next());
        else {
            std::cerr << "usage: corpus_runner [--data DIR] [--eps-voxels 0.5,0.1] [--filter S] [--formats vdb,mrc,inr]"
                         " [--no-delaunay] [--threads N]\n";
            return 2;
        }
    }
    openvdb::initialize();
    std::ifstream in(data + "/manifest.json");
    if (!in) {
        std::cerr << "corpus_runner: cannot read " << data << "/manifest.json\n";
        return 2;
    }
    std::stringstream ss;
    ss << in.rdbuf();
    const nlohmann::json manifest = nlohmann::json::parse(ss.str());

    std::printf("%-42s %-12s %5s %8s %9s %8s %8s %-9s %-9s %-9s %-4s %s\n", "dataset", "dims", "eps", "vertices",
                "triangles", "time_s", "verify_s", "topology", "hausdorff", "delaunay", "M", "notes");
    int rows = 0, failed = 0;
    double mesh_total = 0, verify_total = 0;
    for (const auto& e : manifest) {
        if (isodel::bench::expects_error(e)) continue;
        if (json_string(e, "category") == "invalid") continue;
        const std::string file = json_string(e, "file");
        if (!filter.empty() && file.find(filter) == std::string::npos) continue;
        if (std::find(formats.begin(), formats.end(), json_string(e, "format")) == formats.end()) continue;
        const std::string dims = isodel::bench::dims_string(e);
        isodel::Volume vol;
        try {
            isodel::ReadOptions ro;
            ro.grid_name = json_string(e, "grid_name");
            vol = isodel::read_volume(data + "/" + file, ro);
        } catch (const std::exception& ex) {
            std::printf("%-42s %-12s %5s read error: %s\n", file.c_str(), dims.c_str(), "-", ex.what());
            ++rows;
            ++failed;
            continue;
        }
        const isodel::Inside inside = json_string(e, "inside") == "below" ? isodel::Inside::Below : isodel::Inside::Above;
        for (double eps : eps_list) {
            ++rows;
            isodel::MeshOptions mo;
            mo.isovalue = json_number(e, "isovalue");
            mo.inside = inside;
            mo.eps_voxels = eps;
            mo.threads = threads;
            isodel::MeshResult res;
            const auto t0 = std::chrono::steady_clock::now();
            try {
                res = isodel::mesh_isosurface(*vol.grid, mo);
            } catch (const std::exception& ex) {
                std::printf("%-42s %-12s %5.2f mesh error: %s\n", file.c_str(), dims.c_str(), eps, ex.what());
                std::fflush(stdout);
                ++failed;
                continue;
            }
            const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            isodel::VerifyOptions vo;
            vo.isovalue = mo.isovalue;
            vo.inside = inside;
            vo.eps_voxels = eps;
            vo.check_delaunay = delaunay;
            std::string notes;
            bool ok = false;
            mesh_total += secs; // counted whether or not the verification below completes
            try {
                const auto v0 = std::chrono::steady_clock::now();
                const isodel::VerifyReport r = isodel::verify_surface(*vol.grid, res.surface, vo);
                const double vsecs = std::chrono::duration<double>(std::chrono::steady_clock::now() - v0).count();
                verify_total += vsecs;
                ok = r.passed();
                const char* topo = r.topology_verdict == isodel::TopologyVerdict::Undetermined
                                       ? "undet."
                                       : verdict(true, r.topology_verdict == isodel::TopologyVerdict::Pass);
                char h[64];
                std::snprintf(h, sizeof h, "%s %.3f", verdict(r.hausdorff.checked, r.hausdorff.passed),
                              std::max(r.hausdorff.mesh_to_surface.max_voxels, r.hausdorff.surface_to_mesh.max_voxels));
                notes = "M genus";
                for (const auto& c : r.mesh.components) notes += " " + std::to_string(c.genus);
                if (r.mesh.components.size() > 8) notes = "M " + std::to_string(r.mesh.components.size()) + " comps";
                std::printf("%-42s %-12s %5.2f %8zu %9zu %8.2f %8.2f %-9s %-9s %-9s %-4s %s\n", file.c_str(), dims.c_str(),
                            eps, res.surface.vertices.size(), res.surface.triangles.size(), secs, vsecs, topo, h,
                            verdict(r.delaunay.checked, r.delaunay.passed), r.mesh_ok() ? "ok" : "FAIL", notes.c_str());
            } catch (const std::exception& ex) {
                std::printf("%-42s %-12s %5.2f verify error: %s\n", file.c_str(), dims.c_str(), eps, ex.what());
            }
            std::fflush(stdout);
            failed += !ok;
        }
    }
    std::printf("%d rows, %d failed; mesh %.1f s, verify %.1f s in all\n", rows, failed, mesh_total, verify_total);
    return failed == 0 ? 0 : 1;
}
