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
kiln_require(draco libdraco-dev CONFIG)
kiln_require(meshoptimizer libmeshoptimizer-dev CONFIG)
kiln_require(PNG libpng-dev)
kiln_require(JPEG libjpeg-dev)
# Debian 12's libopencolorio-dev puts its config files straight into /usr/share/cmake, a folder
# find_package does not search; PATHS are searched after the usual places, so another install wins.
kiln_require(OpenColorIO libopencolorio-dev 2.1 CONFIG PATHS /usr/share/cmake)

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

# OpenColorIO 2.1 links only into the colour module (io/colour), opened when a render names a
# working space or a config: linking it into kiln would cost every process start 1.4-1.8 ms.
add_library(kiln_ocio INTERFACE)
target_link_libraries(kiln_ocio INTERFACE OpenColorIO::OpenColorIO)
add_library(kiln::ocio ALIAS kiln_ocio)

# EXR files are read and written through OpenEXR alone: linking it costs a process start next to
# nothing, where OpenImageIO's ~260 libraries cost 0.3-2 s.
add_library(kiln_openexr INTERFACE)
target_link_libraries(kiln_openexr INTERFACE OpenEXR::OpenEXR OpenEXR::OpenEXRCore)
add_library(kiln::openexr ALIAS kiln_openexr)

# Debian ships tinygltf as a shared library: never define TINYGLTF_IMPLEMENTATION here.
add_library(kiln_tinygltf INTERFACE)
target_link_libraries(kiln_tinygltf INTERFACE TinyGLTF::TinyGLTF nlohmann_json::nlohmann_json)
add_library(kiln::tinygltf ALIAS kiln_tinygltf)

# Draco links statically, from a copy of Debian's libdraco.a without its glTF members. The
# archive also holds draco's own build of tinygltf and stb_image (tiny_gltf_utils.cc.o), and GNU ld
# extracts that member for a symbol Debian's libtinygltf.so leaves undefined (stbi_image_free)
# whatever the order of the link line: kiln would then call draco's tinygltf, whose Model and
# TinyGLTF differ from Debian's headers (a crash on every load). Without those members only the
# decoder objects kiln calls are linked (no library added to process start), and a decoder
# object that ever needed a glTF member would fail the link instead of mixing two tinygltfs.
# tests/link_check_test.cpp checks that kiln defines no tinygltf or stb function of its own.
get_target_property(_draco_archive draco::draco_static IMPORTED_LOCATION_NONE)
set(_draco_work "${CMAKE_BINARY_DIR}/third_party/draco_decoder")
set(KILN_DRACO_ARCHIVE "${_draco_work}/libdraco_decoder.a")
if(NOT EXISTS "${KILN_DRACO_ARCHIVE}" OR "${_draco_archive}" IS_NEWER_THAN "${KILN_DRACO_ARCHIVE}")
  file(REMOVE_RECURSE "${_draco_work}")
  file(MAKE_DIRECTORY "${_draco_work}/objects")
  execute_process(COMMAND ${CMAKE_AR} x "${_draco_archive}" WORKING_DIRECTORY "${_draco_work}/objects"
                  RESULT_VARIABLE _draco_rc)
  file(GLOB _draco_gltf_members "${_draco_work}/objects/*gltf*.o" "${_draco_work}/objects/mesh_io.cc.o"
       "${_draco_work}/objects/scene_io.cc.o")
  if(NOT _draco_rc EQUAL 0 OR NOT _draco_gltf_members)
    message(FATAL_ERROR "kiln: could not take libdraco.a apart (${_draco_archive})")
  endif()
  file(REMOVE ${_draco_gltf_members})
  file(GLOB _draco_members "${_draco_work}/objects/*.o")
  execute_process(COMMAND ${CMAKE_AR} qcs "${KILN_DRACO_ARCHIVE}" ${_draco_members} RESULT_VARIABLE _draco_rc)
  if(NOT _draco_rc EQUAL 0)
    message(FATAL_ERROR "kiln: could not write ${KILN_DRACO_ARCHIVE}")
  endif()
  file(REMOVE_RECURSE "${_draco_work}/objects")
endif()
# The archive by path, so the installed package (renderer/package) names its own copy in lib/kiln.
add_library(kiln_draco INTERFACE)
target_link_libraries(kiln_draco INTERFACE "$<BUILD_INTERFACE:${KILN_DRACO_ARCHIVE}>"
                                           "$<INSTALL_INTERFACE:$<INSTALL_PREFIX>/lib/kiln/libdraco_decoder.a>")
add_library(kiln::draco ALIAS kiln_draco)

# Core glTF's two image formats decode through libpng and libjpeg in kiln itself
# (io/image_codecs/direct_decode.h): two small libraries, where the codecs module's OpenImageIO
# costs a textured render 0.2 s of process start and more on a loaded machine.
add_library(kiln_png_jpeg INTERFACE)
target_link_libraries(kiln_png_jpeg INTERFACE PNG::PNG JPEG::JPEG)
add_library(kiln::png_jpeg ALIAS kiln_png_jpeg)

# zlib's CRC-32 is the content checksum of every output (io/exr/exr_checksum.h); libpng needs zlib anyway.
kiln_require(ZLIB zlib1g-dev)
add_library(kiln_zlib INTERFACE)
target_link_libraries(kiln_zlib INTERFACE ZLIB::ZLIB)
add_library(kiln::zlib ALIAS kiln_zlib)

add_library(kiln_meshoptimizer INTERFACE)
target_link_libraries(kiln_meshoptimizer INTERFACE meshoptimizer::meshoptimizer)
add_library(kiln::meshoptimizer ALIAS kiln_meshoptimizer)

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
