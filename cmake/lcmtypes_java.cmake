# Java classes of lcmtypes/*.lcm and lcmtypes/drake/*.lcm in one jar, for lcm-spy: with the jar on its
# class path (`make spy`, scripts/spy.sh) lcm-spy finds each message's class
# by its fingerprint and decodes every channel. Built from lcm-gen --java and
# compiled against Debian's lcm.jar (liblcm-java); skipped, with a note, when
# a JDK or lcm.jar is missing, since nothing else in the build needs Java.
# Output: ${LCMTYPES_JAR} (target contactsim_lcmtypes_jar).
find_package(Java 1.8 COMPONENTS Development)
find_file(LCM_JAR lcm.jar PATHS /usr/share/java /usr/local/share/java NO_DEFAULT_PATH)
if(NOT Java_JAVAC_EXECUTABLE OR NOT Java_JAR_EXECUTABLE OR NOT LCM_JAR)
  message(STATUS "lcmtypes jar for lcm-spy: skipped (needs a JDK and lcm.jar: make deps)")
  return()
endif()

set(LCMTYPES_JAVA_DIR ${CMAKE_BINARY_DIR}/lcmtypes/java)
set(LCMTYPES_JAR ${CMAKE_BINARY_DIR}/lcmtypes/contactsim_lcmtypes.jar)
set(LCM_JAVA_SOURCES)
foreach(f ${LCM_FILES})
  get_filename_component(name ${f} NAME_WE)
  list(APPEND LCM_JAVA_SOURCES ${LCMTYPES_JAVA_DIR}/src/contactsim/${name}.java)
endforeach()
foreach(f ${DRAKE_LCM_FILES})
  get_filename_component(name ${f} NAME_WE)
  list(APPEND LCM_JAVA_SOURCES ${LCMTYPES_JAVA_DIR}/src/drake/${name}.java)
endforeach()
# javac --release 8: the jar loads in any JVM lcm-spy may run on
add_custom_command(
  OUTPUT ${LCMTYPES_JAR}
  COMMAND ${CMAKE_COMMAND} -E rm -rf ${LCMTYPES_JAVA_DIR}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${LCMTYPES_JAVA_DIR}/src ${LCMTYPES_JAVA_DIR}/classes
  COMMAND ${LCM_GEN} --java --jpath ${LCMTYPES_JAVA_DIR}/src ${LCM_FILES} ${DRAKE_LCM_FILES}
  COMMAND ${Java_JAVAC_EXECUTABLE} --release 8 -nowarn -cp ${LCM_JAR} -d ${LCMTYPES_JAVA_DIR}/classes ${LCM_JAVA_SOURCES}
  COMMAND ${Java_JAR_EXECUTABLE} cf ${LCMTYPES_JAR} -C ${LCMTYPES_JAVA_DIR}/classes .
  DEPENDS ${LCM_FILES} ${DRAKE_LCM_FILES}
  COMMENT "lcm-gen --java, javac: contactsim_lcmtypes.jar for lcm-spy")
add_custom_target(contactsim_lcmtypes_jar ALL DEPENDS ${LCMTYPES_JAR})
