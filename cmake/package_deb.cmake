# make package (cpack -G DEB): contactsim_<version>_<arch>.deb with the
# programs, the client for C++ projects, the config in /etc/contactsim and a
# systemd unit (packaging/contactsim.service). The journal folder,
# /var/lib/contactsim, belongs to no package, so upgrades keep it
# (docs/packaging.md, "Upgrading").
install(CODE "set(CONTACTSIM_CONFIG_SOURCE \"${PROJECT_SOURCE_DIR}/config/server.pbtxt\")
  set(CONTACTSIM_CONFIG_STAGING \"${CMAKE_BINARY_DIR}/packaging\")
  set(CONTACTSIM_DATADIR \"${CMAKE_INSTALL_DATADIR}\")" COMPONENT runtime)
install(SCRIPT ${PROJECT_SOURCE_DIR}/cmake/install_config.cmake COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/contactsim.service DESTINATION lib/systemd/system COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/docs/packaging.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME contactsim)
set(CPACK_PACKAGE_CONTACT "contactsim maintainers <contactsim@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Rigid-body contact co-simulation server and C++ client over LCM")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# install with prefix /usr into DESTDIR, so that the config script sees the
# real prefix and writes /etc/contactsim into the package, not onto this machine
set(CPACK_SET_DESTDIR ON)
set(CPACK_INSTALL_PREFIX /usr)  # the prefix CPACK_SET_DESTDIR installs with
set(CPACK_STRIP_FILES ON)  # with its debug info the RelWithDebInfo server is 178 MB, stripped 2.1 MB
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)  # the libraries' Debian packages, from the binaries
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/postinst ${PROJECT_SOURCE_DIR}/packaging/prerm
    ${PROJECT_SOURCE_DIR}/packaging/postrm
    ${PROJECT_SOURCE_DIR}/packaging/conffiles)  # the config survives upgrades as edited
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
