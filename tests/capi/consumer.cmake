# Driven by ctest (tests/capi/CMakeLists.txt), one step per MODE:
#   install       fresh `cmake --install` of the build tree into PREFIX, then check what is there
#   find_package  configure, build and run tests/capi/consumer against PREFIX with find_package(wefm)
#   pkg-config    compile and run the same program with the flags `pkg-config wefm` gives
# Inputs: MODE PREFIX BUILD_DIR SOURCE_DIR WORK_DIR C_COMPILER LIBDIR INCLUDEDIR VERSION SOVERSION, and FLAGS
# (compile and link flags the library's build needs in its consumers: the sanitizers of a sanitizer build)
cmake_minimum_required(VERSION 3.20)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${cmd}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

if(MODE STREQUAL "install")
  file(REMOVE_RECURSE ${PREFIX})
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
  foreach(f ${INCLUDEDIR}/wefm/wefm.h
            ${LIBDIR}/libwefm.so ${LIBDIR}/libwefm.so.${SOVERSION} ${LIBDIR}/libwefm.so.${VERSION}
            ${LIBDIR}/cmake/wefm/wefmConfig.cmake ${LIBDIR}/cmake/wefm/wefmConfigVersion.cmake
            ${LIBDIR}/cmake/wefm/wefmTargets.cmake ${LIBDIR}/pkgconfig/wefm.pc)
    if(NOT EXISTS ${PREFIX}/${f})
      message(FATAL_ERROR "not installed: ${PREFIX}/${f}")
    endif()
  endforeach()
  # The development link and the SONAME link must be links to the real file, as ldconfig expects.
  foreach(link libwefm.so libwefm.so.${SOVERSION})
    if(NOT IS_SYMLINK ${PREFIX}/${LIBDIR}/${link})
      message(FATAL_ERROR "${LIBDIR}/${link} is not a symbolic link")
    endif()
  endforeach()
elseif(MODE STREQUAL "find_package")
  file(REMOVE_RECURSE ${WORK_DIR})
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -DCMAKE_C_COMPILER=${C_COMPILER}
      -DCMAKE_PREFIX_PATH=${PREFIX} -DWEFM_EXPECTED_PREFIX=${PREFIX} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
      "-DCMAKE_C_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}")
  run(${CMAKE_COMMAND} --build ${WORK_DIR})
  run(${WORK_DIR}/consumer)
elseif(MODE STREQUAL "pkg-config")
  find_program(PKG_CONFIG NAMES pkg-config pkgconf REQUIRED)
  file(REMOVE_RECURSE ${WORK_DIR})
  file(MAKE_DIRECTORY ${WORK_DIR})
  # Only the test prefix: a wefm.pc elsewhere on the machine must not be picked up.
  set(ENV{PKG_CONFIG_LIBDIR} ${PREFIX}/${LIBDIR}/pkgconfig)
  unset(ENV{PKG_CONFIG_PATH})
  run(${PKG_CONFIG} --modversion wefm)
  string(STRIP "${run_output}" v)
  if(NOT v STREQUAL VERSION)
    message(FATAL_ERROR "pkg-config says version '${v}', expected ${VERSION}")
  endif()
  run(${PKG_CONFIG} --cflags wefm)
  separate_arguments(cflags UNIX_COMMAND "${run_output}")
  run(${PKG_CONFIG} --libs wefm)
  separate_arguments(libs UNIX_COMMAND "${run_output}")
  run(${PKG_CONFIG} --variable=libdir wefm)
  string(STRIP "${run_output}" libdir)
  file(REAL_PATH ${libdir} libdir)
  file(REAL_PATH ${PREFIX}/${LIBDIR} expected_libdir)
  if(NOT libdir STREQUAL expected_libdir)
    message(FATAL_ERROR "pkg-config libdir ${libdir} is not the installed ${expected_libdir}")
  endif()
  separate_arguments(flags UNIX_COMMAND "${FLAGS}")
  run(${C_COMPILER} -std=c99 -Wall -Wextra -pedantic -Werror ${flags} ${cflags} ${SOURCE_DIR}/consumer.c ${libs}
      -Wl,-rpath,${libdir} -o ${WORK_DIR}/consumer)
  run(${WORK_DIR}/consumer)
else()
  message(FATAL_ERROR "unknown MODE '${MODE}'")
endif()
