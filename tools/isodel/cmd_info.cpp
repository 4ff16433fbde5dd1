// isodel info: what was read, in the units the other subcommands use (index and world boxes,
// voxel size, value range), as text or as one JSON object (--json) for scripts and tests.
#include "cli_common.h"

#include <cstdio>
#include <iostream>
#include <sstream>

namespace isodel::cli {
namespace {

std::string json_string(const std::string& s)
{
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') { out += '\\'; out += char(c); }
        else if (c < 0x20) { char b[8]; std::snprintf(b, sizeof b, "\\u%04x", c); out += b; }
        else out += char(c);
    }
    return out + "\"";
}

// 17 significant digits: a double prints and parses back to the same value.
std::string num(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

std::string vec(const openvdb::Vec3d& v) { return "[" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + "]"; }
std::string ivec(const openvdb::Coord& c)
{
    return "[" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + "]";
}

struct Info {
    openvdb::Coord dims;
    openvdb::Vec3d world_min, world_max, voxel;
    std::string grid_class;
    openvdb::Index64 active = 0, memory = 0;
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
    info.index_to_world = xf.baseMap()->getAffineMap()->getMat4();
    return info;
}

void print_json(const Volume& vol, const Info& i)
{
    std::ostringstream o;
    o << "{\n"
      << "  \"file\": " << json_string(vol.path) << ",\n"
      << "  \"format\": " << json_string(vol.format) << ",\n"
      << "  \"grid_name\": " << json_string(vol.grid->getName()) << ",\n"
      << "  \"grid_class\": " << json_string(i.grid_class) << ",\n"
      << "  \"default_inside\": " << json_string(to_string(vol.default_inside)) << ",\n"
      << "  \"dims\": " << ivec(i.dims) << ",\n"
      << "  \"index_bbox\": [" << ivec(vol.lattice.min()) << ", " << ivec(vol.lattice.max()) << "],\n"
      << "  \"world_bbox\": [" << vec(i.world_min) << ", " << vec(i.world_max) << "],\n"
      << "  \"voxel_size\": " << vec(i.voxel) << ",\n"
      << "  \"value_range\": [" << num(vol.value_min) << ", " << num(vol.value_max) << "],\n"
      << "  \"background\": " << num(vol.grid->background()) << ",\n"
      << "  \"active_voxels\": " << i.active << ",\n"
      << "  \"memory_bytes\": " << i.memory << ",\n"
      << "  \"index_to_world\": [";
    for (int r = 0; r < 4; ++r)
        o << (r ? ", " : "") << "[" << num(i.index_to_world(r, 0)) << ", " << num(i.index_to_world(r, 1)) << ", "
          << num(i.index_to_world(r, 2)) << ", " << num(i.index_to_world(r, 3)) << "]";
    o << "]\n}\n";
    std::cout << o.str();
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
      << "active voxels: " << i.active << "\n"
      << "memory:        " << i.memory << " bytes (" << double(i.memory) / (1024.0 * 1024.0) << " MiB)\n";
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
