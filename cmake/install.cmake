# Install rules (issue 12): `cmake --install build --prefix P` gives a relocatable prefix with
# bin/hoilcd, the static libraries and headers, lib/cmake/hoilcd (targets hoilcd::core, ::sim,
# ::bench and one per subsystem) and share/hoilcd/{scenes,assets}. Programs find the data at run time relative to their
# own binary, or through HOILCD_DATA_DIR (sim/assets/data_dir.h): no source path is compiled in.
include(CMakePackageConfigHelpers)

# The build tree's share/hoilcd links to the sources, so uninstalled programs find their data
# the way installed ones do (build/bin/hoilcd -> build/share/hoilcd).
file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/share/hoilcd)
foreach(folder scenes assets)
  file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${PROJECT_BINARY_DIR}/share/hoilcd/${folder} SYMBOLIC)
endforeach()

set(HOILCD_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/hoilcd)
# Every subsystem library (hoilcd::core_util, ...) and the layers' aggregates (hoilcd::core, ::sim,
# ::bench); cmake/subsystem.cmake installs each subsystem's headers.
get_property(HOILCD_EXPORTED_TARGETS GLOBAL PROPERTY HOILCD_SUBSYSTEMS)
install(TARGETS ${HOILCD_EXPORTED_TARGETS} EXPORT hoilcdTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS hoilcd RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes ${PROJECT_SOURCE_DIR}/assets
        DESTINATION ${CMAKE_INSTALL_DATADIR}/hoilcd)

install(EXPORT hoilcdTargets NAMESPACE hoilcd:: DESTINATION ${HOILCD_CMAKE_INSTALL_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/hoilcdConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/hoilcdConfig.cmake
                              INSTALL_DESTINATION ${HOILCD_CMAKE_INSTALL_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/hoilcdConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/hoilcdConfig.cmake ${PROJECT_BINARY_DIR}/hoilcdConfigVersion.cmake
        DESTINATION ${HOILCD_CMAKE_INSTALL_DIR})
