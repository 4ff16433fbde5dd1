#pragma once
// Internal: shoulder points of tunnels inside one trilinear cell (paper Section 4.3, after Lopes
// and Brodlie). Where the cell's interpolant has an interior critical point s (a saddle: the
// trilinear F has no xx, yy, zz terms, so every interior critical point is one) with F(s) near
// v, Sigma has a neck there: the tunnel of marching cubes 33's interior-ambiguous cases, or a
// thin bridge between two sheets. A Voronoi facet can pass through the whole neck (an interior
// loop no Voronoi edge sees), and a Voronoi cell can hold the whole handle (a torus with a disk
// removed, which the one-boundary-curve test of CBP_VC cannot tell from a disk: the paper's
// Theorem 5 assumes otherwise). Without seeds in the neck, M can lose such a handle
// (tests/seeding/test_tunnel_shoulders.cpp).
//
// On the grid-aligned plane through s normal to axis a, F(s + u e_b + w e_c) = F(s) + k_a u w
// exactly (the in-plane gradient vanishes at s and the plane's bilinear has no u^2, w^2 terms),
// with k_a the mixed second derivative there. Sigma on that plane is a hyperbola whose two
// vertices lie on a diagonal at |u| = |w| = sqrt(|F(s) / k_a|): the points of the neck closest to
// s. The up to six of them ring the neck; they are inserted with the E points as N points of the
// topology phase, so the Voronoi diagram cuts the neck from the start. A vertex that falls outside
// the cell (a saddle within t of a face: the neck passes into the next cell) is replaced by the
// first crossing of Sigma on the same ray from s within twice its distance (else dropped), so
// the ring stays closed across the face.
#include "octree/sample_field.h"

#include <vector>

namespace isodel::mesher {

/// Index-space shoulder points of the necks at the interior critical points of the cells
/// \p crossed_cells (points on Sigma: inside the cell F is a quadratic along the diagonals, solved
/// in closed form; beyond a face, the root of the true F on the ray, isolated by segment_crossings).
std::vector<openvdb::Vec3d> tunnel_shoulder_points(const octree::SampleField& field,
                                                   const std::vector<openvdb::Coord>& crossed_cells);

} // namespace isodel::mesher
