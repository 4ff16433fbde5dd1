#pragma once
/// \file certified_coarsening.h
/// The adaptive grid built from the input and eps by itself (MeshOptions::adaptive, paper
/// Property IV): coarse leaves wherever a certificate proves that the coarse level set is
/// isotopic to the fine one and within a share of eps of it; docs/adaptive.md has the proof.
///
/// Both functions are piecewise trilinear on the unit lattice (a coarse leaf restricted to a
/// unit sub-cell is the trilinear function of the sub-cell's corners, resample.h), so they are
/// compared node by node: phi_f (the input) and phi_a (the adaptive interpolant), both read as
/// SampleField phi with the input's level v* (SampleField::set_effective_isovalue).
///
/// The certificate of a unit cell u (certify_cell) holds when
///  (a) an axis d and a sign s exist such that every d-edge of every band cell (one whose 16
///      corner values, of phi_f and phi_a, are not all of one strict sign) of the 3x3x3 block of
///      unit cells around u has a difference of strict sign s in phi_f and in phi_a. Then every
///      phi_t = (1-t) phi_f + t phi_a is strictly monotone along s e_d on those cells (a
///      trilinear function's d-derivative is bilinear in the other two coordinates, so its
///      extremes on a cell are its four d-edge differences), which are the only cells
///      {phi_t = 0} meets: it is a graph over the plane normal to d there, for every t;
///  (b) delta / g <= min(1, budget along d), delta the largest |phi_f - phi_a| at u's corners,
///      g the smallest |difference| of (a): a point of {phi_a = 0} in u reaches {phi_f = 0}
///      (and back) within delta / g voxels along d, inside the block (the path cannot enter a
///      cell off the band first: phi_a has left 0 along it, with the sign of the cell it
///      would enter).
/// It is required of every "changed" band cell (a corner where the two functions differ). Unchanged
/// cells keep phi_t = phi_f. So {phi_f = 0} and {phi_a = 0} are isotopic, and the Hausdorff
/// distance between them is at most the largest certified distance (docs/adaptive.md).
#include "octree/adaptive_grid.h"
#include "octree/edge_crossings.h"
#include "octree/sample_field.h"

#include <isodel/interrupt.h>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace isodel::octree {

/// The share of eps the coarsening may spend, and the shape of the grid.
struct CoarseningBudget {
    double distance_world = 0; ///< the largest certified distance allowed, world units
    int k = 1;                 ///< level difference of touching leaves
    int max_level = 5;         ///< coarsest leaf: 2^max_level voxels
};

/// Why a certificate fails (the first reason found).
enum class CertificateFailure {
    None,
    CoarseSampleAtLevel, ///< a coarse sample equals v*
    NoMonotoneAxis,      ///< (a): every axis has an edge of the wrong sign or 0 on a band cell
    OverBudget           ///< (b): a monotone axis, but delta / g over the budget or one voxel
};

/// One unit cell's certificate (see the file comment).
struct CellCertificate {
    bool ok = false;
    CertificateFailure failure = CertificateFailure::None;
    int axis = -1;              ///< the axis d of (a); the lowest axis of the shortest distance
    double distance_world = 0;  ///< delta / g times the voxel edge along d
};

/// Voxel edge lengths along the three index axes (world units) of \p field's transform.
std::array<double, 3> voxel_edges(const SampleField& field);

/// The certificate of unit cell \p u for the fine reader \p f and coarse reader \p a; \p edges from
/// voxel_edges, \p budget_world the distance allowed.
CellCertificate certify_cell(const SampleField::Reader& f, const SampleField::Reader& a, const Coord& u,
                             const std::array<double, 3>& edges, double budget_world);

/// Before building: of the input's grid-edge crossings \p e, those on an edge with a crossed unit
/// cell beside it whose level-1 parent (its 2^3 block) the construction's test accepts, read on
/// the input's samples. A crossing leaves E only where its edge is no leaf edge, inside a coarse
/// leaf, and every unit cell of a coarse leaf had its level-1 parent accepted (the repairs only
/// split), so this bounds what the octree can save. Up to the values near coarse leaves: a
/// level set's extension beyond its band (corner values of parents there) and hanging nodes
/// (which move crossings beside coarse leaves) are not modelled; balance only refuses more.
std::size_t crossings_coarse_leaves_could_remove(const SampleField& fine, const std::vector<EdgePoint>& e,
                                                 const std::vector<Coord>& crossed_cells,
                                                 const CoarseningBudget& budget);

/// The adaptive grid and what was measured of it.
struct CertifiedGrid {
    AdaptiveGrid grid;                     ///< samples: the corner samples (the input by default)
    openvdb::FloatGrid::Ptr resampled;     ///< the adaptive interpolant on the unit lattice
    /// resampled read as phi at the input's level v*: the field the mesher meshes.
    std::optional<SampleField> field;
    double distance_world = 0;             ///< the largest certified distance (<= the budget)
    std::size_t cells_certified = 0;       ///< changed cells that needed a certificate
    std::size_t rounds = 0, splits = 0;    ///< repair rounds and leaves split by them
};

/// Builds the grid bottom-up (a parent replaces its 8 children when its own interpolant passes
/// the certificate's tests on its span, or when its span is off Sigma), then checks the
/// certificate on every changed cell of the continuous interpolant and splits, around every cell
/// that fails, the coarsest leaves its certificate reads, until none does. Each split lowers sum
/// over leaves of (8^level - 1) / 7, which bounds the repair rounds; the uniform grid (nothing
/// changed) always passes.
/// \throw Cancelled when \p interrupter asks to stop.
/// \p corner_samples, when given, is where coarse leaves read their corners (an extended level
/// set, extended_level_set.h; same active bounding box as the input); the certificate still
/// compares with \p fine's samples, and nodes outside coarse leaves keep them.
/// \throw InvalidInput corner_samples with another domain.
CertifiedGrid certified_coarsening(const SampleField& fine, const CoarseningBudget& budget,
                                   Interrupter* interrupter = nullptr,
                                   openvdb::FloatGrid::ConstPtr corner_samples = nullptr);

/// The unit cells of \p g whose corners differ between \p f and \p a and whose 16 corner phi
/// values are not all of one strict sign: the cells the certificate is required of. Sorted.
std::vector<Coord> cells_to_certify(const AdaptiveGrid& g, const SampleField& f, const SampleField& a);

} // namespace isodel::octree
