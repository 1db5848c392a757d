# Installation: the library, its public headers, the CLI, the runtime
# modules (${CMAKE_INSTALL_LIBDIR}/texproc), a CMake package
# (find_package(texproc): texproc::texproc) and a pkg-config file.
include(CMakePackageConfigHelpers)

set(TEXPROC_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/texproc)
set(TEXPROC_MODULE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/texproc)  # as src/core/module.cpp looks for it

install(TARGETS texproc EXPORT texprocTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime)
if(TARGET texproc_static_codecs)
  install(TARGETS texproc_static_codecs EXPORT texprocTargets)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/libtexproc/include/texproc DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  COMPONENT dev FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/include/texproc/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/texproc
  COMPONENT dev)
install(TARGETS texproc_exr texproc_oiio texproc_ocio
  LIBRARY DESTINATION ${TEXPROC_MODULE_INSTALL_DIR} COMPONENT runtime)
if(TEXPROC_BUILD_CLI)
  install(TARGETS texproc_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
endif()
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/CHANGELOG.md
  DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)

# libtexproc is a static library: its consumers link what it links. The
# package finds those again (the pkg-config modules under the names the
# exported targets use).
set(TEXPROC_PKG_MODULES IMATH=Imath SPNG=spng ZLIB=zlib)
if(NOT TARGET texproc_static_codecs)
  list(APPEND TEXPROC_PKG_MODULES TIFF=libtiff-4 DEFLATE=libdeflate JPEG=libjpeg ZSTD=libzstd)
endif()
install(EXPORT texprocTargets NAMESPACE texproc:: DESTINATION ${TEXPROC_CMAKE_DIR} COMPONENT dev)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/texprocConfig.cmake.in
  ${PROJECT_BINARY_DIR}/texprocConfig.cmake INSTALL_DESTINATION ${TEXPROC_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/texprocConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/texprocConfig.cmake ${PROJECT_BINARY_DIR}/texprocConfigVersion.cmake
  DESTINATION ${TEXPROC_CMAKE_DIR} COMPONENT dev)

file(RELATIVE_PATH TEXPROC_PC_TO_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
configure_file(${PROJECT_SOURCE_DIR}/cmake/texproc.pc.in ${PROJECT_BINARY_DIR}/texproc.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/texproc.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
