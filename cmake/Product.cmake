# The product: what shading needs, built into one library (phongcl::phongcl, installed) and the
# `phongcl` command line on top of it. Nothing here may link the lab (cmake/Lab.cmake).
phongcl_room(common)
phongcl_room(exr      DEPS phongcl_common OpenEXR::OpenEXR OpenEXR::OpenEXRCore)
phongcl_room(scene    DEPS phongcl_common glm::glm nlohmann_json::nlohmann_json)
phongcl_room(gbuffer  DEPS phongcl_common phongcl_exr)
phongcl_room(image    DEPS phongcl_common phongcl_exr PNG::PNG)
phongcl_room(cl       DEPS phongcl_common phongcl_opencl phongcl_kernels)
# Shadow geometry: meshes read with Assimp, the scene flattened into world space, the BVH and its
# device layout (kernels/shadow_layout.h).
phongcl_room(geometry DEPS phongcl_scene phongcl_kernels assimp::assimp)
# The environment light's maps: an equirect EXR read, validated and convolved to its irradiance.
phongcl_room(environment DEPS phongcl_common phongcl_exr phongcl_scene)
phongcl_room(shading  DEPS phongcl_cl phongcl_scene phongcl_gbuffer phongcl_image phongcl_geometry phongcl_environment phongcl_kernels)
phongcl_room(raycast  DEPS phongcl_scene phongcl_gbuffer phongcl_geometry)
phongcl_room(color    DEPS phongcl_image phongcl_scene phongcl_gbuffer PkgConfig::OCIO yaml-cpp)
# The display transforms' AVX2 loops, chosen at run time where the CPU has AVX2 and FMA
# (host/color/pixel_kernels.h): the rest of the product stays baseline x86-64. Multiply-adds are fused
# where the code says so (_mm256_fmadd_ps), not wherever the compiler may.
set_source_files_properties(host/color/pixel_kernels_avx2.cpp TARGET_DIRECTORY phongcl_color PROPERTIES COMPILE_OPTIONS "-mavx2;-mfma;-ffp-contract=off")
phongcl_room(sequence DEPS phongcl_shading Threads::Threads)
# Relighting over a render: its light-group passes kept, scaled or replaced by the shading of the group.
phongcl_room(composite DEPS phongcl_shading phongcl_image phongcl_exr phongcl_scene)

# One shared library of every product room's objects. Its public face is include/phongcl/ (and the
# room headers those include, installed beside them); dependencies stay private but for GLM, whose
# vectors the scene structs hold.
get_property(product_objects GLOBAL PROPERTY PHONGCL_PRODUCT_OBJECTS)
add_library(phongcl_library SHARED)
add_library(phongcl::phongcl ALIAS phongcl_library)
set_target_properties(phongcl_library PROPERTIES OUTPUT_NAME phongcl EXPORT_NAME phongcl
                      VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR})
target_link_libraries(phongcl_library PRIVATE ${product_objects} phongcl_kernels PUBLIC glm::glm)
target_include_directories(phongcl_library PUBLIC
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/host>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_compile_features(phongcl_library PUBLIC cxx_std_20)

# In the build tree, the command line, the lab and the tests also use the rooms' own headers, which
# reach OpenCL, OpenEXR and JSON directly.
add_library(phongcl_internal INTERFACE)
target_link_libraries(phongcl_internal INTERFACE phongcl_library phongcl_opencl OpenEXR::OpenEXR OpenEXR::OpenEXRCore
                      nlohmann_json::nlohmann_json PNG::PNG PkgConfig::OCIO)
target_include_directories(phongcl_internal INTERFACE ${PROJECT_SOURCE_DIR}/host ${PROJECT_SOURCE_DIR})

# What the product and lab command lines share: option groups, number formats, the top-level catch.
add_library(phongcl_cli_support STATIC host/cli/format.cpp host/cli/inputs.cpp host/cli/outputs.cpp
            host/cli/run_app.cpp)
target_link_libraries(phongcl_cli_support PUBLIC phongcl_internal CLI11::CLI11)

file(GLOB PHONGCL_CLI_COMMANDS CONFIGURE_DEPENDS host/cli/*_command.cpp)
add_executable(phongcl host/cli/main.cpp host/cli/lab_handover.cpp host/cli/shade_over.cpp host/cli/shade_sequence.cpp
               host/cli/sequence_progress.cpp ${PHONGCL_CLI_COMMANDS})
target_link_libraries(phongcl PRIVATE phongcl_cli_support)
# Installed, it finds libphongcl beside it in ../lib.
set_target_properties(phongcl PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
