# The rooms of the house (CONTRIBUTING.md "Layout: the rooms"). A room is a folder of sources with one
# job, included as "NAME/header.h"; its DEPS are the architecture's "may use" column.

# phongcl_room(NAME [DEPS targets...]): host/NAME/*.cpp, a product room. Its objects go into the one
# product library (phongcl::phongcl, cmake/Product.cmake); a header-only room is an interface target.
function(phongcl_room name)
  cmake_parse_arguments(ROOM "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/host/${name}/*.cpp)
  if(sources)
    add_library(phongcl_${name} OBJECT ${sources})
    target_include_directories(phongcl_${name} PUBLIC ${PROJECT_SOURCE_DIR}/host ${PROJECT_SOURCE_DIR}/include)
    target_link_libraries(phongcl_${name} PUBLIC ${ROOM_DEPS})
    set_property(GLOBAL APPEND PROPERTY PHONGCL_PRODUCT_OBJECTS phongcl_${name})
  else()
    add_library(phongcl_${name} INTERFACE)
    target_include_directories(phongcl_${name} INTERFACE ${PROJECT_SOURCE_DIR}/host)
    target_link_libraries(phongcl_${name} INTERFACE ${ROOM_DEPS})
  endif()
endfunction()

# phongcl_lab_room(NAME [DEPS targets...]): lab/NAME/*.cpp as a static library. The lab links the
# product (phongcl_internal), never the other way round, and none of it is installed.
function(phongcl_lab_room name)
  cmake_parse_arguments(ROOM "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/lab/${name}/*.cpp)
  add_library(phongcl_${name} STATIC ${sources})
  target_include_directories(phongcl_${name} PUBLIC ${PROJECT_SOURCE_DIR}/lab)
  target_link_libraries(phongcl_${name} PUBLIC phongcl_internal ${ROOM_DEPS})
endfunction()
