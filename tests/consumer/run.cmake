# Installs horizon from BUILD into WORK/prefix, then configures, builds and runs the consumer.
file(REMOVE_RECURSE ${WORK})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}")
  endif()
endfunction()
step(${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
# Through the environment: a ';' list in a -D argument would be split into several arguments.
string(REPLACE ";" ":" search_path "${WORK}/prefix;${PREFIXES}")
set(ENV{CMAKE_PREFIX_PATH} "${search_path}")
step(${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/build -DEXPECTED_VERSION=${VERSION})
step(${CMAKE_COMMAND} --build ${WORK}/build)
step(${WORK}/build/consumer)

# C, compiled by cc alone: once with the flags written out, once with pkg-config's.
file(GLOB library_dirs LIST_DIRECTORIES true ${WORK}/prefix/lib*)
list(GET library_dirs 0 libdir)
step(cc -std=c99 -Wall -Werror -pedantic ${SOURCE}/c_consumer.c -I${WORK}/prefix/include -L${libdir} -lhorizon
     -Wl,-rpath,${libdir} -o ${WORK}/c_consumer)
step(${WORK}/c_consumer)
execute_process(COMMAND ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${libdir}/pkgconfig pkg-config --cflags --libs horizon
                OUTPUT_VARIABLE pkg_flags OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs horizon failed")
endif()
separate_arguments(pkg_flags UNIX_COMMAND "${pkg_flags}")
step(cc -std=c99 ${SOURCE}/c_consumer.c ${pkg_flags} -Wl,-rpath,${libdir} -o ${WORK}/c_consumer_pkg_config)
step(${WORK}/c_consumer_pkg_config)
