// FacetCache (src/closed_ball/restricted_facets.h) is maintained incrementally: insert() drops the
// records of the facets an insertion destroys, update() computes those of the new ones, and
// only facets whose Voronoi edge crosses Sigma (or left its bound) keep a record. After any
// sequence of insertions and updates, its active facets and restricted stars must equal those
// of a fresh cache scanning the same triangulation; so must they after remove() takes vertices
// out (the tets phase removes grid points next to M that way).
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include "closed_ball/restricted_facets.h"
#include "octree/sample_field.h"

#include <random>

using namespace isodel;
using namespace isodel::mesher;

namespace {

struct Summary {
    std::vector<std::tuple<FacetKey, int, bool>> active;
    std::vector<std::vector<FacetKey>> stars;
    std::vector<FacetKey> overflow, multiple, grid_vertex, far;
};

Summary summarise(const FacetCache& cache)
{
    Summary s;
    s.overflow = cache.flagged().overflow;
    s.multiple = cache.flagged().multiple;
    s.grid_vertex = cache.flagged().grid_vertex;
    s.far = cache.flagged().far;
    for (const auto& e : cache.active()) s.active.emplace_back(e.key, int(e.crossings), e.overflow);
    for (std::uint32_t id = 0; id < cache.vertex_id_bound(); ++id) {
        std::vector<FacetKey> keys;
        for (const auto& f : cache.restricted_star(id)) keys.push_back(f.key);
        s.stars.push_back(keys);
    }
    while (!s.stars.empty() && s.stars.back().empty()) s.stars.pop_back();
    return s;
}

/// The classes the closed-ball checks read, kept incrementally (FacetCache::flagged), equal in
/// \p a and a fresh scan \p b, each of them present (random points make all but the overflow class).
void check_same_flagged(const Summary& a, const Summary& b)
{
    CHECK(a.overflow == b.overflow);
    CHECK(a.multiple == b.multiple);
    CHECK(a.grid_vertex == b.grid_vertex);
    CHECK(a.far == b.far);
    CHECK(!b.multiple.empty());
    CHECK(!b.grid_vertex.empty());
    CHECK(!b.far.empty());
}

/// The 7^3 grid points and 150 random E points; returns the next free id.
std::uint32_t grid_and_edge_points(Delaunay& dt, std::mt19937& rng, std::uniform_real_distribution<double>& u)
{
    std::uint32_t id = 0;
    for (int z = 0; z <= 6; ++z)
        for (int y = 0; y <= 6; ++y)
            for (int x = 0; x <= 6; ++x) dt.insert(Point(x, y, z))->info() = VertexInfo{id++, PointKind::Grid};
    for (int i = 0; i < 150; ++i) dt.insert(Point(u(rng), u(rng), u(rng)))->info() = VertexInfo{id++, PointKind::Edge};
    return id;
}

} // namespace

TEST_CASE("facet cache: incremental records equal a fresh scan after insertions", "[mesher][facet_cache]")
{
    for (unsigned seed = 1; seed <= 3; ++seed) {
        INFO("random 5^3 volume, seed " << seed);
        const auto grid = testing::random_volume(5, seed, false);
        const octree::SampleField field(grid, 0.0, Inside::Above);
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.5, 5.5);
        Delaunay dt;
        std::uint32_t id = grid_and_edge_points(dt, rng, u);
        FacetCache cache;
        cache.set_far_distance(0.3);
        cache.update(dt, field, 1000);
        std::size_t active = 0;
        for (int round = 0; round < 6; ++round) {
            for (int i = 0; i < 40; ++i) {
                const auto kind = i % 3 == 0 ? PointKind::Grid : PointKind::Topology;
                if (cache.insert(dt, Point(u(rng), u(rng), u(rng)), VertexInfo{id, kind}) != Vertex_handle()) ++id;
            }
            cache.update(dt, field, 1000);
            // Read active() between rounds too: it merges the pending changes lazily.
            if (round % 2 == 0) active = cache.active().size();
        }
        FacetCache fresh;
        fresh.set_far_distance(0.3);
        fresh.update(dt, field, 1000);
        const Summary a = summarise(cache), b = summarise(fresh);
        CHECK(active > 0);
        CHECK(a.active.size() == b.active.size());
        CHECK(a.active == b.active);
        CHECK(a.stars == b.stars);
        check_same_flagged(a, b);
    }
}

TEST_CASE("facet cache: incremental records equal a fresh scan after removals", "[mesher][facet_cache]")
{
    for (unsigned seed = 1; seed <= 3; ++seed) {
        INFO("random 5^3 volume, seed " << seed);
        const auto grid = testing::random_volume(5, seed, false);
        const octree::SampleField field(grid, 0.0, Inside::Above);
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.5, 5.5);
        Delaunay dt;
        std::uint32_t id = grid_and_edge_points(dt, rng, u);
        FacetCache cache;
        cache.set_far_distance(0.3);
        cache.update(dt, field, 1000);
        std::size_t removed = 0;
        for (int round = 0; round < 6; ++round) {
            // Inserted points, some removed again before the update, and older vertices of
            // every kind (grid points on the hull too), neighbours among them.
            std::vector<Vertex_handle> fresh;
            for (int i = 0; i < 20; ++i) {
                const auto kind = i % 3 == 0 ? PointKind::Grid : PointKind::Topology;
                const Vertex_handle v = cache.insert(dt, Point(u(rng), u(rng), u(rng)), VertexInfo{id, kind});
                if (v != Vertex_handle()) ++id, fresh.push_back(v);
            }
            std::vector<Vertex_handle> batch(fresh.begin(), fresh.begin() + std::ptrdiff_t(fresh.size() / 4));
            std::vector<Vertex_handle> all;
            for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) all.push_back(v);
            std::sort(all.begin(), all.end(), [](Vertex_handle a, Vertex_handle b) { return a->info().id < b->info().id; });
            for (std::size_t i = std::size_t(round); i < all.size(); i += 17)
                if (std::find(batch.begin(), batch.end(), all[i]) == batch.end()) batch.push_back(all[i]);
            const Vertex_handle first = batch.front();
            for (const Vertex_handle& n : std::vector<Vertex_handle>{first->cell()->vertex(0), first->cell()->vertex(1)})
                if (!dt.is_infinite(n) && std::find(batch.begin(), batch.end(), n) == batch.end()) batch.push_back(n);
            removed += batch.size();
            cache.remove(dt, batch);
            cache.update(dt, field, 1000);
            if (round % 2 == 0) CHECK(cache.active().size() > 0);
        }
        REQUIRE(dt.is_valid());
        FacetCache fresh;
        fresh.set_far_distance(0.3);
        fresh.update(dt, field, 1000);
        const Summary a = summarise(cache), b = summarise(fresh);
        CHECK(removed > 60);
        CHECK(a.active.size() == b.active.size());
        CHECK(a.active == b.active);
        CHECK(a.stars == b.stars);
        check_same_flagged(a, b);
    }
}
