# cmake --install: the C++ client for other projects (component "client":
# the library, its headers and the generated LCM headers, a CMake package
# config for find_package(contactsim CONFIG) with target contactsim::client,
# and contactsim.pc) and the programs (component "runtime": contactsim-server,
# contactsim-ctl, the benchmark tools, the config and scenes, the systemd
# unit). docs/packaging.md; tests/install checks the client part.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(CONTACTSIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/contactsim)
set_target_properties(contactsim_client PROPERTIES EXPORT_NAME client)
set_target_properties(contactsim_signature PROPERTIES EXPORT_NAME signature)
set_target_properties(contactsim_lcmtypes PROPERTIES EXPORT_NAME lcmtypes)
set_target_properties(contactsim_protocol PROPERTIES EXPORT_NAME protocol)
install(TARGETS contactsim_client contactsim_signature contactsim_lcmtypes contactsim_protocol
        EXPORT contactsimTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT client
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/clients/cpp/include/contactsim ${PROJECT_SOURCE_DIR}/protocol/include/contactsim
                  ${LCMTYPES_CPP_DIR}/contactsim ${LCMTYPES_CPP_DIR}/drake ${PROTOCOL_CPP_DIR}/contactsim
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT client)
install(EXPORT contactsimTargets NAMESPACE contactsim:: DESTINATION ${CONTACTSIM_CMAKE_DIR} COMPONENT client)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/contactsimConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/contactsimConfig.cmake INSTALL_DESTINATION ${CONTACTSIM_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/contactsimConfigVersion.cmake COMPATIBILITY SameMinorVersion)
# relocatable: the prefix is found from the .pc file's own folder
file(RELATIVE_PATH CONTACTSIM_PC_TO_PREFIX /p/${CMAKE_INSTALL_LIBDIR}/pkgconfig /p)
configure_file(${PROJECT_SOURCE_DIR}/cmake/contactsim.pc.in ${CMAKE_BINARY_DIR}/contactsim.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/contactsimConfig.cmake ${CMAKE_BINARY_DIR}/contactsimConfigVersion.cmake
        DESTINATION ${CONTACTSIM_CMAKE_DIR} COMPONENT client)
install(FILES ${CMAKE_BINARY_DIR}/contactsim.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT client)

# the programs, the default config and scenes, and the service's unit;
# target contactsim_install_targets builds what installs (and cpack) need
# and nothing else (no tests): docker/Dockerfile's build stage
add_custom_target(contactsim_install_targets)
add_dependencies(contactsim_install_targets contactsim_client contactsim_signature contactsim_lcmtypes contactsim_protocol)
foreach(program contactsim-server contactsim-ctl contactsim-bench contactsim-bench-lockstep contactsim-model-info)
  if(TARGET ${program})  # a build may leave one out (service/CMakeLists.txt)
    install(TARGETS ${program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
    add_dependencies(contactsim_install_targets ${program})
  endif()
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${CMAKE_INSTALL_DATADIR}/contactsim COMPONENT runtime)
if(TARGET contactsim_lcmtypes_jar)
  install(FILES ${LCMTYPES_JAR} DESTINATION ${CMAKE_INSTALL_DATADIR}/java COMPONENT runtime)
  add_dependencies(contactsim_install_targets contactsim_lcmtypes_jar)
endif()
include(${PROJECT_SOURCE_DIR}/cmake/package_deb.cmake)
