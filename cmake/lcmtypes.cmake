# Generates C++ and Python code from lcmtypes/*.lcm with lcm-gen at build time.
# C++ headers land in ${LCMTYPES_CPP_DIR}/contactsim/*.hpp (target
# contactsim_lcmtypes), Python modules in ${LCMTYPES_PY_DIR}/contactsim/*.py,
# which the Python client adds to its package path, and wire_check.hpp.
# The protocol's table (lcmtypes/protocol.toml: channels, method names; the
# reply codes are reply_t's) becomes contactsim/protocol.hpp in
# ${PROTOCOL_CPP_DIR} (target contactsim_protocol, no LCM: the engine's Status
# takes its codes from it), and a copy beside the Python modules.
# Drake's arm-driver messages (lcmtypes/drake/*.lcm, package drake, outside the
# protocol table; docs/protocol.md) land beside them in drake/ and are checked alike.
file(GLOB LCM_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/lcmtypes/*.lcm)
file(GLOB DRAKE_LCM_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/lcmtypes/drake/*.lcm)
set(LCMTYPES_CPP_DIR ${CMAKE_BINARY_DIR}/lcmtypes/cpp)
set(LCMTYPES_PY_DIR ${CMAKE_BINARY_DIR}/lcmtypes/python)
set(LCM_OUTPUTS)
foreach(f ${LCM_FILES})
  get_filename_component(name ${f} NAME_WE)
  list(APPEND LCM_OUTPUTS ${LCMTYPES_CPP_DIR}/contactsim/${name}.hpp
                          ${LCMTYPES_PY_DIR}/contactsim/${name}.py)
endforeach()
foreach(f ${DRAKE_LCM_FILES})
  get_filename_component(name ${f} NAME_WE)
  list(APPEND LCM_OUTPUTS ${LCMTYPES_CPP_DIR}/drake/${name}.hpp ${LCMTYPES_PY_DIR}/drake/${name}.py)
endforeach()
add_custom_command(
  OUTPUT ${LCM_OUTPUTS}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${LCMTYPES_CPP_DIR} ${LCMTYPES_PY_DIR}
  COMMAND ${LCM_GEN} --cpp --cpp-hpath ${LCMTYPES_CPP_DIR} --python --ppath ${LCMTYPES_PY_DIR} ${LCM_FILES} ${DRAKE_LCM_FILES}
  DEPENDS ${LCM_FILES} ${DRAKE_LCM_FILES}
  COMMENT "lcm-gen: C++ and Python code for lcmtypes/*.lcm and lcmtypes/drake/*.lcm")
# wire_check.hpp: bounds checks of every type's encoding, run before a
# generated decoder sees bytes from the network (cmake/lcm_wire_check.py).
find_package(Python3 REQUIRED COMPONENTS Interpreter)
set(LCM_WIRE_CHECK ${LCMTYPES_CPP_DIR}/contactsim/wire_check.hpp)
add_custom_command(
  OUTPUT ${LCM_WIRE_CHECK}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${LCMTYPES_CPP_DIR}/contactsim
  COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/cmake/lcm_wire_check.py ${LCM_WIRE_CHECK} ${LCM_FILES} ${DRAKE_LCM_FILES}
  DEPENDS ${LCM_FILES} ${DRAKE_LCM_FILES} ${PROJECT_SOURCE_DIR}/cmake/lcm_wire_check.py ${PROJECT_SOURCE_DIR}/cmake/lcm_schema.py
  COMMENT "lcm_wire_check.py: bounds checks for lcmtypes/*.lcm")
set(PROTOCOL_TABLE ${PROJECT_SOURCE_DIR}/lcmtypes/protocol.toml)
set(PROTOCOL_CPP_DIR ${CMAKE_BINARY_DIR}/lcmtypes/protocol)
set(PROTOCOL_HPP ${PROTOCOL_CPP_DIR}/contactsim/protocol.hpp)
add_custom_command(
  OUTPUT ${PROTOCOL_HPP} ${LCMTYPES_PY_DIR}/contactsim/protocol.toml
  COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/cmake/protocol_gen.py ${PROTOCOL_HPP} ${PROTOCOL_TABLE} ${LCM_FILES}
  COMMAND ${CMAKE_COMMAND} -E copy ${PROTOCOL_TABLE} ${LCMTYPES_PY_DIR}/contactsim/protocol.toml
  DEPENDS ${PROTOCOL_TABLE} ${LCM_FILES} ${PROJECT_SOURCE_DIR}/cmake/protocol_gen.py
          ${PROJECT_SOURCE_DIR}/cmake/lcm_schema.py
  COMMENT "protocol_gen.py: contactsim/protocol.hpp from lcmtypes/protocol.toml")
add_custom_target(contactsim_lcmtypes_gen ALL DEPENDS ${LCM_OUTPUTS} ${LCM_WIRE_CHECK} ${PROTOCOL_HPP})
add_library(contactsim_protocol INTERFACE)
add_dependencies(contactsim_protocol contactsim_lcmtypes_gen)
target_include_directories(contactsim_protocol INTERFACE $<BUILD_INTERFACE:${PROTOCOL_CPP_DIR}>)
add_library(contactsim_lcmtypes INTERFACE)
add_dependencies(contactsim_lcmtypes contactsim_lcmtypes_gen)
target_include_directories(contactsim_lcmtypes INTERFACE $<BUILD_INTERFACE:${LCMTYPES_CPP_DIR}>)
target_link_libraries(contactsim_lcmtypes INTERFACE contactsim_protocol PkgConfig::LCM)
