# Locates GMP, MPFR, FLINT and Arb, which ship neither CMake nor pkg-config
# files on Debian 12, and defines the imported target uniparam_deps::numeric.
# Used by the build and by the installed uniparamConfig.cmake. A missing
# library is a fatal error, unless the includer set UNIPARAM_DEPS_SOFT: then
# UniparamDeps_FOUND is FALSE and UniparamDeps_NOT_FOUND_MESSAGE says why.
if(TARGET uniparam_deps::numeric)
  set(UniparamDeps_FOUND TRUE)
  return()
endif()
find_path(FLINT_INCLUDE_DIR flint/flint.h)
find_path(ARB_INCLUDE_DIR arb.h PATH_SUFFIXES arb)
find_library(FLINT_LIBRARY NAMES flint)
find_library(ARB_LIBRARY NAMES flint-arb arb)
find_library(MPFR_LIBRARY NAMES mpfr)
find_library(GMP_LIBRARY NAMES gmp)
set(_uniparam_deps_missing "")
foreach(_v FLINT_INCLUDE_DIR ARB_INCLUDE_DIR FLINT_LIBRARY ARB_LIBRARY MPFR_LIBRARY GMP_LIBRARY)
  if(NOT ${_v})
    list(APPEND _uniparam_deps_missing ${_v})
  endif()
endforeach()
if(_uniparam_deps_missing)
  set(UniparamDeps_FOUND FALSE)
  list(JOIN _uniparam_deps_missing ", " _uniparam_deps_missing)
  set(UniparamDeps_NOT_FOUND_MESSAGE "uniparam needs GMP, MPFR, FLINT 2.9 and Arb 2.23; \
not found: ${_uniparam_deps_missing}. On Debian 12: apt-get install libgmp-dev libmpfr-dev \
libflint-dev libflint-arb-dev (or run scripts/install-deps.sh); elsewhere set \
CMAKE_PREFIX_PATH or those variables.")
  unset(_uniparam_deps_missing)
  if(NOT UNIPARAM_DEPS_SOFT)
    message(FATAL_ERROR "${UniparamDeps_NOT_FOUND_MESSAGE}")
  endif()
  return()
endif()
unset(_uniparam_deps_missing)
set(UniparamDeps_FOUND TRUE)
add_library(uniparam_deps::numeric INTERFACE IMPORTED)
set_target_properties(uniparam_deps::numeric PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${FLINT_INCLUDE_DIR};${ARB_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${ARB_LIBRARY};${FLINT_LIBRARY};${MPFR_LIBRARY};${GMP_LIBRARY}")
