# `cpack -G DEB` (scripts/package.sh): one Debian package with the tool, its
# runtime modules, libtexproc with its headers and CMake/pkg-config files,
# and the Python package. Runtime dependencies are read off the binaries by
# dpkg-shlibdeps; what building against the static library needs is
# recommended. Build it from a folder configured with
# -DCMAKE_INSTALL_PREFIX=/usr, so that the paths compiled in are Debian's.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME texproc)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "texproc")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Texture processing for asset pipelines: mip chains, block compression, normal and cone maps")
set(CPACK_PACKAGE_DESCRIPTION
    "texproc cooks textures for real-time graphics: gamma-correct mip chains, BC1-BC7, BC6H, ETC, EAC and ASTC
compression into DDS, KTX2 and KTX1, normal and cone step maps from heightmaps, summed-area tables, cube maps
and image-based lighting. The package holds the texproc tool, libtexproc (static, with headers, a CMake package
and a pkg-config file) and the Python package texproc.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "texproc maintainers <texproc@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(_texproc_deb_depends "")
if(TEXPROC_BUILD_PYTHON)
  # The extension is built for one Python version.
  set(_texproc_deb_depends "python3 (>= ${TEXPROC_PYTHON_VERSION}), python3 (<< ${TEXPROC_PYTHON_VERSION}.99), python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${_texproc_deb_depends}")
# The astc-encoder library is opened with dlopen (ASTC only), so no binary names it.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "libastcenc3d, pkg-config, libtbb-dev, libhwy-dev, libspng-dev, libimath-dev, zlib1g-dev, libtiff-dev, libjpeg62-turbo-dev, libdeflate-dev, libzstd-dev, libwebp-dev, liblzma-dev, liblerc-dev, libjbig-dev")
if(NOT CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  message(STATUS "texproc: CMAKE_INSTALL_PREFIX is ${CMAKE_INSTALL_PREFIX}; a Debian package wants /usr "
                 "(scripts/package.sh configures it so)")
endif()
include(CPack)
