// Downstream use of the installed package: read a volume and mesh a level set through the
// public API only, through the umbrella header. Exit 0 when the mesh is non-empty.
#include <isodel/isodel.h>

#include <cstdlib>
#include <iostream>

int main(int argc, char** argv)
{
    if (argc != 3) {
        std::cerr << "usage: consumer VOLUME ISOVALUE\n";
        return 2;
    }
    openvdb::initialize();
    try {
        const isodel::Volume vol = isodel::read_volume(argv[1]);
        isodel::MeshOptions opt;
        opt.isovalue = std::atof(argv[2]);
        const isodel::MeshResult result = isodel::mesh_isosurface(*vol.grid, opt);
        std::cout << "consumer: " << result.surface.vertices.size() << " vertices, "
                  << result.surface.triangles.size() << " triangles\n";
        return result.surface.triangles.empty() ? 1 : 0;
    } catch (const isodel::Error& e) {
        std::cerr << "consumer: " << e.what() << "\n";
        return 1;
    }
}
