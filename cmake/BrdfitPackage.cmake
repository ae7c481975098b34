# `cpack -G DEB` in the build folder (docs/library.md, "A Debian package"): one package,
# brdfit_<version>_<arch>.deb, installing under /usr what `cmake --install` installs — the
# command, the layer libraries with their headers and CMake package — and the Python module
# where Debian's python3 finds it (/usr/lib/python3/dist-packages; the debian_python component
# of cmake/BrdfitInstall.cmake) instead of the prefix's site-packages.
set(CPACK_PACKAGE_NAME brdfit)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "fit, factorize, preview and export tabulated isotropic BRDFs")
set(CPACK_PACKAGE_DESCRIPTION
    "brdfit loads measured isotropic BRDF tables (MERL .binary, HDF5, RGL .bsdf, NBRDF),\n\
fits analytic models to them, factorizes them into textures, previews them and exports\n\
them to glTF, three.js, Blender, Mitsuba 3 and pbrt-v4. This package holds the brdfit\n\
command, the C++ library (static, with headers and a CMake package) and the Python module.")
set(CPACK_PACKAGE_CONTACT "brdfit maintainers <maintainers@brdfit.invalid>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)

# The installed files, as `cmake --install` lays them out, plus the Debian location of the
# Python module; the prefix's site-packages copy (component python) stays out.
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_COMPONENTS_ALL Unspecified)
if(BRDFIT_PYTHON_BUILT)
  list(APPEND CPACK_COMPONENTS_ALL debian_python)
endif()

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# The shared libraries the command and the module link (libceres, libOpenEXR, libhdf5, libEGL,
# ...) become Depends through dpkg-shlibdeps (dpkg-dev); the module adds its interpreter.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
if(BRDFIT_PYTHON_BUILT)
  math(EXPR _next_minor "${Python_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
      "python3 (>= ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}), python3 (<< ${Python_VERSION_MAJOR}.${_next_minor}), python3-numpy")
endif()
# What find_package(brdfit) finds the library's own dependencies with (brdfitConfig.cmake).
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
    "cmake, pkg-config, libceres-dev, libeigen3-dev, libopenexr-dev, libhdf5-dev, nlohmann-json3-dev, libfmt-dev, libpng-dev, libtinyobjloader-dev, libzip-dev, libegl-dev, libgl-dev, libglfw3-dev")
set(CPACK_GENERATOR DEB)
include(CPack)
