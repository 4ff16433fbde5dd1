#pragma once
// Internal: the lattice every point isodel places lies on, 2^-24 of a voxel.
//
// Why: the exact predicates decide on the coordinates themselves, and a point built in floating
// point as lower + t is rounded at the magnitude of lower. The same shape meshed at 64 and at
// 1600 voxels from the origin would then get coordinates whose last bits differ, and where four
// vertices are nearly cospherical the Delaunay diagonal, and so the mesh, could differ. On a
// dyadic lattice a translation by whole voxels is exact (for voxels whose size is a power of
// two, unit voxels among them, and coordinates below 2^28 voxels), the predicates see the same
// configuration, and the mesh is the same up to the translation.
//  - A grid-edge crossing is placed at lower + (its offset along the edge, rounded to the
//    lattice): exact wherever the edge is.
//  - A constructed point (a refinement candidate, a seed) is rounded to the lattice as it is
//    built. Its own rounding error at large coordinates (a few ulps) straddles a lattice
//    midpoint only with a probability of about 1e-6 per coordinate.
// Rounding moves a point by at most 2^-25 voxel (3e-8), which the checks that follow see like
// any other position: every guarantee is established on the rounded points.
#include <cmath>

namespace isodel::mesher {

/// Lattice steps per voxel (a power of two).
constexpr double kLatticePerVoxel = 16777216.0; // 2^24

/// The lattice step in world units for voxels whose smallest edge is \p min_voxel_edge: 2^-24
/// of the largest power of two not above it, so that dividing and multiplying by it is exact.
inline double lattice_step(double min_voxel_edge)
{
    return std::ldexp(1.0, std::ilogb(min_voxel_edge)) / kLatticePerVoxel;
}

/// \p x rounded to the nearest multiple of \p step (ties to even): exact arithmetic for a
/// power-of-two step, and the identity where doubles are coarser than the step.
inline double on_lattice(double x, double step) { return std::nearbyint(x / step) * step; }

/// A point (x(), y(), z() and a constructor from three coordinates, as CGAL's) rounded to the
/// lattice coordinate by coordinate.
template <class Point>
Point on_lattice(const Point& p, double step)
{
    return Point(on_lattice(p.x(), step), on_lattice(p.y(), step), on_lattice(p.z(), step));
}

} // namespace isodel::mesher
