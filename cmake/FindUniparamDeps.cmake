# Locates GMP, MPFR, FLINT and Arb, which ship neither CMake nor pkg-config
# files on Debian 12, and defines the imported target uniparam_deps::numeric.
if(TARGET uniparam_deps::numeric)
  return()
endif()
find_path(FLINT_INCLUDE_DIR flint/flint.h REQUIRED)
find_path(ARB_INCLUDE_DIR arb.h PATH_SUFFIXES arb REQUIRED)
find_library(FLINT_LIBRARY NAMES flint REQUIRED)
find_library(ARB_LIBRARY NAMES flint-arb arb REQUIRED)
find_library(MPFR_LIBRARY NAMES mpfr REQUIRED)
find_library(GMP_LIBRARY NAMES gmp REQUIRED)
add_library(uniparam_deps::numeric INTERFACE IMPORTED)
set_target_properties(uniparam_deps::numeric PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${FLINT_INCLUDE_DIR};${ARB_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${ARB_LIBRARY};${FLINT_LIBRARY};${MPFR_LIBRARY};${GMP_LIBRARY}")
