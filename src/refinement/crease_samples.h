#pragma once
// Internal: the sample points of the crease check (hausdorff_refinement.h, Sigma -> M along
// the creases). Where Sigma crosses a cell face it is only C0; the crease curve is Sigma on the
// face, where F is bilinear. On each face whose corners do not all agree in sign, lines along
// the face's two axes every 1/R index units cross the curve where F, linear on the line, has
// an exact root. The mesher meshes Sigma' (octree/face_slabs.h), whose creases are these
// curves mapped to the slab boundaries h inside the cell: the samples are put there.
#include "octree/sample_field.h"

#include <vector>

namespace isodel::mesher {

/// R, the lines per index unit that space the samples about eps / 2 apart (world): between 2
/// and 64, whatever eps.
int crease_lines_per_voxel(double min_voxel_edge, double eps);

/// Appends the crease samples of cell \p c (world points) to \p out, in a fixed order: faces
/// x = 0, 1, y = 0, 1, z = 0, 1, then each face's two line directions, then the lines.
/// \p corner: the cell's eight samples minus the isovalue, as SampleField::Reader::cell_corners
/// gives them.
void crease_samples(const octree::SampleField& field, const openvdb::Coord& c, const double corner[8],
                    int lines_per_voxel, std::vector<openvdb::Vec3d>& out);

} // namespace isodel::mesher
