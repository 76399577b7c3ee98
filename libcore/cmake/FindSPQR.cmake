# SPDX-License-Identifier: LGPL-2.1-or-later
# Finds SuiteSparseQR (SPQR) and defines the imported target SPQR::SPQR.
# SuiteSparse 7+ ships a CMake package (SuiteSparse::SPQR), used when present;
# SuiteSparse 5 (Debian 12) has none, so the header and library are searched
# for directly. SPQR needs CHOLMOD (find it first) and LAPACK/BLAS.
find_package(SPQR CONFIG QUIET NAMES SPQR)
if(TARGET SuiteSparse::SPQR)
  if(NOT TARGET SPQR::SPQR)
    add_library(SPQR::SPQR INTERFACE IMPORTED)
    target_link_libraries(SPQR::SPQR INTERFACE SuiteSparse::SPQR)
  endif()
  set(SPQR_FOUND TRUE)
  return()
endif()

find_path(SPQR_INCLUDE_DIR SuiteSparseQR_C.h PATH_SUFFIXES suitesparse)
find_library(SPQR_LIBRARY NAMES spqr)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SPQR REQUIRED_VARS SPQR_LIBRARY SPQR_INCLUDE_DIR)
if(SPQR_FOUND AND NOT TARGET SPQR::SPQR)
  add_library(SPQR::SPQR UNKNOWN IMPORTED)
  set_target_properties(SPQR::SPQR PROPERTIES
    IMPORTED_LOCATION "${SPQR_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${SPQR_INCLUDE_DIR}")
  if(TARGET CHOLMOD::CHOLMOD)
    set_property(TARGET SPQR::SPQR APPEND PROPERTY INTERFACE_LINK_LIBRARIES CHOLMOD::CHOLMOD)
  endif()
endif()
mark_as_advanced(SPQR_INCLUDE_DIR SPQR_LIBRARY)
