# make package (cpack -G DEB): contactsim_<version>_<arch>.deb with the
# programs, the client for C++ projects, the config in /etc/contactsim and a
# systemd unit (packaging/contactsim.service). The journal folder,
# /var/lib/contactsim, belongs to no package, so upgrades keep it
# (docs/packaging.md, "Upgrading").
if(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  set(CONTACTSIM_ETC /etc)  # an absolute /etc for the package, beside /usr
else()
  set(CONTACTSIM_ETC ${CMAKE_INSTALL_SYSCONFDIR})
endif()
install(FILES ${PROJECT_SOURCE_DIR}/config/server.pbtxt DESTINATION ${CONTACTSIM_ETC}/contactsim COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/contactsim.service DESTINATION lib/systemd/system COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/docs/packaging.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME contactsim)
set(CPACK_PACKAGE_CONTACT "contactsim maintainers <contactsim@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Rigid-body contact co-simulation server and C++ client over LCM")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)  # the libraries' Debian packages, from the binaries
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/postinst ${PROJECT_SOURCE_DIR}/packaging/prerm
    ${PROJECT_SOURCE_DIR}/packaging/conffiles)  # the config survives upgrades as edited
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
