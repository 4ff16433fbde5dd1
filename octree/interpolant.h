#pragma once
/// \file interpolant.h
/// The continuous interpolant F on an adaptive grid (paper Section 2: "the user specifies a local
/// interpolant"; Section 4.2: octree gridding).
///
/// Local interpolant: a function of a cell's 8 corner values, behind LocalInterpolant so other
/// local schemes can be plugged in; trilinear is the default (and the one Section 4.3 simplifies).
///
/// Hanging nodes: a corner of a fine leaf lying inside a face or an edge of a coarser leaf is not
/// read from the samples; its value is that coarser leaf's interpolant there. Rule used:
///     value(n) = interpolant of the coarsest leaf whose closed span contains n, evaluated at n
/// (a sample when n is a corner of that leaf, which then is a corner of every leaf containing n).
/// The coarse leaf's own corners are resolved the same way first, so chains of hanging nodes are
/// resolved from coarse to fine (recursion depth <= number of levels).
/// Why this makes F continuous (for trilinear): a fine face inside a coarse face gets its 4 corner
/// values from the coarse face's bilinear function, and a bilinear function restricted to an
/// aligned sub-rectangle is the bilinear function of its corner values; likewise on edges
/// (linear). Any local interpolant whose face restriction depends only on that face's corners and
/// is reproduced on sub-faces by corner values gives the same guarantee; others need their own
/// constraints.
#include "octree/adaptive_grid.h"
#include "octree/cell_interpolant.h" // Cubic

#include <array>
#include <optional>

namespace isodel::octree {

using openvdb::Vec3d;

/// One cell's interpolant from its corner values (index n = i + 2j + 4k for corner (i,j,k)),
/// in local coordinates u in [0,1]^3.
class LocalInterpolant {
public:
    virtual ~LocalInterpolant() = default;
    virtual const char* name() const = 0;
    virtual double eval(const double corners[8], const Vec3d& u) const = 0;
    /// The restriction to the segment u(t) = a + t (b - a), as a polynomial in t (degree <= 3;
    /// local interpolants of higher degree are not representable here).
    virtual Cubic along_segment(const double corners[8], const Vec3d& a, const Vec3d& b) const = 0;
};

/// Trilinear interpolation, evaluated as a chain of lerps so that equal corner values give
/// exactly that value (a constant region stays bit-exact).
class TrilinearInterpolant final : public LocalInterpolant {
public:
    const char* name() const override { return "trilinear"; }
    double eval(const double c[8], const Vec3d& u) const override;
    Cubic along_segment(const double c[8], const Vec3d& a, const Vec3d& b) const override;
};

/// The process-wide trilinear instance.
const LocalInterpolant& trilinear();

/// Per-thread evaluation of the continuous interpolant (values in raw sample units; apply
/// SampleField::phi_of_value for phi).
class InterpolantReader {
public:
    explicit InterpolantReader(const AdaptiveGrid& g, const LocalInterpolant& li = trilinear())
        : cells_(g), li_(&li) {}

    const AdaptiveGrid::Reader& cells() const { return cells_; }
    const LocalInterpolant& local() const { return *li_; }

    /// Value at lattice node \p n (a sample, or a hanging-node constraint). \p n in the domain.
    double node_value(const Coord& n) const;
    /// Resolved corner values of a cell (hanging nodes constrained).
    void corners(const CellId& c, double out[8]) const;
    /// F at index-space point \p p evaluated with cell \p c's interpolant (p in c's closed span).
    double eval_in(const CellId& c, const Vec3d& p) const;
    /// F at index-space point \p p (leaf chosen by floor(p); the value does not depend on the
    /// choice on shared boundaries). nullopt outside the cells of the domain.
    std::optional<double> eval(const Vec3d& p) const;
    /// The leaf containing \p p (floor convention, clamped onto the domain's upper faces).
    std::optional<CellId> leaf_at(const Vec3d& p) const;

private:
    AdaptiveGrid::Reader cells_;
    const LocalInterpolant* li_;
};

/// Local coordinates of index-space point \p p in cell \p c.
inline Vec3d local_coords(const CellId& c, const Vec3d& p)
{
    const double s = c.size();
    return Vec3d((p.x() - c.origin.x()) / s, (p.y() - c.origin.y()) / s, (p.z() - c.origin.z()) / s);
}

} // namespace isodel::octree
