#include "octree/sample_field.h"

#include "octree/critical_values.h"
#include "octree/stored_tiles.h"

#include <isodel/errors.h>

#include <openvdb/tree/LeafManager.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace isodel::octree {

namespace {

using Tree = openvdb::FloatTree;
using LeafRange = openvdb::tree::LeafManager<const Tree>::LeafRange;

/// What the constructor learns from the samples and the face/cell saddles: the value range,
/// whether one equals v (a tie, within rounding for a saddle), and the gap below v.
struct ValueScan {
    explicit ValueScan(double isovalue) : v(isovalue), round_off(1e-12 * std::max(1.0, std::abs(isovalue))) {}
    double v, round_off;
    double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
    bool tie = false;
    double gap = std::numeric_limits<double>::infinity();

    void consider(double f)
    {
        vmin = std::min(vmin, f);
        vmax = std::max(vmax, f);
        if (f == v) tie = true;
        else if (f < v) gap = std::min(gap, v - f);
    }
    /// A saddle's value is a quotient or a square root: a tie is within rounding of v.
    void critical(double f)
    {
        if (std::abs(f - v) <= round_off) tie = true;
        else if (f < v) gap = std::min(gap, v - f);
    }
    /// Minima, maxima and an "or": the same result in any order, so at any thread count.
    void join(const ValueScan& o)
    {
        vmin = std::min(vmin, o.vmin);
        vmax = std::max(vmax, o.vmax);
        tie = tie || o.tie;
        gap = std::min(gap, o.gap);
    }
};

/// The leaves of \p tree in parallel, each thread folding into its own copy of \p scan.
template <typename Body>
void for_each_leaf(const Tree& tree, ValueScan& scan, const Body& body)
{
    openvdb::tree::LeafManager<const Tree> leaves(tree);
    tbb::enumerable_thread_specific<ValueScan> local(scan);
    tbb::parallel_for(leaves.leafRange(), [&](const LeafRange& range) {
        ValueScan& mine = local.local();
        for (auto leaf = range.begin(); leaf; ++leaf) body(*leaf, mine);
    });
    for (const ValueScan& s : local) scan.join(s);
}

/// Every stored value of the domain: active voxels and tiles, and inactive ones inside the
/// lattice (anywhere when the ring reads the background). Tiles are read once, never expanded;
/// inactive tiles of the background value are skipped (stored_tiles.h), since the constructor
/// counts the background itself whenever an inactive sample can read it.
void scan_stored_values(const openvdb::FloatGrid& grid, const CoordBBox& lattice, bool ring_reads_background,
                        ValueScan& scan)
{
    for_each_stored_tile(grid.tree(), [&](const CoordBBox& b, float value, bool active) {
        // Inactive tiles beyond the lattice are read only through a ring that reads the background.
        if (!active && !ring_reads_background && !lattice.hasOverlap(b)) return;
        scan.consider(value);
    });
    for_each_leaf(grid.tree(), scan, [&](const Tree::LeafNodeType& leaf, ValueScan& mine) {
        for (auto v = leaf.cbeginValueAll(); v; ++v)
            if (v.isValueOn() || ring_reads_background || lattice.isInside(v.getCoord())) mine.consider(*v);
    });
}

/// Critical values of the faces and cells (critical_values.h) bound the shift like samples do:
/// {F >= t} changes topology only at them, so v* = v - d with d below the gap has the topology
/// of the limit. A bilinear face saddle exactly at v (corners (1,-1,-1,1) at v = 0) makes Sigma
/// non-manifold just like a sample at v and follows the same rule; so does a cell's interior
/// saddle. Only faces and cells whose corners straddle v matter (otherwise a corner sample is
/// nearer to v than the saddle), and only those with a corner on an active voxel.
void scan_critical_values(const openvdb::FloatGrid& grid, const CoordBBox& lattice, bool ring_reads_background,
                          ValueScan& scan)
{
    const double v = scan.v;
    tbb::enumerable_thread_specific<openvdb::FloatGrid::ConstAccessor> accessors([&] { return grid.getConstAccessor(); });
    for_each_leaf(grid.tree(), scan, [&](const Tree::LeafNodeType& leaf, ValueScan& mine) {
        auto& acc = accessors.local();
        for (auto it = leaf.cbeginValueOn(); it; ++it) {
            const Coord c = it.getCoord();
            // A face or cell reaching into a ring that reads as outside is not one of F's samples.
            const bool whole_cell = ring_reads_background || lattice.isInside(c.offsetBy(1));
            auto corner = [&](int n) { return c.offsetBy(n & 1, (n >> 1) & 1, (n >> 2) & 1); }; // bits x, y, z
            std::array<double, 8> f;
            for (int n = 0; n < 8; ++n) f[n] = acc.getValue(corner(n));
            for (int axis = 0; axis < 3; ++axis) {
                const int e1 = 1 << ((axis + 1) % 3), e2 = 1 << ((axis + 2) % 3);
                if (!ring_reads_background && !lattice.isInside(corner(e1 | e2))) continue;
                const double a = f[0], b = f[e1], cc = f[e2], d = f[e1 | e2];
                if (std::min({a, b, cc, d}) > v || std::max({a, b, cc, d}) < v) continue;
                double sv;
                if (face_saddle_value(a, b, cc, d, sv)) mine.critical(sv);
            }
            if (!whole_cell) continue;
            const auto [lo, hi] = std::minmax_element(f.begin(), f.end());
            if (*lo > v || *hi < v) continue;
            CellCritical points[2];
            const int np = cell_critical_points(f, points);
            for (int k = 0; k < np; ++k) mine.critical(points[k].value);
        }
    });
}

} // namespace

SampleField::SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside)
    : SampleField(std::move(grid), isovalue, inside, std::nullopt)
{
}

SampleField::SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside, double v_star)
    : SampleField(std::move(grid), isovalue, inside, std::optional<double>(v_star))
{
}

SampleField::SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside,
                         std::optional<double> v_star)
    : grid_(std::move(grid)), isovalue_(isovalue), effective_(isovalue), inside_(inside),
      sign_(inside == Inside::Above ? 1.0 : -1.0)
{
    if (!grid_) throw InvalidInput("null grid");
    const CoordBBox active = grid_->evalActiveVoxelBoundingBox();
    if (active.empty() || grid_->activeVoxelCount() == 0)
        throw InvalidInput("grid '" + grid_->getName() + "' is empty (no active voxels)");
    domain_ = active;
    domain_.expand(1);

    // One pass over the domain: value range, whether a sample equals v, and the gap below v.
    // Samples outside the active voxels read as background/tiles, which count too. Leaves are
    // scanned in parallel; the results are minima, maxima and an "or", so the same at any
    // thread count.
    lattice_ = active;
    const double bg = grid_->background();
    ring_reads_background_ = sign_ * (bg - isovalue) < 0;
    ValueScan scan(isovalue);
    scan_stored_values(*grid_, lattice_, ring_reads_background_, scan);
    // Inactive samples of the domain (background, inactive tiles). The ring around the active
    // box reads the background only when it is strictly outside (see the header: a dense file's
    // lattice is its box, and a background at or inside v - MRC's 0 at v = 0 - would wrap the
    // box in a spurious shell); inside the lattice, inactive voxels read it whenever they exist.
    if (ring_reads_background_ || std::uint64_t(grid_->activeVoxelCount()) < active.volume()) scan.consider(bg);
    // The saddles matter for the range check below only when v is not strictly inside the range.
    if (!v_star || !(isovalue > scan.vmin && isovalue < scan.vmax))
        scan_critical_values(*grid_, lattice_, ring_reads_background_, scan);
    const double vmin = scan.vmin, vmax = scan.vmax, gap = scan.gap;
    const bool tie = scan.tie;
    vmin_ = vmin;
    vmax_ = vmax;
    if (!(isovalue > vmin && isovalue < vmax) && !(tie && vmin < vmax)) {
        std::ostringstream os;
        os << "isovalue " << isovalue << " is outside the value range [" << vmin << ", " << vmax
           << "] of grid '" << grid_->getName() << "': the level set is empty";
        throw InvalidInput(os.str());
    }
    if (v_star) {
        effective_ = *v_star;
    } else if (tie) {
        const double span = vmax - vmin;
        double d = std::min(0.5 * gap, 1e-2 * span);
        if (!(d > 0)) d = 1e-2 * span;
        effective_ = isovalue - d;
    }
    // Outside samples sit clearly on the outside side.
    outside_magnitude_ = std::max(1.0, vmax - vmin);

    const auto& xf = grid_->transform();
    min_edge_ = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        Vec3d e(0.0);
        e[a] = 1.0;
        const Vec3d w = xf.indexToWorld(e) - xf.indexToWorld(Vec3d(0.0));
        min_edge_ = std::min(min_edge_, w.length());
    }
    for (int n = 0; n < 8; ++n) {
        const Vec3d d(n & 1 ? 1.0 : -1.0, n & 2 ? 1.0 : -1.0, n & 4 ? 1.0 : -1.0);
        unit_slab_shift_ = std::max(unit_slab_shift_, (xf.indexToWorld(d) - xf.indexToWorld(Vec3d(0.0))).length());
    }
}

FaceSlabs SampleField::face_slabs_for_eps_world(double eps) const
{
    FaceSlabs s = face_slabs_for_eps(eps / min_edge_);
    if (unit_slab_shift_ > 0) s.h = std::min(s.h, kMaxSlabShift * eps / unit_slab_shift_);
    return s;
}

SampleField::SampleField(const SampleField& parent, const CoordBBox& clip) : SampleField(parent)
{
    // Beyond domain() every sample reads as outside (Reader::phi), so clipping the domain is
    // the whole change; the mesher's loops (edge crossings, protective layer) run over
    // domain(), so a block costs its box, not the grid's.
    domain_.intersect(clip);
    if (domain_.empty()) throw InvalidInput("block box misses the grid's domain");
}

} // namespace isodel::octree
