# hoilcd_subsystem(<layer> <name> [PUBLIC deps...] [PRIVATE deps...]): the library of one
# subsystem folder <layer>/<name>/ (headers in include/hoilcd/<layer>/<name>/, sources in src/),
# as target hoilcd_<layer>_<name> and alias hoilcd::<layer>_<name>. Its include folder is seen
# only by targets that link it, so an include of an undeclared subsystem fails to compile: the
# build enforces the dependency rule (docs/design.md). Every subsystem joins its layer's
# aggregate target hoilcd::<layer> and the install export.
function(hoilcd_subsystem layer name)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE" ${ARGN})
  set(target hoilcd_${layer}_${name})
  set(dir ${CMAKE_CURRENT_SOURCE_DIR}/${name})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${dir}/src/*.cpp)  # methods keep a folder each
  add_library(${target} ${sources})
  add_library(hoilcd::${layer}_${name} ALIAS ${target})
  target_include_directories(${target}
    PUBLIC $<BUILD_INTERFACE:${dir}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${dir}/src)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  # Also linked into the Python module (a shared object): position independent, and
  # -fno-semantic-interposition lets GCC inline within a library as it does without -fPIC.
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON
                                             EXPORT_NAME ${layer}_${name})
  target_compile_options(${target} PRIVATE -fno-semantic-interposition)
  hoilcd_warnings(${target})
  target_link_libraries(hoilcd_${layer} INTERFACE ${target})
  set_property(GLOBAL APPEND PROPERTY HOILCD_SUBSYSTEMS ${target})
  install(DIRECTORY ${dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# hoilcd_layer(<layer>): the aggregate target hoilcd::<layer>, every subsystem of the layer.
function(hoilcd_layer layer)
  add_library(hoilcd_${layer} INTERFACE)
  add_library(hoilcd::${layer} ALIAS hoilcd_${layer})
  set_target_properties(hoilcd_${layer} PROPERTIES EXPORT_NAME ${layer})
  set_property(GLOBAL APPEND PROPERTY HOILCD_SUBSYSTEMS hoilcd_${layer})
endfunction()
