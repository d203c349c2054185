# uniparam_layer(NAME DEPENDS): the static library uniparam_<NAME> of one
# layer (core, algebra, reparam): every src/*.cpp of the calling folder, the
# public headers of its include/ (installed as uniparam/<NAME>/...), the
# alias uniparam::<NAME>, linked PUBLIC to DEPENDS (the layer below only).
function(uniparam_layer NAME DEPENDS)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(uniparam_${NAME} STATIC ${sources})
  add_library(uniparam::${NAME} ALIAS uniparam_${NAME})
  set_target_properties(uniparam_${NAME} PROPERTIES POSITION_INDEPENDENT_CODE ON EXPORT_NAME ${NAME})
  target_include_directories(uniparam_${NAME} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(uniparam_${NAME} PUBLIC ${DEPENDS})
  target_compile_options(uniparam_${NAME} PRIVATE -Wall -Wextra)
endfunction()
