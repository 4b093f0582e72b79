# The core's folder rule (core/CMakeLists.txt): a file in core/src/F/ or core/include/wefm/core/F/
# includes core headers only from F itself and the folders F depends on, never the C API, and every
# core file lies in a declared folder. Any folder may include common/ (wefm/common/), which lies
# below the core and includes nothing of the project's (checked too, in <core>/../common).
#
#   cmake -DCORE_DIR=<core> -DLAYERS="sys:|linalg:sys|..." -P check_layers.cmake
#   cmake -DSELF_TEST=<scratch folder> -P check_layers.cmake
# The second form runs the check on a small tree with known faults and fails unless it reports
# exactly those: the check itself can fail.

cmake_minimum_required(VERSION 3.25)

# Sets ${out} to the list of broken rules ("path: message") under core_dir, by the rules in
# `layers` ("name:dep,dep" entries).
function(check_core_layers core_dir layers out)
  set(errors "")
  set(names "")
  foreach(rule IN LISTS layers)
    string(REGEX REPLACE ":.*" "" name "${rule}")
    string(REGEX REPLACE "^[^:]*:" "" deps "${rule}")
    string(REPLACE "," ";" deps "${deps}")
    list(APPEND names ${name})
    set(allowed_${name} ${name} ${deps})
  endforeach()

  file(GLOB_RECURSE files RELATIVE ${core_dir} ${core_dir}/src/* ${core_dir}/include/*)
  foreach(rel IN LISTS files)
    if(NOT rel MATCHES "\\.(c|cc|cpp|h|hpp|inc)$")
      continue()
    endif()
    string(REGEX MATCH "^(src|include/wefm/core)/([^/]+)/.+" in_folder "${rel}")
    if(in_folder)
      set(folder ${CMAKE_MATCH_2})
    else()
      list(APPEND errors "${rel}: not inside a folder of the core")
      continue()
    endif()
    if(NOT folder IN_LIST names)
      list(APPEND errors "${rel}: folder '${folder}' is not declared in core/CMakeLists.txt")
      continue()
    endif()
    file(STRINGS ${core_dir}/${rel} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]wefm/")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[\"<]([^\">]*)[\">].*" "\\1" header "${line}")
      if(header MATCHES "^wefm/common/")
        continue()
      elseif(NOT header MATCHES "^wefm/core/")
        list(APPEND errors "${rel}: includes ${header}, but the core never includes the C API")
      elseif(header MATCHES "^wefm/core/([^/]+)/")
        if(NOT CMAKE_MATCH_1 IN_LIST allowed_${folder})
          string(JOIN ", " may ${allowed_${folder}})
          list(APPEND errors "${rel}: includes ${header}, but folder ${folder} may include only ${may}")
        endif()
      else()
        list(APPEND errors "${rel}: includes ${header}, which is not inside a folder of the core")
      endif()
    endforeach()
  endforeach()
  set(${out} "${errors}" PARENT_SCOPE)
endfunction()

# Sets ${out} to the includes of the project's headers other than its own under common_dir.
function(check_common common_dir out)
  set(errors "")
  file(GLOB_RECURSE files RELATIVE ${common_dir} ${common_dir}/*.cpp ${common_dir}/*.hpp ${common_dir}/*.h)
  foreach(rel IN LISTS files)
    file(STRINGS ${common_dir}/${rel} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]wefm/")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[\"<]([^\">]*)[\">].*" "\\1" header "${line}")
      if(NOT header MATCHES "^wefm/common/")
        list(APPEND errors "common/${rel}: includes ${header}, but common includes nothing of the project's")
      endif()
    endforeach()
  endforeach()
  set(${out} "${errors}" PARENT_SCOPE)
endfunction()

if(SELF_TEST)
  set(t ${SELF_TEST}/core_layers_fixture)
  file(REMOVE_RECURSE ${t})
  file(WRITE ${t}/include/wefm/core/low/a.hpp "#include \"wefm/core/low/b.hpp\"\n")
  file(WRITE ${t}/include/wefm/core/low/b.hpp "#pragma once\n#include \"wefm/common/replace_file.hpp\"\n")
  file(WRITE ${t}/common/include/wefm/common/x.hpp "#include \"wefm/common/y.hpp\"\n#include \"wefm/core/low/b.hpp\"\n")
  file(WRITE ${t}/src/low/a.cpp "#include \"wefm/core/low/a.hpp\"\n#include \"wefm/core/high/c.hpp\"\n")
  file(WRITE ${t}/src/high/c.cpp "#include \"wefm/core/low/a.hpp\"\n#include <wefm/wefm.h>\n")
  file(WRITE ${t}/src/stray.cpp "\n")
  file(WRITE ${t}/src/other/d.cpp "\n")
  file(WRITE ${t}/src/high/e.cpp "  #  include \"wefm/core/flat.hpp\"\n")
  check_core_layers(${t} "low:;high:low" errors)
  check_common(${t}/common common_errors)
  list(APPEND errors ${common_errors})
  file(REMOVE_RECURSE ${t})
  set(expected
      "common/include/wefm/common/x.hpp: includes wefm/core/low/b.hpp, but common includes nothing of the project's"
      "src/high/c.cpp: includes wefm/wefm.h, but the core never includes the C API"
      "src/high/e.cpp: includes wefm/core/flat.hpp, which is not inside a folder of the core"
      "src/low/a.cpp: includes wefm/core/high/c.hpp, but folder low may include only low"
      "src/other/d.cpp: folder 'other' is not declared in core/CMakeLists.txt"
      "src/stray.cpp: not inside a folder of the core")
  list(SORT errors)
  if(NOT errors STREQUAL expected)
    string(REPLACE ";" "\n  " got "${errors}")
    message(FATAL_ERROR "check_layers self-test: expected the six planted faults, got:\n  ${got}")
  endif()
  message(STATUS "check_layers self-test: the six planted faults found")
  return()
endif()

if(NOT CORE_DIR OR NOT LAYERS)
  message(FATAL_ERROR "usage: cmake -DCORE_DIR=<core> -DLAYERS=\"name:deps|...\" -P check_layers.cmake")
endif()
string(REPLACE "|" ";" layers "${LAYERS}")
check_core_layers(${CORE_DIR} "${layers}" errors)
check_common(${CORE_DIR}/../common common_errors)
list(APPEND errors ${common_errors})
if(errors)
  list(LENGTH errors n)
  string(REPLACE ";" "\n  " text "${errors}")
  message(FATAL_ERROR "${n} include(s) break the core's folder rules (core/CMakeLists.txt):\n  ${text}")
endif()
message(STATUS "core folders: every include keeps the rules ${LAYERS}")
