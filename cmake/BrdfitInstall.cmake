# `cmake --install build --prefix P` (docs/library.md): the public headers under
# P/include/brdfit/<layer>/, the layer libraries under P/lib, the CLI under P/bin, the Python
# module under P/${BRDFIT_PYTHON_INSTALL_DIR}, and P/lib/cmake/brdfit/brdfitConfig.cmake with
# the exported targets brdfit::<layer> and brdfit::brdfit (everything: pipeline and export).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(_brdfit_layers models core io export fit factor report preview pipeline)
foreach(_l ${_brdfit_layers})
  install(DIRECTORY ${CMAKE_SOURCE_DIR}/${_l}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/brdfit/${_l}
          FILES_MATCHING PATTERN "*.h" PATTERN "*.glsl")
  set_target_properties(brdfit_${_l} PROPERTIES EXPORT_NAME ${_l})
endforeach()

# brdfit::brdfit: the whole library (pipeline/ links every layer below it but export/, which
# the commands use beside it).
add_library(brdfit_all INTERFACE)
target_link_libraries(brdfit_all INTERFACE brdfit_pipeline brdfit_export)
set_target_properties(brdfit_all PROPERTIES EXPORT_NAME brdfit)
# The warnings target is a link-only dependency of the static libraries: exported, empty of
# meaning for consumers.
set_target_properties(brdfit_warnings PROPERTIES EXPORT_NAME warnings)
# The io layer's HDF5 (cmake/BrdfitHdf5.cmake): the shared libraries for a consumer.
set_target_properties(brdfit_hdf5 PROPERTIES EXPORT_NAME hdf5)

list(TRANSFORM _brdfit_layers PREPEND brdfit_ OUTPUT_VARIABLE _brdfit_targets)
install(TARGETS ${_brdfit_targets} brdfit_all brdfit_warnings brdfit_hdf5 EXPORT brdfitTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/brdfit)
install(TARGETS brdfit RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT brdfitTargets NAMESPACE brdfit:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/brdfit)

if(BRDFIT_PYTHON_BUILT)
  set(BRDFIT_PYTHON_INSTALL_DIR
      "${CMAKE_INSTALL_LIBDIR}/python${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}/site-packages"
      CACHE STRING "where cmake --install puts the Python module, relative to the prefix")
  install(TARGETS brdfit_python LIBRARY DESTINATION ${BRDFIT_PYTHON_INSTALL_DIR} COMPONENT python)
  # Where Debian's python3 finds a packaged extension (Debian Python Policy §3.6): the .deb's
  # copy (cmake/BrdfitPackage.cmake), left out of a plain `cmake --install`.
  install(TARGETS brdfit_python LIBRARY DESTINATION lib/python3/dist-packages
          COMPONENT debian_python EXCLUDE_FROM_ALL)
endif()

# brdfit_preview links glfw privately when it was found (preview/CMakeLists.txt): a link-only
# dependency the consumer must find too.
get_target_property(_preview_libs brdfit_preview LINK_LIBRARIES)
set(BRDFIT_NEEDS_GLFW OFF)
if("glfw" IN_LIST _preview_libs)
  set(BRDFIT_NEEDS_GLFW ON)
endif()
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/brdfitConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/brdfitConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/brdfit)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/brdfitConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/brdfitConfig.cmake ${CMAKE_BINARY_DIR}/brdfitConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/brdfit)
