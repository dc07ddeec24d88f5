# All dependencies come from Debian 12 packages (tools/install-deps.sh).
find_package(Threads REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs video dnn features2d calib3d)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(fmt 9 REQUIRED)  # text formatting (Debian libfmt-dev)
find_package(PNG REQUIRED)
find_package(ZLIB REQUIRED)  # CRC-32 of binary files and MCAP records
# MCAP chunk compression (Debian libzstd-dev, liblz4-dev): no CMake packages.
find_package(PkgConfig REQUIRED)
pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)
pkg_check_modules(LZ4 REQUIRED IMPORTED_TARGET liblz4)
find_package(assimp 5.2 REQUIRED)  # model files (glTF/GLB, FBX, OBJ) for sim/assets

find_package(mujoco 2.2 REQUIRED)
# Debian's mujoco target names /usr/include/libqhull_r, which exists only with
# libqhull-dev; drop missing include dirs so generation never fails.
get_target_property(_mj_inc mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
if(_mj_inc)
  set(_mj_inc_ok "")
  foreach(_dir IN LISTS _mj_inc)
    if(EXISTS "${_dir}")
      list(APPEND _mj_inc_ok "${_dir}")
    endif()
  endforeach()
  set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_mj_inc_ok}")
endif()

if(DEPOT_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(DEPOT_BUILD_BENCH)
  find_package(benchmark QUIET)
endif()
