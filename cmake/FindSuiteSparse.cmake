# SuiteSparse 5.12 (Debian 12) ships neither CMake config nor pkg-config files.
# Defines SuiteSparse::CHOLMOD and SuiteSparse::UMFPACK (with their dependencies).
find_path(SuiteSparse_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
foreach(lib cholmod umfpack amd colamd camd ccolamd suitesparseconfig)
  string(TOUPPER ${lib} LIB)
  find_library(SuiteSparse_${LIB}_LIBRARY ${lib})
  list(APPEND SuiteSparse_REQUIRED_VARS SuiteSparse_${LIB}_LIBRARY)
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse REQUIRED_VARS SuiteSparse_INCLUDE_DIR ${SuiteSparse_REQUIRED_VARS})

if(SuiteSparse_FOUND AND NOT TARGET SuiteSparse::CHOLMOD)
  add_library(SuiteSparse::config UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::config PROPERTIES
    IMPORTED_LOCATION ${SuiteSparse_SUITESPARSECONFIG_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${SuiteSparse_INCLUDE_DIR})
  foreach(lib AMD COLAMD CAMD CCOLAMD)
    add_library(SuiteSparse::${lib} UNKNOWN IMPORTED)
    set_target_properties(SuiteSparse::${lib} PROPERTIES
      IMPORTED_LOCATION ${SuiteSparse_${lib}_LIBRARY}
      INTERFACE_LINK_LIBRARIES SuiteSparse::config)
  endforeach()
  add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
    IMPORTED_LOCATION ${SuiteSparse_CHOLMOD_LIBRARY}
    INTERFACE_LINK_LIBRARIES "SuiteSparse::AMD;SuiteSparse::COLAMD;SuiteSparse::CAMD;SuiteSparse::CCOLAMD")
  add_library(SuiteSparse::UMFPACK UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::UMFPACK PROPERTIES
    IMPORTED_LOCATION ${SuiteSparse_UMFPACK_LIBRARY}
    INTERFACE_LINK_LIBRARIES "SuiteSparse::CHOLMOD;SuiteSparse::AMD")
endif()
