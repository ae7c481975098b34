# brdfit_hdf5: the HDF5 libraries the io layer links (HDF5 tables and fit reports).
#
# A target that sets the property BRDFIT_STATIC_HDF5 (the brdfit executable, cli/CMakeLists.txt)
# links Debian's static archives of the same HDF5 when they exist: the shared libhdf5 brings
# libcurl and its TLS, Kerberos, LDAP and IDN libraries (30 of the executable's 80 shared
# libraries) for a remote-file driver (ROS3) brdfit never opens, and loading them is a third of
# every command's start (`brdfit --version` 18 -> 11 ms; docs/fitting.md, "Whole command"). The
# static archives reference none of them. Everything else (the installed library, the Python
# module, the tests) links the shared HDF5: one HDF5 per process beside h5py or another user.
# Sanitizer and fuzz builds keep it shared too: their leak suppressions and scripts/fuzz.sh
# recognise HDF5's own allocations and crashes by the library's name in a stack frame.
option(BRDFIT_CLI_STATIC_HDF5 "Link the brdfit executable with the static HDF5 archives if present" ON)
add_library(brdfit_hdf5 INTERFACE)
get_filename_component(_brdfit_hdf5_dir "${HDF5_C_LIBRARY_hdf5}" DIRECTORY)
set(_brdfit_hdf5_static "")
if(BRDFIT_CLI_STATIC_HDF5 AND NOT BRDFIT_SANITIZE AND NOT BRDFIT_FUZZ
   AND EXISTS "${_brdfit_hdf5_dir}/libhdf5.a" AND EXISTS "${_brdfit_hdf5_dir}/libhdf5_cpp.a")
  find_library(BRDFIT_SZIP_LIBRARY NAMES sz)
  find_package(ZLIB)
  if(BRDFIT_SZIP_LIBRARY AND ZLIB_FOUND)
    # The C++ archive first: it uses the C one.
    set(_brdfit_hdf5_static "${_brdfit_hdf5_dir}/libhdf5_cpp.a;${_brdfit_hdf5_dir}/libhdf5.a;"
                            "${BRDFIT_SZIP_LIBRARY};${ZLIB_LIBRARIES};${CMAKE_DL_LIBS};m")
    string(REPLACE ";;" ";" _brdfit_hdf5_static "${_brdfit_hdf5_static}")
  endif()
endif()
if(_brdfit_hdf5_static)
  set(_static "$<BOOL:$<TARGET_PROPERTY:BRDFIT_STATIC_HDF5>>")
  target_link_libraries(brdfit_hdf5 INTERFACE
                        "$<${_static}:${_brdfit_hdf5_static}>"
                        "$<$<NOT:${_static}>:hdf5::hdf5_cpp;hdf5::hdf5>")
  message(STATUS "brdfit executable: static HDF5 from ${_brdfit_hdf5_dir}")
else()
  target_link_libraries(brdfit_hdf5 INTERFACE hdf5::hdf5_cpp hdf5::hdf5)
endif()
