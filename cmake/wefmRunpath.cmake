# Run-time search paths (RUNPATH) of everything we build, stage and install.
#
# An empty RUNPATH entry (a leading, trailing or doubled ':') means the current working directory to
# the dynamic loader, so a libcholmod.so.3 planted there would be loaded by `import wefm` or the CLI.
# CMake produces such entries itself whenever a target is installed with an INSTALL_RPATH that differs
# from its build RPATH: it links the build tree's copy with a trailing ':' and pads it with more ':'
# up to the install RPATH's length, so that the install step can edit the string in place. Hence:
#   - no global install RPATH: libwefm's dependencies are system libraries; its own RUNPATH is
#     $ORIGIN, linked once for the build tree and the install (capi/CMakeLists.txt), so that a copy
#     shipped with its dependencies beside it finds them; a target without one is linked with its
#     exact build RPATH;
#   - the build RPATH is $ORIGIN-relative (the build tree can move; no absolute build paths);
#   - installed programs that load libwefm get wefm_runpath(): one RUNPATH, linked once, valid in
#     both places (BUILD_WITH_INSTALL_RPATH), so the install step never edits it.
# tests/runpath checks every ELF file we build, stage and install with readelf.
set(CMAKE_BUILD_RPATH_USE_ORIGIN ON)

# A -DCMAKE_INSTALL_RPATH=... given by the user is added to the installed programs' RUNPATH (an
# absolute dependency prefix, say) instead of being applied to every target.
set(WEFM_EXTRA_INSTALL_RPATH "${CMAKE_INSTALL_RPATH}")
set(CMAKE_INSTALL_RPATH "")

# wefm_runpath(<target> <install dir>): <target> (an executable or module linking wefm::wefm) is
# installed to <install dir> (relative to the prefix, or absolute). Its RUNPATH names, relative to
# $ORIGIN, the installed library directory and the build tree's libwefm directory.
function(wefm_runpath target install_dir)
  if(IS_ABSOLUTE "${install_dir}")
    set(installed "${install_dir}")
  else()
    set(installed "${CMAKE_INSTALL_PREFIX}/${install_dir}")
  endif()
  file(RELATIVE_PATH to_libdir "${installed}" "${CMAKE_INSTALL_FULL_LIBDIR}")

  get_target_property(type ${target} TYPE)
  if(type STREQUAL "EXECUTABLE")
    get_target_property(built ${target} RUNTIME_OUTPUT_DIRECTORY)
  else()
    get_target_property(built ${target} LIBRARY_OUTPUT_DIRECTORY)
  endif()
  if(NOT built)
    get_target_property(built ${target} BINARY_DIR)
  endif()
  get_target_property(lib_built wefm LIBRARY_OUTPUT_DIRECTORY)
  if(NOT lib_built)
    get_target_property(lib_built wefm BINARY_DIR)
  endif()
  file(RELATIVE_PATH to_build_lib "${built}" "${lib_built}")

  set(runpath "")
  foreach(rel IN ITEMS "${to_libdir}" "${to_build_lib}")
    string(REGEX REPLACE "/+$" "" rel "${rel}")
    if(rel STREQUAL "")
      list(APPEND runpath "$ORIGIN")
    else()
      list(APPEND runpath "$ORIGIN/${rel}")
    endif()
  endforeach()
  list(APPEND runpath ${WEFM_EXTRA_INSTALL_RPATH})
  list(REMOVE_DUPLICATES runpath)
  set_target_properties(${target} PROPERTIES BUILD_WITH_INSTALL_RPATH ON INSTALL_RPATH "${runpath}")
endfunction()
