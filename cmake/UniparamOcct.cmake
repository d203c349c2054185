# uniparam_find_occt(PREFIX HEADER LIB...): OpenCASCADE for a test or a
# benchmark (never a dependency of the library). Looks for HEADER (in an
# opencascade/ folder too) and every LIB; sets in the caller's scope
#   PREFIX_INCLUDE_DIR  the folder of HEADER (cached),
#   PREFIX_PATHS        the libraries' paths, in the order given (each cached
#                       as PREFIX_<LIB>),
#   PREFIX_FOUND        false when the header or any library is missing.
function(uniparam_find_occt PREFIX HEADER)
  find_path(${PREFIX}_INCLUDE_DIR ${HEADER} PATH_SUFFIXES opencascade)
  set(found ${${PREFIX}_INCLUDE_DIR})
  set(paths)
  foreach(lib ${ARGN})
    find_library(${PREFIX}_${lib} ${lib})
    if(NOT ${PREFIX}_${lib})
      set(found FALSE)
    endif()
    list(APPEND paths ${${PREFIX}_${lib}})
  endforeach()
  set(${PREFIX}_FOUND ${found} PARENT_SCOPE)
  set(${PREFIX}_PATHS ${paths} PARENT_SCOPE)
endfunction()
