#pragma once
/// \file sample_field.h
/// The function being meshed, in one place: the samples of an openvdb::FloatGrid, the level
/// v* actually meshed, and the side that is inside. Everything downstream (edge crossings,
/// protective layer, segment roots, verify) reads samples through phi(), never the grid.
///
///   phi(ijk) = s * (value(ijk) - v*),  s = +1 if inside is above, -1 if below,
///
/// so phi > 0 inside and phi < 0 outside, and phi is never exactly 0 at a sample.
///
/// Rules (see include/isodel/mesh.h):
///  - Ties: a sample equal to v counts as above v; Sigma is the limit of {F = v - d}, d -> 0+.
///    When some sample, the bilinear saddle of some cell face, or the saddle inside some cell
///    equals v (critical_values.h) we mesh v* = v - d with
///        d = min( gap/2, 1e-2 * (value range) ),
///        gap = min{ v - c : c < v a sample or a face or cell critical value },
///    otherwise v* = v. No critical value lies in [v*, v), so {F = v*} has the topology of the
///    limit (Morse theory on the cells, faces and vertices); E points never coincide with grid
///    points, and two blobs touching at a saddle at v are one component. d is as large as that
///    allows, up to 1 % of the range: a sample at v and a neighbour one quantum below put a
///    feature ~d/quantum voxel thick between them, and with a cap as small as 1e-3 of the
///    range such features on quantized data are too thin for a mesh at eps = 0.5 voxel to
///    keep their handles. The surface moves by about d / |grad F| from the limit.
///  - Domain: samples inside the active bounding box (the lattice) are read through the grid
///    (inactive voxels give the background or tile value). The ring of samples around it reads
///    the background too when the background is strictly outside (a fog volume's 0 below v: Sigma
///    may pass between the last active voxel and its inactive neighbour), and is "outside"
///    otherwise (a dense file's box whose background 0 equals v). Beyond domain() every sample
///    is "outside" (phi = -outside_magnitude), so Sigma is a union of closed surfaces inside
///    domain().expand(1), and the solid is clipped by the lattice box where it reaches it.
#include "octree/face_slabs.h"

#include <isodel/volume.h>

#include <openvdb/openvdb.h>

#include <optional>
#include <string>

namespace isodel::octree {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::Vec3d;

struct ValueScan; // value_scan.h

/// What a SampleField takes from the whole volume, for a field whose grid holds only part of the
/// samples (one process of a partitioned run reads only its blocks' boxes of the file,
/// surface/partitioned_file.h): with it, the part reads every sample it holds exactly as the
/// whole volume's field does.
struct FieldSummary {
    CoordBBox lattice;      ///< the whole volume's active bounding box
    double vmin = 0, vmax = 0; ///< value_min(), value_max() of the whole volume's field
    double v_star = 0;      ///< the tie rule's level for the whole volume
};

/// The summary from the joined scan of the whole volume (value_scan.h: its stored values, the
/// background where an inactive sample reads it, and the face and cell saddles).
/// \throw InvalidInput the level set is empty (the message names \p grid_name)
FieldSummary summarize_scan(const ValueScan& scan, const CoordBBox& lattice, double isovalue,
                            const std::string& grid_name);

class SampleField {
public:
    /// \throw InvalidInput empty grid, or \p isovalue outside the value range of the domain.
    SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside);

    /// The same field read at a given level \p v_star instead of the tie rule's own (the adaptive
    /// path reads its coarse fields at the input's v*, see set_effective_isovalue). The face and
    /// cell saddles decide only the tie rule's shift, so they are not scanned, unless \p isovalue
    /// lies outside the samples' open range, where a tie decides whether the level set is empty
    /// (a saddle lies within its corners' range, so only within rounding of its end). Everything
    /// else (range, outside value) is what the constructor above gives.
    SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside, double v_star);

    /// A field on \p grid, which holds the samples it will be asked for, with what the whole
    /// volume decides given by \p whole (lattice, range, level); nothing is scanned.
    SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside, const FieldSummary& whole);

    /// \p parent seen through the box \p clip (sample coordinates): the same samples, level v*
    /// and outside value inside it, "outside" beyond it, so its Sigma is \p parent's Sigma inside
    /// \p clip, closed along the box. The field of one block of partitioned meshing
    /// (src/surface/partitioned_meshing.h). \throw InvalidInput if \p clip misses the domain.
    SampleField(const SampleField& parent, const CoordBBox& clip);

    const openvdb::FloatGrid& grid() const { return *grid_; }
    openvdb::FloatGrid::ConstPtr grid_ptr() const { return grid_; }
    const openvdb::math::Transform& transform() const { return grid_->transform(); }
    /// Samples read through the grid: active bbox grown by one voxel.
    const CoordBBox& domain() const { return domain_; }
    /// The active bounding box (the ring around it is domain() less this box).
    const CoordBBox& lattice() const { return lattice_; }
    /// True when the ring (domain() less lattice()) reads the grid, false when it reads
    /// outside_phi() (see "Domain" above).
    bool ring_reads_background() const { return ring_reads_background_; }
    double isovalue() const { return isovalue_; }
    double effective_isovalue() const { return effective_; }
    /// Meshes {F = v_star} instead of the tie rule's own level: the adaptive path reads its
    /// coarse field at the input's v* so that one level compares the two functions
    /// (certified_coarsening.h, which also rejects a coarse sample equal to v_star).
    void set_effective_isovalue(double v_star) { effective_ = v_star; }
    Inside inside() const { return inside_; }
    double value_min() const { return vmin_; }
    double value_max() const { return vmax_; }

    /// phi from a raw sample value (for callers iterating the grid themselves).
    double phi_of_value(double value) const { return sign_ * (value - effective_); }
    /// phi at a sample outside domain().
    double outside_phi() const { return -outside_magnitude_; }

    Vec3d index_to_world(const Vec3d& p) const { return grid_->transform().indexToWorld(p); }
    Vec3d world_to_index(const Vec3d& p) const { return grid_->transform().worldToIndex(p); }
    /// Smallest voxel edge in world units (length of the shortest index-axis step).
    double min_voxel_edge() const { return min_edge_; }

    /// Sigma' (face_slabs.h): the slabs the mesher's geometric queries (phi_at, segment_crossings,
    /// cell_function.h) read F through. Default h = 0: F itself. Samples (phi, cell_corners)
    /// are never affected.
    const FaceSlabs& face_slabs() const { return slabs_; }
    void set_face_slabs(const FaceSlabs& slabs) { slabs_ = slabs; }
    /// The farthest phi moves a point, in world units: max |T (+-h, +-h, +-h)| over the sign
    /// combinations (T the linear part of index-to-world). d_H(Sigma', Sigma) is at most this.
    double face_slab_shift() const { return slabs_.h * unit_slab_shift_; }
    /// The mesher's slabs for a Hausdorff bound \p eps (world units): face_slabs_for_eps in
    /// smallest voxel edges, narrowed where elongated or sheared voxels would move Sigma' more
    /// than kMaxSlabShift x eps (0.035 eps: never on a cubic lattice, where the shift is
    /// sqrt(3) eps / 50).
    FaceSlabs face_slabs_for_eps_world(double eps) const;
    static constexpr double kMaxSlabShift = 0.035;

    /// A cheap per-thread reader of phi (owns an OpenVDB ValueAccessor, which is not thread-safe).
    class Reader {
    public:
        explicit Reader(const SampleField& f) : f_(&f), acc_(f.grid_->getConstAccessor()) {}
        double phi(const Coord& ijk) const
        {
            if (!f_->domain_.isInside(ijk)) return f_->outside_phi();
            if (!f_->ring_reads_background_ && !f_->lattice_.isInside(ijk)) return f_->outside_phi();
            return f_->phi_of_value(acc_.getValue(ijk));
        }
        /// Corner phi values of the unit cell with lowest corner \p c, in the order
        /// index = i + 2j + 4k (corner (i,j,k) at c + (i,j,k)).
        void cell_corners(const Coord& c, double out[8]) const
        {
            const Coord d = c.offsetBy(1);
            const bool inside = f_->domain_.isInside(c) && f_->domain_.isInside(d) &&
                                (f_->ring_reads_background_ || (f_->lattice_.isInside(c) && f_->lattice_.isInside(d)));
            if (!inside) {
                for (int n = 0; n < 8; ++n) out[n] = phi(c.offsetBy(n & 1, (n >> 1) & 1, (n >> 2) & 1));
                return;
            }
            // Every corner is read from the grid (the hot path: mesh cells, segment walks,
            // Newton steps). A cell off a leaf's last row, column and layer has its eight corners
            // in one leaf: one probe instead of eight accessor reads (the same values).
            using Leaf = openvdb::FloatGrid::TreeType::LeafNodeType;
            constexpr int kLast = int(Leaf::DIM) - 1;
            if ((c[0] & kLast) != kLast && (c[1] & kLast) != kLast && (c[2] & kLast) != kLast)
                if (const Leaf* leaf = acc_.probeConstLeaf(c)) {
                    const openvdb::Index o = Leaf::coordToOffset(c);
                    for (int n = 0; n < 8; ++n)
                        out[n] = f_->phi_of_value(leaf->getValue(o + ((n & 1) << (2 * Leaf::LOG2DIM)) +
                                                                 (((n >> 1) & 1) << Leaf::LOG2DIM) + ((n >> 2) & 1)));
                    return;
                }
            for (int n = 0; n < 8; ++n)
                out[n] = f_->phi_of_value(acc_.getValue(c.offsetBy(n & 1, (n >> 1) & 1, (n >> 2) & 1)));
        }
        const SampleField& field() const { return *f_; }

    private:
        const SampleField* f_;
        mutable openvdb::FloatGrid::ConstAccessor acc_;
    };

private:
    /// Both public constructors: \p v_star given or the tie rule's.
    SampleField(openvdb::FloatGrid::ConstPtr grid, double isovalue, Inside inside, std::optional<double> v_star);
    /// Outside magnitude, smallest voxel edge and slab shift, from the range and the transform.
    void init_geometry();

    openvdb::FloatGrid::ConstPtr grid_;
    CoordBBox domain_;
    CoordBBox lattice_;                 ///< the active bounding box
    bool ring_reads_background_ = true; ///< see "Domain" above
    double isovalue_, effective_;
    Inside inside_;
    double sign_;
    double vmin_, vmax_;
    double outside_magnitude_;
    double min_edge_;
    double unit_slab_shift_ = 0; ///< face_slab_shift() per unit of h
    FaceSlabs slabs_;
};

} // namespace isodel::octree
