#include "volume/interior_points.h"

#include "seeding/adaptive_points.h"

namespace isodel::mesher {

openvdb::CoordBBox volume_box(const octree::SampleField& field, const openvdb::MaskGrid& g_mask)
{
    openvdb::CoordBBox box = field.domain();
    box.expand(1);
    const openvdb::CoordBBox g = g_mask.evalActiveVoxelBoundingBox();
    if (!g.empty()) box.expand(g);
    return box;
}

std::vector<openvdb::Coord> interior_points(const octree::SampleField& field, const openvdb::MaskGrid& g_mask,
                                            TetRegion region, const octree::AdaptiveGrid::Reader* adaptive)
{
    const bool want_in = region == TetRegion::Inside || region == TetRegion::Both;
    const bool want_out = region == TetRegion::Outside || region == TetRegion::Both;
    // Inside points lie in the domain (beyond it phi < 0); outside points fill the whole box.
    const openvdb::CoordBBox box = want_out ? volume_box(field, g_mask) : field.domain();
    const octree::SampleField::Reader reader(field);
    const auto acc = g_mask.getConstAccessor();
    std::vector<openvdb::Coord> out;
    for (int z = box.min().z(); z <= box.max().z(); ++z)
        for (int y = box.min().y(); y <= box.max().y(); ++y)
            for (int x = box.min().x(); x <= box.max().x(); ++x) {
                const openvdb::Coord c(x, y, z);
                if (acc.isValueOn(c)) continue;
                // phi is never 0 at a sample (octree/sample_field.h): "strictly" is automatic.
                if (!(reader.phi(c) > 0 ? want_in : want_out)) continue;
                if (adaptive && !is_leaf_node(*adaptive, c)) continue;
                out.push_back(c);
            }
    return out;
}

} // namespace isodel::mesher
