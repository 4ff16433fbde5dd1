#include "octree/sample_field.h"

#include "octree/critical_values.h"

#include <isodel/errors.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace isodel::octree {

SampleField::SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside)
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
    // Samples outside the active voxels read as background/tiles, which count too.
    double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
    bool tie = false;
    double gap = std::numeric_limits<double>::infinity();
    auto consider = [&](double f) {
        vmin = std::min(vmin, f);
        vmax = std::max(vmax, f);
        if (f == isovalue) tie = true;
        else if (f < isovalue) gap = std::min(gap, isovalue - f);
    };
    for (auto it = grid_->cbeginValueOn(); it; ++it) {
        const double f = *it;
        if (it.isVoxelValue()) consider(f);
        else consider(f); // tiles: one value for the whole tile
    }
    // Inactive samples of the domain (background, inactive tiles). The ring around the active
    // box reads the background only when it is strictly outside (see the header: a dense file's
    // lattice is its box, and a background at or inside v - MRC's 0 at v = 0 - would wrap the
    // box in a spurious shell); inside the lattice, inactive voxels read it whenever they exist.
    lattice_ = active;
    const double bg = grid_->background();
    ring_reads_background_ = sign_ * (bg - isovalue) < 0;
    if (ring_reads_background_ || std::uint64_t(grid_->activeVoxelCount()) < active.volume()) consider(bg);
    for (auto it = grid_->cbeginValueOff(); it; ++it) {
        // Inactive tiles beyond the lattice are read only through a ring that reads the background.
        if (!ring_reads_background_ && !lattice_.hasOverlap(it.getBoundingBox())) continue;
        consider(*it);
    }
    // Critical values of the faces and cells (critical_values.h) bound the shift like samples do:
    // {F >= t} changes topology only at them, so v* = v - d with d below the gap has the topology
    // of the limit. A bilinear face saddle exactly at v (corners (1,-1,-1,1) at v = 0) makes Sigma
    // non-manifold just like a sample at v and follows the same rule; so does a cell's interior
    // saddle; both within rounding of v (a quotient, a square root). Only faces and cells
    // whose corners straddle v matter: otherwise a corner sample is nearer to v than the saddle.
    {
        const double round_off = 1e-12 * std::max(1.0, std::abs(isovalue));
        auto critical = [&](double f) {
            if (std::abs(f - isovalue) <= round_off) tie = true;
            else if (f < isovalue) gap = std::min(gap, isovalue - f);
        };
        auto acc = grid_->getConstAccessor();
        for (auto it = grid_->cbeginValueOn(); it; ++it) {
            if (!it.isVoxelValue()) continue;
            const Coord c = it.getCoord();
            // A face or cell reaching into a ring that reads as outside is not one of F's samples.
            const bool whole_cell = ring_reads_background_ || lattice_.isInside(c.offsetBy(1));
            auto corner = [&](int n) { return c.offsetBy(n & 1, (n >> 1) & 1, (n >> 2) & 1); }; // bits x, y, z
            std::array<double, 8> f;
            for (int n = 0; n < 8; ++n) f[n] = acc.getValue(corner(n));
            for (int axis = 0; axis < 3; ++axis) {
                const int e1 = 1 << ((axis + 1) % 3), e2 = 1 << ((axis + 2) % 3);
                if (!ring_reads_background_ && !lattice_.isInside(corner(e1 | e2))) continue;
                const double a = f[0], b = f[e1], cc = f[e2], d = f[e1 | e2];
                if (std::min({a, b, cc, d}) > isovalue || std::max({a, b, cc, d}) < isovalue) continue;
                double s;
                if (face_saddle_value(a, b, cc, d, s)) critical(s);
            }
            if (!whole_cell) continue;
            const auto [lo, hi] = std::minmax_element(f.begin(), f.end());
            if (*lo > isovalue || *hi < isovalue) continue;
            CellCritical points[2];
            const int np = cell_critical_points(f, points);
            for (int k = 0; k < np; ++k) critical(points[k].value);
        }
    }
    vmin_ = vmin;
    vmax_ = vmax;
    if (!(isovalue > vmin && isovalue < vmax) && !(tie && vmin < vmax)) {
        std::ostringstream os;
        os << "isovalue " << isovalue << " is outside the value range [" << vmin << ", " << vmax
           << "] of grid '" << grid_->getName() << "': the level set is empty";
        throw InvalidInput(os.str());
    }
    if (tie) {
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
