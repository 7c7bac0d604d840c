# Install-time script (install(SCRIPT), cmake/package_deb.cmake): the
# server's config, written when the prefix is known, which it is not at
# configure time (cpack installs into /usr, `cmake --install --prefix P`
# anywhere). The package's config goes to /etc/contactsim, where
# packaging/conffiles names it; any other prefix gets P/etc/contactsim.
# config/server.pbtxt names its scene relative to itself (scenes/...),
# which holds in the repository; installed, the scenes are in
# P/share/contactsim/scenes, so the copy names them by absolute path
# (docs/packaging.md, "Debian package").
# In: CONTACTSIM_CONFIG_SOURCE, CONTACTSIM_CONFIG_STAGING, CONTACTSIM_DATADIR.
if(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  set(etc /etc/contactsim)
else()
  set(etc ${CMAKE_INSTALL_PREFIX}/etc/contactsim)
endif()
file(READ ${CONTACTSIM_CONFIG_SOURCE} text)
string(REGEX REPLACE "(^|\n)scene: \"([^\"/][^\"]*)\"" "\\1scene: \"${CMAKE_INSTALL_PREFIX}/${CONTACTSIM_DATADIR}/contactsim/\\2\""
       text "${text}")
file(WRITE ${CONTACTSIM_CONFIG_STAGING}/server.pbtxt "${text}")
file(INSTALL ${CONTACTSIM_CONFIG_STAGING}/server.pbtxt DESTINATION ${etc})
