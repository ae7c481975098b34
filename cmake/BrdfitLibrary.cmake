# brdfit_layer(<layer> [EXECUTABLE name] [LAYERS lower...] [LIBS external...]): the CMake
# library brdfit_<layer> (or, with EXECUTABLE, the program of that name)
# of one layer folder (docs/architecture.md), built from every .cc in the folder (globbed with
# CONFIGURE_DEPENDS: adding a file needs no CMake edit; no .cc gives an INTERFACE library).
# LAYERS names the lower layers this one may use: they are its only brdfit link dependencies,
# and tests/architecture/check_layers.py reads these calls to check every #include against them
# (an include of a layer that is not below fails `make test`).
function(brdfit_layer layer)
  cmake_parse_arguments(L "" "EXECUTABLE" "LAYERS;LIBS" ${ARGN})
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
  elseif(_srcs)
    add_library(${name} STATIC ${_srcs})
    target_include_directories(${name} PUBLIC ${CMAKE_SOURCE_DIR})
    target_link_libraries(${name} PUBLIC ${deps} ${L_LIBS} PRIVATE brdfit_warnings)
  else()
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${CMAKE_SOURCE_DIR})
    target_link_libraries(${name} INTERFACE ${deps} ${L_LIBS})
  endif()
endfunction()
