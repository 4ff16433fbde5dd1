#include "octree/sample_field.h"

#include "octree/value_scan.h"

#include <isodel/errors.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace isodel::octree {

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
    scan_stored_values(*grid_, lattice_, ring_reads_background_, every_sample(), scan);
    // Inactive samples of the domain (background, inactive tiles). The ring around the active
    // box reads the background only when it is strictly outside (see the header: a dense file's
    // lattice is its box, and a background at or inside v - MRC's 0 at v = 0 - would wrap the
    // box in a spurious shell); inside the lattice, inactive voxels read it whenever they exist.
    if (ring_reads_background_ || std::uint64_t(grid_->activeVoxelCount()) < active.volume()) scan.consider(bg);
    // The saddles matter for the range check below only when v is not strictly inside the range.
    if (!v_star || !(isovalue > scan.vmin && isovalue < scan.vmax))
        scan_critical_values(*grid_, lattice_, ring_reads_background_, every_sample(), scan);
    const FieldSummary whole = summarize_scan(scan, lattice_, isovalue, grid_->getName());
    vmin_ = whole.vmin;
    vmax_ = whole.vmax;
    effective_ = v_star ? *v_star : whole.v_star;
    init_geometry();
}

FieldSummary summarize_scan(const ValueScan& scan, const CoordBBox& lattice, double isovalue,
                            const std::string& grid_name)
{
    const double vmin = scan.vmin, vmax = scan.vmax, gap = scan.gap;
    const bool tie = scan.tie;
    if (!(isovalue > vmin && isovalue < vmax) && !(tie && vmin < vmax)) {
        std::ostringstream os;
        os << "isovalue " << isovalue << " is outside the value range [" << vmin << ", " << vmax
           << "] of grid '" << grid_name << "': the level set is empty";
        throw InvalidInput(os.str());
    }
    FieldSummary out;
    out.lattice = lattice;
    out.vmin = vmin;
    out.vmax = vmax;
    out.v_star = isovalue;
    if (tie) {
        const double span = vmax - vmin;
        double d = std::min(0.5 * gap, 1e-2 * span);
        if (!(d > 0)) d = 1e-2 * span;
        out.v_star = isovalue - d;
    }
    return out;
}

SampleField::SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside, const FieldSummary& whole)
    : grid_(std::move(grid)), isovalue_(isovalue), effective_(whole.v_star), inside_(inside),
      sign_(inside == Inside::Above ? 1.0 : -1.0)
{
    if (!grid_) throw InvalidInput("null grid");
    if (whole.lattice.empty()) throw InvalidInput("grid '" + grid_->getName() + "' is empty (no active voxels)");
    lattice_ = whole.lattice;
    domain_ = lattice_;
    domain_.expand(1);
    ring_reads_background_ = sign_ * (grid_->background() - isovalue) < 0;
    vmin_ = whole.vmin;
    vmax_ = whole.vmax;
    init_geometry();
}

void SampleField::init_geometry()
{
    // Outside samples sit clearly on the outside side.
    outside_magnitude_ = std::max(1.0, vmax_ - vmin_);

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
