// Check 1: the topology of Sigma without the mesher (see refined_lattice.h for why it is exact
// in the limit and consistent at every R). Components and genus per component from the marching
// tetrahedra surface: vertices merged by sub-lattice edge key, components by union-find, and
// chi = V - E + F = V - F/2 per component (the surface is closed, every edge has two triangles).
#include "verify/refined_lattice.h"

#include "octree/critical_values.h"

#include <isodel/errors.h>
#include <isodel/verify.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <tuple>

namespace isodel::verify {
namespace {

/// Open addressing hash map uint64 -> int32 (std::unordered_map's node per entry would cost
/// several times the memory of a 12-byte slot).
class KeyMap {
public:
    KeyMap() { rehash(1 << 16); }
    /// Id of \p key, inserting next_id if absent.
    std::int32_t get(std::uint64_t key, std::int32_t next_id)
    {
        if (2 * (size_ + 1) > keys_.size()) rehash(keys_.size() * 2);
        std::size_t h = hash(key) & (keys_.size() - 1);
        while (keys_[h] != kEmpty) {
            if (keys_[h] == key) return vals_[h];
            h = (h + 1) & (keys_.size() - 1);
        }
        keys_[h] = key;
        vals_[h] = next_id;
        ++size_;
        return next_id;
    }

private:
    static constexpr std::uint64_t kEmpty = ~std::uint64_t(0); // keys use 63 bits
    static std::size_t hash(std::uint64_t k)
    {
        k ^= k >> 33;
        k *= 0xff51afd7ed558ccdULL;
        k ^= k >> 33;
        return std::size_t(k);
    }
    void rehash(std::size_t cap)
    {
        std::vector<std::uint64_t> ok = std::move(keys_);
        std::vector<std::int32_t> ov = std::move(vals_);
        keys_.assign(cap, kEmpty);
        vals_.assign(cap, 0);
        for (std::size_t i = 0; i < ok.size(); ++i) {
            if (ok[i] == kEmpty) continue;
            std::size_t h = hash(ok[i]) & (cap - 1);
            while (keys_[h] != kEmpty) h = (h + 1) & (cap - 1);
            keys_[h] = ok[i];
            vals_[h] = ov[i];
        }
    }
    std::vector<std::uint64_t> keys_;
    std::vector<std::int32_t> vals_;
    std::size_t size_ = 0;
};

struct UnionFind {
    std::vector<std::int32_t> p;
    std::int32_t add()
    {
        p.push_back(std::int32_t(p.size()));
        return p.back();
    }
    std::int32_t find(std::int32_t x)
    {
        while (p[std::size_t(x)] != x) x = p[std::size_t(x)] = p[std::size_t(p[std::size_t(x)])];
        return x;
    }
    void unite(std::int32_t a, std::int32_t b)
    {
        a = find(a);
        b = find(b);
        if (a != b) p[std::size_t(std::max(a, b))] = std::min(a, b);
    }
};

/// Planes through the near-critical points of F in the crossed cells (refined_lattice.h): cell
/// saddles and face saddles whose phi is within kNearCritical of the cell's phi range from 0.
/// At most \p max_per_slab per slab, nearest to v first; none closer than 1e-9 to another plane
/// (or to a uniform plane k/R for R in 1..128 - a sub-cell that thin adds nothing).
/// Sharing octree/critical_values.h with the tie rule is safe: a misplaced plane cannot change
/// the reference's topology, only fail to sharpen it.
SlabPlanes near_critical_planes(const TrilinearField& field, const std::vector<Coord>& cells, const Coord& base,
                                int max_per_slab)
{
    constexpr double kNearCritical = 2e-3;
    struct Candidate {
        double closeness; // |phi| / cell range
        int axis;
        std::int64_t slab;
        double t;
    };
    std::vector<Candidate> cand;
    octree::SampleField::Reader reader(field.samples());
    for (const Coord& c : cells) {
        double phi[8];
        reader.cell_corners(c, phi);
        std::array<double, 8> f;
        std::copy(phi, phi + 8, f.begin());
        const auto [lo, hi] = std::minmax_element(f.begin(), f.end());
        const double range = *hi - *lo;
        if (!(range > 0)) continue;
        auto add = [&](double value, const double pos[3], const bool on_axis[3]) {
            const double closeness = std::abs(value) / range;
            if (!(closeness < kNearCritical)) return;
            for (int a = 0; a < 3; ++a)
                if (on_axis[a]) cand.push_back({closeness, a, std::int64_t(c[a] - base[a]), pos[a]});
        };
        octree::CellCritical pts[2];
        const int np = octree::cell_critical_points(f, pts);
        const bool all[3] = {true, true, true};
        for (int k = 0; k < np; ++k) {
            const double pos[3] = {pts[k].x, pts[k].y, pts[k].z};
            add(pts[k].value, pos, all);
        }
        // Faces perpendicular to axis a at offset 0 and 1; (p, q) = the other two axes.
        for (int a = 0; a < 3; ++a) {
            const int p = (a + 1) % 3, q = (a + 2) % 3;
            for (int side = 0; side < 2; ++side) {
                const int b0 = side << a, bp = 1 << p, bq = 1 << q;
                double u, w, value;
                if (!octree::face_saddle(f[b0], f[b0 | bp], f[b0 | bq], f[b0 | bp | bq], u, w, value)) continue;
                double pos[3];
                pos[a] = side;
                pos[p] = u;
                pos[q] = w;
                bool on_axis[3] = {true, true, true};
                on_axis[a] = false;
                add(value, pos, on_axis);
            }
        }
    }
    std::sort(cand.begin(), cand.end(), [](const Candidate& x, const Candidate& y) {
        return std::tie(x.closeness, x.axis, x.slab, x.t) < std::tie(y.closeness, y.axis, y.slab, y.t);
    });
    SlabPlanes planes;
    for (const Candidate& k : cand) {
        auto& slabs = planes.extra[std::size_t(k.axis)];
        if (k.slab < 0) continue;
        if (slabs.size() <= std::size_t(k.slab)) slabs.resize(std::size_t(k.slab) + 1);
        auto& slab = slabs[std::size_t(k.slab)];
        if (int(slab.size()) >= max_per_slab) continue;
        bool clear = true;
        for (double t : slab) clear = clear && std::abs(t - k.t) > 1e-9;
        for (int R = 1; R <= 128 && clear; ++R) clear = std::abs(k.t * R - std::round(k.t * R)) > 1e-9 * R;
        if (!clear) continue;
        slab.insert(std::upper_bound(slab.begin(), slab.end(), k.t), k.t);
    }
    return planes;
}

/// Components of the marching-tetrahedra surface at refinement R, sorted by (genus, triangles).
std::vector<ComponentTopology> topology_at(const TrilinearField& field, const std::vector<Coord>& cells,
                                         const Coord& base, int R, const SlabPlanes& planes)
{
    KeyMap ids;
    UnionFind uf;
    std::vector<std::int32_t> tri_vertex; // one vertex per triangle, to count F per component
    CellRefiner refiner(R, &planes, base);
    octree::SampleField::Reader reader(field.samples());
    // An edge inside the cell (off its faces) belongs to this cell alone, so its id lives in a
    // dense per-cell table (stamped by cell) instead of the global map, whose lookups miss the
    // cache. The ids are handed out in the same order either way. The table has 8 entries per
    // sub-lattice point of a cell, so past kDenseMax (32 MiB of ids and stamps; R = 64 takes 17 MiB)
    // every edge goes to the global map.
    constexpr std::size_t kDenseMax = std::size_t(1) << 22;
    std::vector<std::int32_t> local_id;
    std::vector<std::uint32_t> local_stamp;
    std::uint32_t stamp = 0;
    for (const Coord& c : cells) {
        ++stamp;
        bool sized = false, dense = false;
        std::int64_t o[3] = {0, 0, 0};
        int n[3] = {0, 0, 0};
        refiner.run<false>(reader, c, [&](const RefTriangle& t) {
            if (!sized) {
                sized = true;
                for (int a = 0; a < 3; ++a) {
                    o[a] = refiner.origin(a);
                    n[a] = refiner.planes(a);
                }
                const std::size_t need = 8 * std::size_t(n[0]) * std::size_t(n[1]) * std::size_t(n[2]);
                dense = need <= kDenseMax;
                if (dense && local_id.size() < need) {
                    local_id.resize(need);
                    local_stamp.resize(need, 0);
                }
            }
            std::int32_t v[3];
            for (int q = 0; q < 3; ++q) {
                const std::uint64_t key = t.key[q];
                const unsigned dir = unsigned(key & 7u);
                const int l[3] = {int(std::int64_t((key >> 43) & 0xFFFFF) - o[0]),
                                  int(std::int64_t((key >> 23) & 0xFFFFF) - o[1]),
                                  int(std::int64_t((key >> 3) & 0xFFFFF) - o[2])};
                bool interior = dense;
                for (int a = 0; a < 3; ++a)
                    interior = interior && ((dir >> a & 1u) || (l[a] > 0 && l[a] < n[a] - 1));
                const std::int32_t next = std::int32_t(uf.p.size());
                if (interior) {
                    const std::size_t i = 8 * (std::size_t(l[0]) + std::size_t(n[0]) * (std::size_t(l[1]) + std::size_t(n[1]) * std::size_t(l[2]))) + dir;
                    if (local_stamp[i] != stamp) {
                        local_stamp[i] = stamp;
                        local_id[i] = next;
                    }
                    v[q] = local_id[i];
                } else {
                    v[q] = ids.get(key, next);
                }
                if (v[q] == next) uf.add();
            }
            uf.unite(v[0], v[1]);
            uf.unite(v[0], v[2]);
            tri_vertex.push_back(v[0]);
        });
    }
    std::vector<std::int64_t> nv(uf.p.size(), 0), nf(uf.p.size(), 0);
    for (std::size_t i = 0; i < uf.p.size(); ++i) ++nv[std::size_t(uf.find(std::int32_t(i)))];
    for (std::int32_t v : tri_vertex) ++nf[std::size_t(uf.find(v))];
    std::vector<ComponentTopology> out;
    for (std::size_t r = 0; r < nv.size(); ++r) {
        if (nv[r] == 0 || uf.p[r] != std::int32_t(r)) continue;
        if (nf[r] % 2 != 0) throw Error("verify: reference surface not closed (odd triangle count)");
        ComponentTopology comp;
        comp.euler = int(nv[r] - nf[r] / 2);
        comp.genus = (2 - comp.euler) / 2;
        comp.triangles = std::size_t(nf[r]);
        out.push_back(comp);
    }
    std::sort(out.begin(), out.end(), [](const ComponentTopology& a, const ComponentTopology& b) {
        return a.genus != b.genus ? a.genus < b.genus : a.triangles < b.triangles;
    });
    return out;
}

std::vector<int> genera(const std::vector<ComponentTopology>& comps)
{
    std::vector<int> g;
    for (const auto& c : comps) g.push_back(c.genus);
    return g; // already sorted by genus
}

} // namespace

ReferenceTopologyReport reference_topology(const TrilinearField& field, int refine, int max_refine, double budget)
{
    const auto t0 = std::chrono::steady_clock::now();
    ReferenceTopologyReport rep;
    Coord base;
    const std::vector<Coord> cells = crossed_cells(field, base);
    rep.crossed_cells = cells.size();
    const SlabPlanes planes = near_critical_planes(field, cells, base, 16);
    rep.critical_planes = planes.count();
    // R, 2R, then (if they disagree) keep doubling while within max_refine: near-critical data
    // (a saddle value close to v) needs a finer lattice before the PL surface settles.
    // R itself is raised above \p refine while the 2R level stays within \p budget sub-lattice
    // samples: on random data R = 4 and 8 can agree on a spurious handle of the PL surface
    // that finer lattices no longer show, and small volumes can afford much finer lattices.
    const double per_cell = budget / double(std::max<std::size_t>(cells.size(), 1));
    refine = std::max(refine, std::min(16, int(std::floor(std::cbrt(per_cell) / 2.0))));
    std::vector<ComponentTopology> prev = topology_at(field, cells, base, refine, planes);
    rep.refinements.push_back(refine);
    rep.genera.push_back(genera(prev));
    for (int R = 2 * refine;; R *= 2) {
        std::vector<ComponentTopology> cur = topology_at(field, cells, base, R, planes);
        rep.refinements.push_back(R);
        rep.genera.push_back(genera(cur));
        if (rep.genera[rep.genera.size() - 2] == rep.genera.back()) {
            rep.determined = true;
            rep.components = std::move(cur);
            break;
        }
        const bool affordable = max_refine > 0 && double(cells.size()) * std::pow(2.0 * R, 3) <= 1.5 * budget;
        if (2 * R > std::max(max_refine, 2 * refine) && !affordable) {
            rep.components = std::move(cur);
            break;
        }
        prev = std::move(cur);
    }
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return rep;
}

} // namespace isodel::verify

namespace isodel {

ReferenceTopologyReport reference_topology(const openvdb::FloatGrid& grid, double isovalue,
                                           Inside inside, int refine, int max_refine, double budget)
{
    verify::TrilinearField field(grid, isovalue, inside);
    return verify::reference_topology(field, refine, max_refine, budget);
}

} // namespace isodel
