#pragma once
// Internal: the Euler characteristic of Sigma n Vor(p), sampled - the fallback of the CBP_VC
// disk check (voronoi_cell_disks.h) for the cells its exact silhouette certificate cannot settle
// (a disk that folds over itself, a tip of a thin tube).
//
// Sigma is replaced by T, the marching-tetrahedra surface of F sampled \p per_voxel times per
// voxel edge on the Freudenthal (Kuhn) subdivision of the sub-lattice: every sub-cube is cut
// into six tetrahedra along its main diagonal, so T is a 2-manifold without ambiguous cases,
// the level set of the piecewise-linear interpolant of the samples. The sub-lattice is aligned
// with the voxels, so F is sampled exactly and only features thinner than 1/per_voxel voxel
// can be lost.
//
// chi(T n V) is computed without clipping T as a whole: the compactly supported Euler
// characteristic is additive over a partition into relatively open cells, so
//   chi(T n V) = sum over the open vertices, edges and triangles s of T of chi_c(s n V),
// and each term is local. V is convex, so s n V is convex: a vertex counts 1 if in V; an open
// edge's piece is an interval counting +1, 0 or -1 as 2, 1 or 0 of its ends are V's (an end
// at the edge's own vertex is open); an open triangle's piece counts 1 minus the number of arcs
// of V's boundary crossing it (1 when it lies wholly inside the triangle or V contains it).
#include "octree/sample_field.h"

#include <cmath>
#include <vector>

namespace isodel::mesher {

/// A Voronoi cell V = {x : |x - p| <= |x - w| for every neighbour w} in index coordinates, where
/// it is {u : n . u <= c for every plane} (the grid's transform is affine).
struct VoronoiCellPlanes {
    std::vector<openvdb::Vec3d> n;
    std::vector<double> c;

    /// \p p, \p neighbours in world coordinates.
    VoronoiCellPlanes(const octree::SampleField& field, const openvdb::Vec3d& p,
                      const std::vector<openvdb::Vec3d>& neighbours);

    bool contains(const openvdb::Vec3d& u) const
    {
        for (std::size_t i = 0; i < n.size(); ++i)
            if (n[i].dot(u) - c[i] > 0) return false;
        return true;
    }
    /// The box [lo, hi] lies strictly beyond one plane.
    bool misses_box(const openvdb::Vec3d& lo, const openvdb::Vec3d& hi) const
    {
        for (std::size_t i = 0; i < n.size(); ++i) {
            double m = -c[i];
            for (int k = 0; k < 3; ++k) m += n[i][k] * (n[i][k] > 0 ? lo[k] : hi[k]);
            if (m > 0) return true;
        }
        return false;
    }
    /// The box [lo, hi] lies beyond one plane by more than the rounding of this test can move,
    /// so that misses_box holds of every box inside it as well, however it is rounded.
    bool misses_box_surely(const openvdb::Vec3d& lo, const openvdb::Vec3d& hi) const
    {
        for (std::size_t i = 0; i < n.size(); ++i) {
            double m = -c[i], scale = std::abs(c[i]);
            for (int k = 0; k < 3; ++k) {
                m += n[i][k] * (n[i][k] > 0 ? lo[k] : hi[k]);
                scale += std::abs(n[i][k]) * (std::abs(lo[k]) + std::abs(hi[k]));
            }
            if (m > 1e-12 * scale) return true;
        }
        return false;
    }
    /// chi_c of the open segment (a, b) intersected with V.
    int open_segment(const openvdb::Vec3d& a, const openvdb::Vec3d& b) const;
    /// chi_c of the open triangle (a, b, c) intersected with V.
    int open_triangle(const openvdb::Vec3d& a, const openvdb::Vec3d& b, const openvdb::Vec3d& c) const;
};

/// chi(T n V), T sampled on the index-space box [\p lo, \p hi] (which must contain V).
int sampled_euler_characteristic(const octree::SampleField::Reader& reader, const VoronoiCellPlanes& cell,
                                 const openvdb::Vec3d& lo, const openvdb::Vec3d& hi, int per_voxel);

} // namespace isodel::mesher
