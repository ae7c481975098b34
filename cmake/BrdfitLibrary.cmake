# brdfit_layer(<layer> [EXECUTABLE name | PYMODULE name] [LAYERS lower...] [LIBS external...]):
# the CMake library brdfit_<layer> (or, with EXECUTABLE, the program of that name; with
# PYMODULE, the Python extension module of that name, target brdfit_<layer>)
# of one layer folder (docs/architecture.md), built from every .cc in the folder (globbed with
# CONFIGURE_DEPENDS: adding a file needs no CMake edit; no .cc gives an INTERFACE library).
# LAYERS names the lower layers this one may use: they are its only brdfit link dependencies,
# and tests/architecture/check_layers.py reads these calls to check every #include against them
# (an include of a layer that is not below fails `make test`).
function(brdfit_layer layer)
  cmake_parse_arguments(L "" "EXECUTABLE;PYMODULE" "LAYERS;LIBS" ${ARGN})
  set(name brdfit_${layer})
  set(deps)
  foreach(l ${L_LAYERS})
    list(APPEND deps brdfit_${l})
  endforeach()
  file(GLOB _srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  if(L_EXECUTABLE)
    add_executable(${L_EXECUTABLE} ${_srcs})
    target_link_libraries(${L_EXECUTABLE} PRIVATE ${deps} ${L_LIBS} brdfit_warnings)
    set_target_properties(${L_EXECUTABLE} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR})
  elseif(L_PYMODULE)
    pybind11_add_module(${name} MODULE NO_EXTRAS ${_srcs})  # no LTO
    target_link_libraries(${name} PRIVATE ${deps} ${L_LIBS} brdfit_warnings)
    set_target_properties(${name} PROPERTIES OUTPUT_NAME ${L_PYMODULE})
  elseif(_srcs)
    add_library(${name} STATIC ${_srcs})
    target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}>
                                              $<INSTALL_INTERFACE:include/brdfit>)
    if(BRDFIT_PYTHON_BUILT)  # linked into the Python module too (cmake/BrdfitPython.cmake)
      set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
      # Direct calls inside the library as without -fPIC (GCC keeps them interposable else).
      target_compile_options(${name} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-fno-semantic-interposition>)
    endif()
    set_property(GLOBAL APPEND PROPERTY BRDFIT_LIBRARIES ${name})
    target_link_libraries(${name} PUBLIC ${deps} ${L_LIBS} PRIVATE brdfit_warnings)
  else()
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}>
                                                 $<INSTALL_INTERFACE:include/brdfit>)
    set_property(GLOBAL APPEND PROPERTY BRDFIT_LIBRARIES ${name})
    target_link_libraries(${name} INTERFACE ${deps} ${L_LIBS})
  endif()
endfunction()
