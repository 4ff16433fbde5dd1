#pragma once
/// \file far_field.h
/// Coarse leaves where a sparse grid stores nothing: the far field of a narrow-band level set.
///
/// The bottom-up constructions (certified_coarsening.h, seed_octree.h) start from the unit cells
/// that touch allocated sample nodes (value_cells_sparse) and leave every other cell at level 0,
/// which costs no storage. But a leaf may differ by at most k levels from every leaf it touches
/// (balance.h), so a level-0 far field a few voxels from Sigma caps the leaves at Sigma at level
/// k + 1 or so, whatever their certificate says: a narrow band is only 3 voxels wide. Here the
/// far field gets the coarsest leaves it can have before the band is coarsened; balance() then
/// splits those beside fine leaves, as it would on a dense grid.
///
/// A far-field leaf is a cell whose closed span (corner nodes included) lies in the domain,
/// touches no allocated leaf node of the samples, and reads phi of one strict sign there: phi is
/// then a convex combination of corners of one sign on every unit cell of it, so Sigma misses
/// it, and it certifies itself in every construction ("off Sigma"). The span's values are those
/// of tiles and the background, read one block of the tree at a time, so the cost follows the
/// tree's nodes, not the box's voxels.
#include "octree/adaptive_grid.h"
#include "octree/sample_field.h"

#include <isodel/interrupt.h>

namespace isodel::octree {

/// What the closed box of sample nodes \p span reads of \p f: stored samples (an allocated leaf
/// node), or phi of one or both strict signs. Nodes beyond f's domain, and in the ring when it
/// does not read the background, read "outside", as SampleField::Reader::phi reads them.
struct SpanReading {
    bool stored = false;
    bool positive = false;
    bool negative = false;
    bool one_sign() const { return !stored && positive != negative; }
};
SpanReading read_span(const SampleField& f, openvdb::FloatGrid::ConstAccessor& acc, const CoordBBox& span);

/// Marks as leaves of the uniform grid \p g (over f's samples) the coarsest far-field cells of
/// level <= \p max_level (see the file comment). Returns the number of leaves set.
/// \throw InvalidInput \p g has a leaf above level 0; Cancelled when \p interrupter asks to stop.
std::size_t coarsen_far_field(AdaptiveGrid& g, const SampleField& f, int max_level, Interrupter* interrupter = nullptr);

} // namespace isodel::octree
