#include "surface/block_mesher.h"

#include "delaunay/circumcenter.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace isodel::mesher {

BlockMesher::BlockMesher(const octree::SampleField& field, const BlockSpec& block, const MeshOptions& options,
                         int trusted_margin, Interrupter* interrupter)
    : spec_(block), options_(options)
{
    openvdb::CoordBBox box = block.box;
    box.intersect(field.domain());
    // The trusted box: the box less the margin on its inner faces. On the domain's faces the
    // block's field is the global one out to the ring and beyond, so nothing is cut there.
    const openvdb::CoordBBox& d = field.domain();
    for (int a = 0; a < 3; ++a) {
        trusted_lo_[a] = box.min()[a] <= d.min()[a] ? -HUGE_VAL : box.min()[a] + trusted_margin;
        trusted_hi_[a] = box.max()[a] >= d.max()[a] ? HUGE_VAL : box.max()[a] - trusted_margin;
    }
    // A world ball of radius r spans r * |row a of the inverse linear map| along index axis a.
    const openvdb::Vec3d o = field.world_to_index(openvdb::Vec3d(0.0));
    openvdb::Vec3d sq(0.0);
    for (int j = 0; j < 3; ++j) {
        openvdb::Vec3d e(0.0);
        e[j] = 1.0;
        const openvdb::Vec3d col = field.world_to_index(e) - o;
        for (int a = 0; a < 3; ++a) sq[a] += col[a] * col[a];
    }
    for (int a = 0; a < 3; ++a) ball_axis_scale_[a] = std::sqrt(sq[a]);
    if (box.empty()) return;

    field_ = &field;
    box_ = box;
    options_.threads = 0; // the caller's limit holds; nested TBB work shares it
    options_.tets = TetRegion::None;
    options_.block_voxels = 0;
    options_.block_count = 0;
    // eps in world units of the whole field, so that every block refines to the same bound.
    if (options_.eps <= 0) options_.eps = options.eps_voxels * field.min_voxel_edge();
    st_.effective_isovalue = field.effective_isovalue();
    interrupter_ = interrupter;
    build(interrupter);
}

void BlockMesher::build(Interrupter* interrupter)
{
    FieldRun run;
    run.field = field_;
    run.point_box = &box_;
    run.seeds = seeds_;
    CandidateFilter keep = [this](const Point& p) { return owns({p.x(), p.y(), p.z()}); };
    CandidateFilter near = [this](const Point& p) { return near_own({p.x(), p.y(), p.z()}); };
    // A rebuild counts E, G, the tube points and the seeds again: they were counted the first time.
    const MeshStats before = st_;
    pipeline_ = std::make_unique<SurfacePipeline>(run, options_, std::move(keep), std::move(near), st_, interrupter);
    if (built_) {
        st_.e_points = before.e_points;
        st_.g_points = before.g_points;
        st_.snapped = before.snapped;
        st_.n_topology = before.n_topology;
        st_.n_geometry = before.n_geometry;
    }
    built_ = true;
    if (pipeline_->empty()) return;
    // G's repairs (own or a neighbour's) come back as seeds: G's mask holds them, as the kept
    // block's did, so that a later repair does not add them again.
    bool grid_seeds = false;
    for (const SeedPoint& seed : seeds_) grid_seeds = grid_seeds || seed.kind == PointKind::Grid;
    if (grid_seeds) {
        auto acc = pipeline_->g_mask().get().getAccessor();
        for (const SeedPoint& seed : seeds_) {
            if (seed.kind != PointKind::Grid) continue;
            const openvdb::Vec3d q = field_->world_to_index({seed.p[0], seed.p[1], seed.p[2]});
            acc.setValueOn(openvdb::Coord(int(std::lround(q[0])), int(std::lround(q[1])), int(std::lround(q[2]))));
        }
    }
    next_unsent_ = pipeline_->first_inserted();
    pipeline_->refiner().measure_voxel_bound();
}

void BlockMesher::park()
{
    if (parked_ || empty()) return;
    if (!counted_) {
        own_e_ = own_edge_points();
        own_g_ = own_grid_points();
        counted_ = true;
    }
    unsent_ = take_new_points();
    parked_surface_ = compute_owned_surface();
    std::vector<std::pair<std::uint32_t, SeedPoint>> later;
    const Delaunay& dt = pipeline_->dt();
    const std::uint32_t first = pipeline_->first_inserted();
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        if (v->info().id >= first)
            later.push_back({v->info().id, SeedPoint{{v->point().x(), v->point().y(), v->point().z()}, v->info().kind}});
    std::sort(later.begin(), later.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [id, seed] : later) seeds_.push_back(seed);
    pipeline_.reset();
    parked_ = true;
}

openvdb::Vec3d BlockMesher::index_of(const Point& p) const
{
    return pipeline_->field().world_to_index({p.x(), p.y(), p.z()});
}

bool BlockMesher::reads(const std::array<double, 3>& w) const
{
    if (!field_) return false;
    const openvdb::Vec3d q = field_->world_to_index({w[0], w[1], w[2]});
    for (int a = 0; a < 3; ++a)
        if (!(q[a] >= box_.min()[a] && q[a] <= box_.max()[a])) return false;
    return true;
}

bool BlockMesher::owns(const std::array<double, 3>& w) const
{
    const openvdb::Vec3d q = field_->world_to_index({w[0], w[1], w[2]});
    for (int a = 0; a < 3; ++a)
        if (!(q[a] >= spec_.own_lo[a] && q[a] < spec_.own_hi[a])) return false;
    return true;
}

bool BlockMesher::near_own(const std::array<double, 3>& w) const
{
    const openvdb::Vec3d q = field_->world_to_index({w[0], w[1], w[2]});
    for (int a = 0; a < 3; ++a)
        if (!(q[a] >= spec_.own_lo[a] - kNearVoxels && q[a] < spec_.own_hi[a] + kNearVoxels)) return false;
    return true;
}

void BlockMesher::refine()
{
    if (!empty() && !parked_) stalled_ = !pipeline_->refiner().run(true);
}

std::vector<SeedPoint> BlockMesher::take_new_points()
{
    std::vector<std::pair<std::uint32_t, SeedPoint>> fresh;
    if (parked_) return std::move(unsent_);
    if (empty()) return {};
    const Delaunay& dt = pipeline_->dt();
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
        const VertexInfo& info = v->info();
        if (info.id < next_unsent_) continue;
        const Point& p = v->point();
        fresh.push_back({info.id, SeedPoint{{p.x(), p.y(), p.z()}, info.kind}});
    }
    std::sort(fresh.begin(), fresh.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    next_unsent_ = pipeline_->refiner().next_id();
    std::vector<SeedPoint> out;
    out.reserve(fresh.size());
    for (const auto& [id, s] : fresh) out.push_back(s);
    return out;
}

std::size_t BlockMesher::receive(const std::vector<SeedPoint>& points)
{
    if (empty()) return 0;
    std::vector<std::pair<Point, PointKind>> mine;
    for (const SeedPoint& s : points)
        if (reads(s.p)) mine.emplace_back(Point(s.p[0], s.p[1], s.p[2]), s.kind);
    if (mine.empty()) return 0;
    const bool rebuilt = parked_;
    if (parked_) {
        build(interrupter_);
        parked_ = false;
        ++rebuilds_;
    }
    const std::size_t added = pipeline_->refiner().insert_received(mine);
    next_unsent_ = pipeline_->refiner().next_id(); // what it received is not its own to hand out
    if (rebuilt && added == 0) {
        // Nothing new: no refine() follows, so the rebuilt block's facet records were never
        // computed. The parked state (facets, points) is still the block's: keep it.
        pipeline_.reset();
        parked_ = true;
    }
    return added;
}

bool BlockMesher::ball_trusted(const Cell_handle& c) const
{
    if (pipeline_->dt().is_infinite(c)) return false;
    const Point center = robust_circumcenter(c);
    const double r = std::sqrt(CGAL::squared_distance(center, c->vertex(0)->point()));
    const openvdb::Vec3d q = index_of(center);
    for (int a = 0; a < 3; ++a) {
        const double h = r * ball_axis_scale_[a];
        if (!(q[a] - h >= trusted_lo_[a] && q[a] + h <= trusted_hi_[a])) return false;
    }
    return true;
}

BlockSurface BlockMesher::owned_surface() const
{
    return parked_ ? parked_surface_ : compute_owned_surface();
}

BlockSurface BlockMesher::compute_owned_surface() const
{
    BlockSurface out;
    if (empty()) return out;
    const auto by_position = [](Vertex_handle a, Vertex_handle b) {
        const Point &p = a->point(), &q = b->point();
        return std::make_tuple(p.x(), p.y(), p.z()) < std::make_tuple(q.x(), q.y(), q.z());
    };
    for (const auto& e : pipeline_->refiner().cache().active()) {
        if (e.crossings != 1) continue;
        auto vs = facet_vertices(e.facet);
        // The owner: the facet's smallest vertex (by coordinates, so every block names the same).
        const Vertex_handle owner = *std::min_element(vs.begin(), vs.end(), by_position);
        const Point& o = owner->point();
        if (!owns({o.x(), o.y(), o.z()})) continue;
        const Cell_handle c = e.facet.first;
        if (!ball_trusted(c) || !ball_trusted(c->neighbor(e.facet.second))) {
            ++out.balls_outside;
            continue;
        }
        // Orient as extract_surface does: the normal along the Voronoi edge's inside -> outside.
        const Vector n = CGAL::cross_product(vs[1]->point() - vs[0]->point(), vs[2]->point() - vs[0]->point());
        if (n * e.record->outward < 0) std::swap(vs[1], vs[2]);
        WorldTriangle t;
        for (int i = 0; i < 3; ++i) t[i] = {vs[i]->point().x(), vs[i]->point().y(), vs[i]->point().z()};
        out.triangles.push_back(t);
    }
    return out;
}

template <class Counted>
std::size_t BlockMesher::count_own(Counted counted) const
{
    std::size_t n = 0;
    if (empty()) return n;
    const Delaunay& dt = pipeline_->dt();
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        if (counted(v->info()) && owns({v->point().x(), v->point().y(), v->point().z()})) ++n;
    return n;
}

std::size_t BlockMesher::own_edge_points() const
{
    if (counted_) return own_e_;
    return count_own([](const VertexInfo& i) { return i.kind == PointKind::Edge || i.kind == PointKind::Snapped; });
}

std::size_t BlockMesher::own_grid_points() const
{
    // G as the first triangulation had it: the repairs come later, and are counted apart.
    if (counted_) return own_g_;
    const std::uint32_t first = pipeline_ ? pipeline_->first_inserted() : 0;
    return count_own([first](const VertexInfo& i) { return i.kind == PointKind::Grid && i.id < first; });
}

} // namespace isodel::mesher
