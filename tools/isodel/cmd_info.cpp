// isodel info: what was read, in the units the other subcommands use (index and world boxes,
// voxel size, value range), as text or as one JSON object (--json) for scripts and tests.
#include "cli_common.h"

#include <isodel/adaptive.h>

#include <nlohmann/json.hpp>

#include <iostream>
#include <sstream>

namespace isodel::cli {
namespace {

std::string ivec(const openvdb::Coord& c)
{
    return "[" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + "]";
}

struct Info {
    openvdb::Coord dims;
    openvdb::Vec3d world_min, world_max, voxel;
    std::string grid_class;
    openvdb::Index64 active = 0, memory = 0;
    /// The stored nodes, which isodel's work follows (not the box): leaf nodes of 8^3 voxels,
    /// and tiles (a constant over a larger box), active ones apart.
    openvdb::Index64 leaves = 0, tiles = 0, active_tiles = 0;
    openvdb::math::Mat4d index_to_world;
};

Info gather(const Volume& vol)
{
    Info info;
    const auto& xf = vol.grid->transform();
    info.dims = vol.lattice.dim();
    // World box of the lattice: all 8 corners, since a sheared map moves every corner differently.
    info.world_min = openvdb::Vec3d(std::numeric_limits<double>::max());
    info.world_max = openvdb::Vec3d(std::numeric_limits<double>::lowest());
    for (int c = 0; c < 8; ++c) {
        const openvdb::Vec3d ijk(c & 1 ? vol.lattice.max().x() : vol.lattice.min().x(),
                                 c & 2 ? vol.lattice.max().y() : vol.lattice.min().y(),
                                 c & 4 ? vol.lattice.max().z() : vol.lattice.min().z());
        const openvdb::Vec3d w = xf.indexToWorld(ijk);
        info.world_min = openvdb::math::minComponent(info.world_min, w);
        info.world_max = openvdb::math::maxComponent(info.world_max, w);
    }
    info.voxel = xf.voxelSize();
    info.grid_class = openvdb::GridBase::gridClassToString(vol.grid->getGridClass());
    info.active = vol.grid->activeVoxelCount();
    info.memory = vol.grid->memUsage();
    info.leaves = vol.grid->tree().leafCount();
    auto tile = vol.grid->tree().cbeginValueAll();
    tile.setMaxDepth(openvdb::FloatTree::ValueAllCIter::LEAF_DEPTH - 1);
    // Every slot of an internal node without a child is a tile; those inactive at the
    // background value are only the background, and are not counted.
    const float background = vol.grid->background();
    for (; tile; ++tile) {
        if (!tile.isValueOn() && *tile == background) continue;
        ++info.tiles;
        if (tile.isValueOn()) ++info.active_tiles;
    }
    info.index_to_world = xf.baseMap()->getAffineMap()->getMat4();
    return info;
}

// Integers as integers; doubles written so they read back to the same value.
void print_json(const Volume& vol, const Info& i)
{
    using Json = nlohmann::ordered_json;
    auto vec = [](const openvdb::Vec3d& v) { return Json::array({v[0], v[1], v[2]}); };
    auto ijk = [](const openvdb::Coord& c) { return Json::array({c.x(), c.y(), c.z()}); };
    Json o;
    o["file"] = vol.path;
    o["format"] = vol.format;
    o["grid_name"] = vol.grid->getName();
    o["grid_class"] = i.grid_class;
    o["default_inside"] = to_string(vol.default_inside);
    o["dims"] = ijk(i.dims);
    o["index_bbox"] = Json::array({ijk(vol.lattice.min()), ijk(vol.lattice.max())});
    o["world_bbox"] = Json::array({vec(i.world_min), vec(i.world_max)});
    o["voxel_size"] = vec(i.voxel);
    o["value_range"] = Json::array({double(vol.value_min), double(vol.value_max)});
    o["background"] = double(vol.grid->background());
    o["active_voxels"] = i.active;
    o["leaf_nodes"] = i.leaves;
    o["tiles"] = i.tiles;
    o["active_tiles"] = i.active_tiles;
    o["memory_bytes"] = i.memory;
    Json m = Json::array();
    for (int r = 0; r < 4; ++r)
        m.push_back(Json::array({i.index_to_world(r, 0), i.index_to_world(r, 1), i.index_to_world(r, 2),
                                 i.index_to_world(r, 3)}));
    o["index_to_world"] = std::move(m);
    if (const auto a = adaptive_info(vol.path)) // isodel decimate or mesh --adaptive-grid
        o["adaptive"] = {{"levels", a->levels}, {"k", a->k}, {"leaves_per_level", a->histogram},
                         {"source", a->source}};
    // A path need not be UTF-8: invalid bytes are written as U+FFFD rather than failing.
    std::cout << o.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
}

void print_text(const Volume& vol, const Info& i)
{
    std::ostringstream o;
    o.precision(9);
    o << "file:          " << vol.path << "\n"
      << "format:        " << vol.format << "\n"
      << "grid:          '" << vol.grid->getName() << "', class " << i.grid_class << " (default inside: "
      << to_string(vol.default_inside) << " the isovalue)\n"
      << "dims:          " << i.dims.x() << " x " << i.dims.y() << " x " << i.dims.z() << "\n"
      << "index bbox:    " << ivec(vol.lattice.min()) << " -> " << ivec(vol.lattice.max()) << "\n"
      << "world bbox:    " << i.world_min << " -> " << i.world_max << "\n"
      << "voxel size:    " << i.voxel << "\n"
      << "value range:   [" << vol.value_min << ", " << vol.value_max << "]\n"
      << "background:    " << vol.grid->background() << "\n"
      << "active voxels: " << i.active << " in " << i.leaves << " leaf nodes of 8^3 and " << i.active_tiles
      << " active tiles (" << i.tiles << " tiles in all)\n"
      << "memory:        " << i.memory << " bytes (" << double(i.memory) / (1024.0 * 1024.0) << " MiB)\n";
    if (const auto a = adaptive_info(vol.path)) {
        o << "adaptive:      " << a->levels << " levels, k " << a->k << ", leaves per level";
        for (const auto n : a->histogram) o << ' ' << n;
        o << " (" << a->source << ")\n";
    }
    std::cout << o.str();
}

} // namespace

void add_info_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("info", "Print dims, bounding boxes, voxel size, value range of a volume");
    auto in = std::make_shared<InputOptions>();
    auto json = std::make_shared<bool>(false);
    add_input_options(*cmd, *in);
    cmd->add_flag("--json", *json, "Print one JSON object instead of text");
    cmd->callback([in, json, &exit_code] {
        const Volume vol = read_input(*in);
        const Info info = gather(vol);
        if (*json) print_json(vol, info);
        else print_text(vol, info);
        exit_code = kOk;
    });
}

} // namespace isodel::cli
