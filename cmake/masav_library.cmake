# A library per folder: its sources are the folder's own .cpp (and .cu) files, found at
# configure time, so a folder's files are its library and a new file needs no build line.
#   masav_folder_library(name [DEPENDS public deps...] [PRIVATE private deps...])
function(masav_folder_library name)
  cmake_parse_arguments(arg "" "" "DEPENDS;PRIVATE" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp
       ${CMAKE_CURRENT_SOURCE_DIR}/*.cu)
  add_library(${name} STATIC ${sources})
  # In the tree the repository root; installed, the engine's headers under include/masav/detail
  # (what the public headers in include/masav/ include).
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                                            $<INSTALL_INTERFACE:include/masav/detail>)
  target_link_libraries(${name} PUBLIC ${arg_DEPENDS} PRIVATE ${arg_PRIVATE})
  masav_target_defaults(${name})
endfunction()
