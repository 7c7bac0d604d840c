# ctest: installs the "client" component into a fresh prefix, then configures
# and builds tests/install/consumer against it, by find_package and by
# pkg-config, and runs both programs. Bounded: one small file, twice.
#   cmake -DBUILD=... -DSOURCE=... -DWORK=... -DCXX=... -DFLAGS=... -P consumer_test.cmake
file(REMOVE_RECURSE ${WORK})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN}\n${out}\n${err}")
  endif()
  set(OUT "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD} --component client --prefix ${WORK}/prefix)
# the sanitizer build's library needs its runtime at link time (FLAGS)
set(pc ${WORK}/prefix/lib/pkgconfig:${WORK}/prefix/lib/x86_64-linux-gnu/pkgconfig)
run(${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc} ${CMAKE_COMMAND} -S ${SOURCE}/tests/install/consumer
    -B ${WORK}/build -DCMAKE_CXX_COMPILER=${CXX} "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}"
    -DCMAKE_PREFIX_PATH=${WORK}/prefix)
run(${CMAKE_COMMAND} --build ${WORK}/build)
foreach(program consumer_cmake consumer_pkgconfig)
  run(${WORK}/build/${program})
  if(NOT OUT MATCHES "mode lockstep, STATUS of [0-9]+ bytes")
    message(FATAL_ERROR "${program}: ${OUT}")
  endif()
endforeach()
