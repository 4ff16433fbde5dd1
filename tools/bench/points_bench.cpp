// points_bench: the stages before the Delaunay triangulation, stage by stage, at 1 and 2
// threads, against the whole run. One row per volume of ../shared/data (every .vdb entry of the
// manifest without expect_error) and of any --data directory (tools/bench/protein_128_bench.sh
// makes the 128^3 protein). Columns (medians of --reps, milliseconds):
//   field   SampleField construction: value range and the tie scan of samples and face/cell
//           saddles (octree/sample_field.cpp)
//   E, G, tubes   edge_crossings, protective_layer, thin tubes + tunnel shoulders
//   pre1, pre2    field + E + G + tubes at 1 and 2 threads; x = pre1 / pre2
//   points  MeshStats::seconds["points"] of a whole run at --threads (E, G, tubes, shoulders)
//   total   that run's total; share = points / total
//
//   points_bench [--data DIR]... [--reps 3] [--whole-reps 1] [--eps-voxels 0.5] [--threads 2]
//                [--only SUBSTRING] [--stages-at-threads 1]
// --stages-at-threads 1 adds a line per volume: each stage's median at --threads.
// The stages run --reps times, the whole run --whole-reps times (its points and total are
// medians over those; 0 times the stages alone, for profiling them).
#include "support/bench_support.h"

#include "octree/edge_crossings.h"
#include "octree/protective_layer.h"
#include "octree/sample_field.h"
#include "seeding/thin_tubes.h"
#include "seeding/tunnel_shoulders.h"

#include <isodel/mesh.h>
#include <isodel/volume.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

struct Stages {
    double field = 0, e = 0, g = 0, tubes = 0;
    double pre() const { return field + e + g + tubes; }
};

/// One pass over the pre-Delaunay stages at \p threads, each stage timed on its own.
Stages run_stages(const openvdb::FloatGrid::Ptr& grid, double iso, isodel::Inside inside, int threads)
{
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    Stages s;
    auto t0 = Clock::now();
    const isodel::octree::SampleField field(grid, iso, inside);
    s.field = since(t0);
    t0 = Clock::now();
    const auto e = isodel::octree::edge_crossings(field);
    s.e = since(t0);
    t0 = Clock::now();
    const auto layer = isodel::octree::protective_layer(field, e.crossed_cells);
    s.g = since(t0);
    t0 = Clock::now();
    const std::vector<openvdb::Coord>& cells = e.crossed_cells;
    const auto tubes = isodel::mesher::thin_tube_points(field, cells);
    const auto necks = isodel::mesher::tunnel_shoulder_points(field, cells);
    s.tubes = since(t0);
    (void)layer;
    (void)tubes;
    (void)necks;
    return s;
}

struct Entry {
    std::string path, name, grid;
    double iso = 0;
    std::string inside;
};

std::vector<Entry> entries(const std::string& dir)
{
    std::vector<Entry> out;
    std::ifstream in(dir + "/manifest.json");
    if (!in) return out;
    const auto manifest = nlohmann::json::parse(in);
    for (const auto& e : manifest) {
        if (isodel::bench::json_string(e, "format") != "vdb" || e.contains("expect_error")) continue;
        Entry x;
        x.name = isodel::bench::json_string(e, "file");
        x.path = dir + "/" + x.name;
        x.grid = isodel::bench::json_string(e, "grid_name");
        x.iso = e.at("isovalue").get<double>();
        x.inside = isodel::bench::json_string(e, "inside");
        out.push_back(x);
    }
    return out;
}

} // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> dirs;
    int reps = 3, whole_reps = 1, threads = 2;
    double eps_voxels = 0.5;
    std::string only;
    bool stages_at_threads = false;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i], v = argv[i + 1];
        if (a == "--data") dirs.push_back(v);
        else if (a == "--reps") reps = std::max(1, std::stoi(v));
        else if (a == "--whole-reps") whole_reps = std::max(0, std::stoi(v));
        else if (a == "--threads") threads = std::max(1, std::stoi(v));
        else if (a == "--eps-voxels") eps_voxels = std::stod(v);
        else if (a == "--only") only = v;
        else if (a == "--stages-at-threads") stages_at_threads = v == "1";
        else {
            std::fprintf(stderr, "points_bench: unknown option %s\n", a.c_str());
            return 2;
        }
    }
    if (dirs.empty()) {
        const std::string f = __FILE__; // <repo>/tools/bench/points_bench.cpp; ../shared beside the repo
        dirs.push_back(f.substr(0, f.rfind("/tools/bench/")) + "/../shared/data");
    }
    std::printf("%-44s %9s %7s %7s %7s %7s %7s %7s %5s %7s %7s %6s\n", "volume", "active", "field", "E", "G",
                "tubes", "pre1", "pre2", "x", "points", "total", "share");
    double worst_share = 0, worst_x = 1e9;
    for (const auto& dir : dirs)
        for (const Entry& e : entries(dir)) {
            if (!only.empty() && e.name.find(only) == std::string::npos) continue;
            isodel::ReadOptions ro;
            ro.grid_name = e.grid;
            const isodel::Volume vol = isodel::read_volume(e.path, ro);
            const isodel::Inside inside = e.inside == "below" ? isodel::Inside::Below
                                          : e.inside == "above" ? isodel::Inside::Above
                                                                : vol.default_inside;
            std::vector<Stages> one, two;
            std::vector<double> points, total;
            for (int r = 0; r < reps; ++r) { // interleaved: 1 thread, 2 threads (, whole run)
                one.push_back(run_stages(vol.grid, e.iso, inside, 1));
                two.push_back(run_stages(vol.grid, e.iso, inside, threads));
                if (r >= whole_reps) continue;
                isodel::MeshOptions mo;
                mo.isovalue = e.iso;
                mo.inside = inside;
                mo.eps_voxels = eps_voxels;
                mo.threads = threads;
                const auto res = isodel::mesh_isosurface(*vol.grid, mo);
                points.push_back(res.stats.seconds.at("points"));
                total.push_back(res.stats.seconds.at("total"));
            }
            auto med = [](const std::vector<Stages>& v, double Stages::*m) {
                std::vector<double> x;
                for (const auto& s : v) x.push_back(s.*m);
                return median(x);
            };
            std::vector<double> pre1, pre2;
            for (const auto& s : one) pre1.push_back(s.pre());
            for (const auto& s : two) pre2.push_back(s.pre());
            if (stages_at_threads)
                std::printf("  at %d threads: field %.2f E %.2f G %.2f tubes %.2f\n", threads, 1e3 * med(two, &Stages::field),
                             1e3 * med(two, &Stages::e), 1e3 * med(two, &Stages::g), 1e3 * med(two, &Stages::tubes));
            const double p1 = median(pre1), p2 = median(pre2);
            const double share = points.empty() ? 0.0 : median(points) / median(total); // --whole-reps 0: no whole run
            worst_share = std::max(worst_share, share);
            worst_x = std::min(worst_x, p1 / p2);
            const double ms = 1e3;
            std::printf("%-44s %9llu %7.2f %7.2f %7.2f %7.2f %7.2f %7.2f %5.2f %7.2f %7.1f %5.1f%%\n",
                        e.name.substr(0, 44).c_str(), (unsigned long long)vol.grid->activeVoxelCount(),
                        ms * med(one, &Stages::field), ms * med(one, &Stages::e), ms * med(one, &Stages::g),
                        ms * med(one, &Stages::tubes), ms * p1, ms * p2, p1 / p2, ms * median(points),
                        ms * median(total), 100 * share);
            std::fflush(stdout);
        }
    std::printf("worst share %.1f%%, smallest 1/%d-thread ratio of the pre-Delaunay stages %.2f\n", 100 * worst_share,
                threads, worst_x);
    return 0;
}
