# All dependencies come from Debian packages (see README.md).
foreach(dir /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/aarch64-linux-gnu/cmake/OpenVDB
            /usr/lib/cmake/OpenVDB /usr/local/lib/cmake/OpenVDB)
  if(EXISTS ${dir}/FindOpenVDB.cmake)
    list(APPEND CMAKE_MODULE_PATH ${dir})
    set(ISODEL_OPENVDB_MODULE_DIR ${dir})
    break()
  endif()
endforeach()
find_package(OpenVDB REQUIRED)
find_package(TBB REQUIRED)
find_package(CGAL REQUIRED)
find_package(Eigen3 REQUIRED NO_MODULE)
find_package(ZLIB REQUIRED)
# JSON reading and writing (--stats, verify --json, info --json, the shared data's manifest):
# header-only, Debian's nlohmann-json3-dev.
find_package(nlohmann_json 3 REQUIRED)
if(ISODEL_BUILD_TOOLS)
  find_package(CLI11 REQUIRED)
endif()
if(ISODEL_BUILD_TESTS)
  find_package(Catch2 2 REQUIRED)
endif()
