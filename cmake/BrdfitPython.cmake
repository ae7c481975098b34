# Whether the Python module (python/, docs/python.md) is built: BRDFIT_PYTHON and pybind11
# found, never under BRDFIT_SANITIZE (an ASan-instrumented extension cannot be loaded by an
# uninstrumented python3 without preloading libasan; its tests say so and skip). When built,
# the layer libraries are compiled position-independent so that the module can link them.
if(BRDFIT_PYTHON AND BRDFIT_SANITIZE)
  message(STATUS "brdfit: Python module not built under BRDFIT_SANITIZE (python3 cannot load "
                 "an ASan-instrumented extension without LD_PRELOAD of libasan)")
  set(BRDFIT_PYTHON OFF)
endif()
if(BRDFIT_PYTHON AND BRDFIT_FUZZ)
  message(STATUS "brdfit: Python module not built with BRDFIT_FUZZ (the fuzz build is sanitized)")
  set(BRDFIT_PYTHON OFF)
endif()
if(BRDFIT_PYTHON)
  # The Debian interpreter, whose python3-numpy and python3-pytest scripts/setup-deps.sh
  # installs, before any other python3 on the PATH (pyenv, conda); -DPython_EXECUTABLE=... wins.
  if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python_EXECUTABLE /usr/bin/python3)
  endif()
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG QUIET)
  if(NOT pybind11_FOUND)
    message(STATUS "brdfit: pybind11 not found (Debian python3-pybind11): no Python module")
    set(BRDFIT_PYTHON OFF)
  endif()
endif()
set(BRDFIT_PYTHON_BUILT ${BRDFIT_PYTHON})
