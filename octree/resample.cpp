#include "octree/resample.h"

#include "octree/adaptive_vdb_format.h"
#include "octree/interpolant.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>

#include <openvdb/tools/Prune.h>

namespace isodel::octree {

openvdb::FloatGrid::Ptr resample_dense(const AdaptiveGrid& g) { return resample_dense(g, g.samples()); }

openvdb::FloatGrid::Ptr resample_dense(const AdaptiveGrid& g, const openvdb::FloatGrid& base)
{
    auto out = base.deepCopy();
    const float bg = out->background();
    CoordBBox active = g.domain();
    active.expand(-1);
    auto acc = out->getAccessor();
    InterpolantReader ir(g);
    for (int l = 1; l <= g.max_level(); ++l)
        for (const CellId& c : g.leaves(l)) {
            double cv[8];
            ir.corners(c, cv);
            const double inv = 1.0 / c.size();
            for (auto it = c.nodes().begin(); it; ++it) {
                const Coord d = *it - c.origin;
                const float v = float(ir.local().eval(cv, Vec3d(d.x() * inv, d.y() * inv, d.z() * inv)));
                if (active.isInside(*it) && v != bg) acc.setValueOn(*it, v);
                else acc.setValueOff(*it, v);
            }
        }
    if (!active.empty()) { // the extremes fix the active bounding box, hence the domain
        // Copies, not references: getValue may return a reference to a tile value, which
        // setValueOn overwrites when it allocates the leaf.
        const float lo = acc.getValue(active.min()), hi = acc.getValue(active.max());
        acc.setValueOn(active.min(), lo);
        acc.setValueOn(active.max(), hi);
    }
    openvdb::tools::prune(out->tree());
    return out;
}

} // namespace isodel::octree

namespace isodel {

openvdb::FloatGrid::Ptr resample(const AdaptiveVolume& volume, Interrupter* intr)
{
    if (intr) intr->start("resample");
    const octree::AdaptiveGrid g = octree::to_adaptive_grid(volume);
    if (intr && intr->wasInterrupted(0)) throw Cancelled("resample: interrupted");
    auto out = octree::resample_dense(g);
    // Plain grid: drop the adaptive markers so the result reads as an ordinary volume.
    for (const char* key : {"isodel_adaptive", "isodel_k", "isodel_levels", "isodel_tolerance",
                            "isodel_domain_min", "isodel_domain_max"})
        out->removeMeta(key);
    if (intr) intr->end();
    return out;
}

} // namespace isodel
