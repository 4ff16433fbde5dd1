#include "octree/sample_field.h"

#include <isodel/errors.h>

#include <algorithm>
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
    // Bilinear saddles of cell faces exactly at v (e.g. corners (1,-1,-1,1) at v = 0) make Sigma
    // non-manifold just like a sample at v; they follow the same rule (Sigma is the limit from
    // below), and saddles just below v bound the shift like samples do. Only faces whose corners
    // straddle v can hold one. (Saddles inside a cell are not considered.)
    {
        auto acc = grid_->getConstAccessor();
        for (auto it = grid_->cbeginValueOn(); it; ++it) {
            if (!it.isVoxelValue()) continue;
            const Coord c = it.getCoord();
            const double a = *it;
            for (int axis = 0; axis < 3; ++axis) {
                Coord e1(0, 0, 0), e2(0, 0, 0);
                e1[(axis + 1) % 3] = 1;
                e2[(axis + 2) % 3] = 1;
                // A face reaching into a ring that reads as outside is not a face of F's samples.
                if (!ring_reads_background_ && !lattice_.isInside(c + e1 + e2)) continue;
                const double b = acc.getValue(c + e1), cc = acc.getValue(c + e2), d = acc.getValue(c + e1 + e2);
                if (std::min({a, b, cc, d}) > isovalue || std::max({a, b, cc, d}) < isovalue) continue;
                const double den = a - b - cc + d;
                if (den == 0) continue;
                const double u = (a - cc) / den, w = (a - b) / den;
                if (!(u > 0 && u < 1 && w > 0 && w < 1)) continue;
                const double num = a * d - b * cc;
                if (num == isovalue * den) tie = true;
                else if (num / den < isovalue) gap = std::min(gap, isovalue - num / den);
            }
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
        double d = std::min(0.5 * gap, 1e-3 * span);
        if (!(d > 0)) d = 1e-3 * span;
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
