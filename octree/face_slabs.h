#pragma once
/// \file face_slabs.h
/// The surface isodel meshes: Sigma' = {F o phi = v}, Sigma with a slab of half-width h around
/// every grid plane (docs/algorithm.md, "Two deliberate departures": face slabs).
///
/// Why. The trilinear Sigma is only C0 across cell faces. Where F has a valley across a face
/// (it grows away from the face on both sides) and a small gradient along it, Sigma's two sheets
/// meet along the face at an arbitrarily small dihedral angle: a knife-edge fin. A wedge is scale
/// invariant, so Voronoi edges near its edge cross both sheets at every scale and the closed ball
/// refinement never ends. Cancelling such pairs of crossings per Voronoi edge instead would be
/// a rule, not a surface: the closed-ball checks (CBP_VE, CBP_VF, CBP_VC, Theorem 1) and the
/// eps test would each see a different surface, so no single surface is certified. Sigma' is
/// one surface that every check of the mesher reads the same way, homeomorphic to Sigma and
/// close to it (below).
///
/// What. phi maps mesh index space onto sample index space, one axis at a time: the slab
/// [c - h, c + h] around every integer c goes to c, and each cell's core [c + h, c + 1 - h] is
/// stretched affinely onto [c, c + 1]. So F' = F o phi is constant across a slab, equal to the
/// face's bilinear function, and trilinear in every core; each mesh cell [c, c + 1]^3 reads the
/// samples of the same sample cell c, split into up to 27 boxes (slab-low, core, slab-high per
/// axis) on each of which F' is trilinear.
///  - No knife edges: at a slab's boundary plane F' does not vary across the slab side, so that
///    sheet of Sigma' is perpendicular to the plane and meets the other one at 90 degrees or more.
///    A fin's tip becomes a blunt end at least 2h thick.
///  - Same topology: Sigma' is Sigma with each curve Sigma n face thickened into a band (curve x
///    [-h, h]) and each E point into a square; where Sigma crosses the faces and edges
///    transversally (always, after the tie rule of sample_field.h moves v off the face saddles)
///    that is a homeomorphism.
///  - Close: |x - phi(x)| <= h per axis, so d_H(Sigma', Sigma) <= max |T (+-h, +-h, +-h)| in
///    world units (T the linear part of index-to-world; SampleField::face_slab_shift); the
///    mesher meshes Sigma' within eps minus that.
/// h = 0 is the identity: F' = F.
#include <openvdb/math/Vec3.h>

#include <algorithm>
#include <cmath>

namespace isodel::octree {

struct FaceSlabs {
    double h = 0.0; ///< half-width of the slab around each grid plane, index units, in [0, 1/4]

    /// phi on one axis, in coordinates local to a cell: [0, h] -> 0, [h, 1 - h] -> [0, 1], [1 - h, 1] -> 1.
    double local(double t) const
    {
        if (h == 0) return t;
        if (t <= h) return 0.0;
        if (t >= 1 - h) return 1.0;
        return (t - h) / (1 - 2 * h);
    }
    /// phi: mesh index space -> sample index space.
    double to_sample(double x) const
    {
        if (h == 0) return x;
        const double c = std::floor(x);
        return c + local(x - c);
    }
    openvdb::math::Vec3d to_sample(const openvdb::math::Vec3d& x) const
    {
        return {to_sample(x[0]), to_sample(x[1]), to_sample(x[2])};
    }
    /// A preimage of a sample-space point: the unique one off the grid planes, the slab's
    /// middle (the plane itself) on them. Maps points of Sigma to points of Sigma'.
    double from_sample(double s) const
    {
        if (h == 0) return s;
        const double c = std::floor(s), u = s - c;
        return u == 0 ? c : c + h + u * (1 - 2 * h);
    }
    openvdb::math::Vec3d from_sample(const openvdb::math::Vec3d& s) const
    {
        return {from_sample(s[0]), from_sample(s[1]), from_sample(s[2])};
    }
    /// The local box (0: [0, h], 1: [h, 1 - h], 2: [1 - h, 1]) holding local coordinate t.
    int piece_of(double t) const
    {
        if (h == 0) return 1;
        return t < h ? 0 : t > 1 - h ? 2 : 1;
    }
    /// Bounds of local box \p i (see piece_of).
    void piece_bounds(int i, double& lo, double& hi) const
    {
        lo = i == 0 ? 0.0 : i == 1 ? h : 1 - h;
        hi = i == 0 ? h : i == 1 ? 1 - h : 1.0;
    }
};

/// The slabs the mesher uses for a Hausdorff bound of \p eps_voxels (smallest voxel edges):
/// h = eps / 50, at most 1/4. A fin's tip is 2h thick in Sigma', and refining toward it costs
/// about its length / h points, so h should not be tiny; eps / 50 still keeps the shift
/// |T (h, h, h)| (under 0.035 eps on a cubic lattice) a small part of the bound.
inline FaceSlabs face_slabs_for_eps(double eps_voxels)
{
    return FaceSlabs{std::min(0.25, 0.02 * eps_voxels)};
}

} // namespace isodel::octree
