#include "volume/interior_points.h"

#include "seeding/adaptive_points.h"

#include <openvdb/tools/Morphology.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace isodel::mesher {
namespace {

/// The box of the uniform G' (no rounding).
openvdb::CoordBBox plain_box(const octree::SampleField& field, const openvdb::MaskGrid& g_mask)
{
    openvdb::CoordBBox box = field.domain();
    box.expand(1);
    const openvdb::CoordBBox g = g_mask.evalActiveVoxelBoundingBox();
    if (!g.empty()) box.expand(g);
    return box;
}

/// The distance from G at which spacing 2^l starts: T_l = ceil((2^l - 1) / grading).
double level_start(int l, double grading)
{
    return std::ceil((std::ldexp(1.0, l) - 1) / grading);
}

/// \p spacing with max_level lowered to the largest level some sample of \p box can be far
/// enough from G for (T_l at most the box's extent): higher levels never occur, and rounding
/// the box up to their spacing, or dilating G that far, would be work for nothing.
GradedSpacing reachable(GradedSpacing spacing, const openvdb::CoordBBox& box)
{
    const openvdb::Coord dim = box.dim();
    const int extent = std::max({dim.x(), dim.y(), dim.z()});
    int l = 0;
    while (l < spacing.max_level && level_start(l + 1, spacing.grading) <= extent)
        ++l;
    spacing.max_level = l;
    return spacing;
}

/// zones[l - 1] holds the voxels closer to G than the distance at which spacing 2^l starts,
/// T_l: outside it the spacing is at least 2^l. The zones grow by dilating G (26-neighbourhood:
/// chessboard distance).
/// \pre spacing == reachable(spacing, plain box): each dilation is bounded by the box's extent.
/// Clipped to \p box after each dilation: what lies beyond holds no sample.
std::vector<openvdb::MaskGrid::ConstPtr> spacing_zones(const openvdb::MaskGrid& g_mask, const GradedSpacing& spacing,
                                                       const openvdb::CoordBBox& box)
{
    std::vector<openvdb::MaskGrid::ConstPtr> zones;
    openvdb::MaskGrid::Ptr grown = g_mask.deepCopy();
    int radius = 0; // grown = the voxels within this chessboard distance of G
    for (int l = 1; l <= spacing.max_level; ++l) {
        const int target = std::max(0, int(level_start(l, spacing.grading)) - 1);
        if (target > radius || zones.empty()) {
            if (target > radius) {
                openvdb::tools::dilateActiveValues(grown->tree(), target - radius, openvdb::tools::NN_FACE_EDGE_VERTEX,
                                                   openvdb::tools::EXPAND_TILES);
                grown->clip(box);
                radius = target;
            }
            zones.push_back(grown->deepCopy());
        }
        else {
            zones.push_back(zones.back()); // the same zone: nothing new to copy
        }
    }
    return zones;
}

} // namespace

int graded_max_level(double tet_size, double voxel)
{
    if (tet_size <= 0) return 3;
    const double ratio = tet_size / voxel;
    if (!(ratio >= 2)) return 0;
    if (!(ratio < 1024)) return 10; // infinity included
    // Slack for float32 voxel sizes (8.8 / 1.1f = 7.9999998 voxels is 8), far below a real difference.
    return std::min(10, int(std::floor(std::log2(ratio) + 1e-6)));
}

namespace {

/// \p box with its extent rounded up to a multiple of 2^max_level.
openvdb::CoordBBox rounded_box(const openvdb::CoordBBox& box, int max_level)
{
    const int step = 1 << max_level;
    openvdb::Coord hi = box.max();
    for (int a = 0; a < 3; ++a) {
        const int span = hi[a] - box.min()[a];
        hi[a] = box.min()[a] + (span + step - 1) / step * step;
    }
    return openvdb::CoordBBox(box.min(), hi);
}

} // namespace

openvdb::CoordBBox volume_box(const octree::SampleField& field, const openvdb::MaskGrid& g_mask,
                              const GradedSpacing* spacing)
{
    const openvdb::CoordBBox box = plain_box(field, g_mask);
    return spacing ? rounded_box(box, reachable(*spacing, box).max_level) : box;
}

std::vector<openvdb::Coord> interior_points(const octree::SampleField& field, const openvdb::MaskGrid& g_mask,
                                            TetRegion region, const octree::AdaptiveGrid::Reader* adaptive,
                                            const GradedSpacing* spacing)
{
    const bool want_in = region == TetRegion::Inside || region == TetRegion::Both;
    const bool want_out = region == TetRegion::Outside || region == TetRegion::Both;
    if (adaptive) spacing = nullptr;
    // Inside points lie in the domain (beyond it phi < 0); outside points fill the whole box.
    // The same box and levels as volume_box, computed once here.
    const openvdb::CoordBBox plain = plain_box(field, g_mask);
    const std::optional<GradedSpacing> levels =
        spacing ? std::optional<GradedSpacing>(reachable(*spacing, plain)) : std::nullopt;
    const openvdb::CoordBBox outer = levels ? rounded_box(plain, levels->max_level) : plain;
    const openvdb::CoordBBox box = want_out ? outer : field.domain();
    const openvdb::Coord anchor = outer.min();
    std::vector<openvdb::MaskGrid::ConstPtr> zones;
    if (levels) zones = spacing_zones(g_mask, *levels, outer);
    std::vector<openvdb::MaskGrid::ConstAccessor> in_zone;
    for (const auto& z : zones)
        in_zone.push_back(z->getConstAccessor());
    const octree::SampleField::Reader reader(field);
    const auto acc = g_mask.getConstAccessor();
    std::vector<openvdb::Coord> out;
    for (int z = box.min().z(); z <= box.max().z(); ++z)
        for (int y = box.min().y(); y <= box.max().y(); ++y)
            for (int x = box.min().x(); x <= box.max().x(); ++x) {
                const openvdb::Coord c(x, y, z);
                if (acc.isValueOn(c)) continue;
                // c lies on the lattices of levels 0..k, k the number of trailing zero bits its
                // offsets from the anchor share; it is kept when its own level is at most k, that
                // is when it is in zone k (closer to G than where level k + 1 starts). One probe.
                if (!in_zone.empty()) {
                    const unsigned bits = unsigned((x - anchor.x()) | (y - anchor.y()) | (z - anchor.z()));
                    const std::size_t k =
                        bits == 0 ? in_zone.size() : std::min<std::size_t>(in_zone.size(), __builtin_ctz(bits));
                    if (k < in_zone.size() && !in_zone[k].isValueOn(c)) continue;
                }
                // phi is never 0 at a sample (octree/sample_field.h): "strictly" is automatic.
                if (!(reader.phi(c) > 0 ? want_in : want_out)) continue;
                if (adaptive && !is_leaf_node(*adaptive, c)) continue;
                out.push_back(c);
            }
    return out;
}

} // namespace isodel::mesher
