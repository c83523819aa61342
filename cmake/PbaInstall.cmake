# `cmake --install` puts the core's headers, library and a CMake package in place, so another
# project can `find_package(pba)` and link `pba::core`, and, where the build has it, the scene
# loader `pba::scene` with its header pba/scene/scene.hpp (installed only with its library).
# Of pba/detail/ only what an installed header includes is installed (rotation.hpp's rigid step,
# a template a user instantiates); the rest are what pba's own libraries and tests inline.
include(CMakePackageConfigHelpers)
install(DIRECTORY include/pba DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} PATTERN scene EXCLUDE PATTERN detail EXCLUDE)
install(FILES include/pba/detail/rigid_step.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pba/detail)
set(PBA_INSTALLED_TARGETS pba_core)
set(PBA_WITH_SCENE OFF)
if(TARGET pba_scene)
  install(DIRECTORY include/pba/scene DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/pba)
  list(APPEND PBA_INSTALLED_TARGETS pba_scene)
  set(PBA_WITH_SCENE ON)
endif()
install(TARGETS ${PBA_INSTALLED_TARGETS} EXPORT pbaTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT pbaTargets NAMESPACE pba:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pba)
# A static pba_core carries its private dependencies into the consumer's link line: the config
# file must find Qhull for it then (a shared one has linked it already).
get_target_property(_pba_core_type pba_core TYPE)
if(_pba_core_type STREQUAL "STATIC_LIBRARY")
  set(PBA_CORE_STATIC TRUE)
else()
  set(PBA_CORE_STATIC FALSE)
endif()
configure_package_config_file(cmake/pbaConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/pbaConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pba)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/pbaConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/pbaConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/pbaConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pba)
if(TARGET pba)
  install(TARGETS pba RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
