#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <openvdb/openvdb.h>

int main(int argc, char* argv[])
{
    openvdb::initialize();
    return Catch::Session().run(argc, argv);
}
