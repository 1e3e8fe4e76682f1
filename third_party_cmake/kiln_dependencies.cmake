# Finds kiln's dependencies among Debian 12 packages and wraps them as kiln::* targets,
# so a later move (Embree 4, a vendored build) touches this file only. Nothing is downloaded:
# a missing package stops configure with the apt package to install.

macro(kiln_require package_name apt_name)
  find_package(${package_name} ${ARGN} QUIET)
  if(NOT ${package_name}_FOUND)
    message(FATAL_ERROR "kiln: ${package_name} not found. Install it with: apt-get install ${apt_name}"
                        " (or run tools/setup.sh, which installs every dependency)")
  endif()
endmacro()

kiln_require(embree libembree-dev 3.13 CONFIG)
kiln_require(TBB libtbb-dev CONFIG)
kiln_require(OpenImageIO libopenimageio-dev CONFIG)
kiln_require(OpenEXR libopenexr-dev 3 CONFIG)
kiln_require(TinyGLTF libtinygltf-dev CONFIG)
kiln_require(glm libglm-dev CONFIG)
kiln_require(CLI11 libcli11-dev CONFIG)
kiln_require(nlohmann_json nlohmann-json3-dev CONFIG)

# Debian's OpenImageIO target lists include folders of optional dependencies (OpenCV) that
# are not installed; CMake refuses targets naming folders that do not exist, so keep only real ones.
get_target_property(_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
set(_oiio_existing "")
foreach(_dir IN LISTS _oiio_includes)
  if(EXISTS "${_dir}")
    list(APPEND _oiio_existing "${_dir}")
  endif()
endforeach()
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_existing}")

add_library(kiln_embree INTERFACE)
target_link_libraries(kiln_embree INTERFACE embree)
add_library(kiln::embree ALIAS kiln_embree)

add_library(kiln_tbb INTERFACE)
target_link_libraries(kiln_tbb INTERFACE TBB::tbb)
add_library(kiln::tbb ALIAS kiln_tbb)

add_library(kiln_oiio INTERFACE)
target_link_libraries(kiln_oiio INTERFACE OpenImageIO::OpenImageIO)
add_library(kiln::oiio ALIAS kiln_oiio)

# EXR files are read and written through OpenEXR alone: linking it costs a process start next to
# nothing, where OpenImageIO's ~260 libraries cost 0.3-2 s.
add_library(kiln_openexr INTERFACE)
target_link_libraries(kiln_openexr INTERFACE OpenEXR::OpenEXR)
add_library(kiln::openexr ALIAS kiln_openexr)

# Debian ships tinygltf as a shared library: never define TINYGLTF_IMPLEMENTATION here.
add_library(kiln_tinygltf INTERFACE)
target_link_libraries(kiln_tinygltf INTERFACE TinyGLTF::TinyGLTF nlohmann_json::nlohmann_json)
add_library(kiln::tinygltf ALIAS kiln_tinygltf)

add_library(kiln_glm INTERFACE)
target_link_libraries(kiln_glm INTERFACE glm::glm)
target_compile_definitions(kiln_glm INTERFACE GLM_ENABLE_EXPERIMENTAL)
add_library(kiln::glm ALIAS kiln_glm)

add_library(kiln_cli11 INTERFACE)
target_link_libraries(kiln_cli11 INTERFACE CLI11::CLI11)
add_library(kiln::cli11 ALIAS kiln_cli11)

add_library(kiln_json INTERFACE)
target_link_libraries(kiln_json INTERFACE nlohmann_json::nlohmann_json)
add_library(kiln::json ALIAS kiln_json)

if(KILN_BUILD_TESTS)
  kiln_require(GTest libgtest-dev CONFIG)
endif()
