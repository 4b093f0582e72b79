# Target `docs`: the API reference of wefm.h (docs/Doxyfile) in <build>/docs/html when Doxygen is found
# (Debian package doxygen; optional, nothing else needs it). Without Doxygen the target says so and fails.
find_program(WEFM_DOXYGEN doxygen)
if(WEFM_DOXYGEN)
  add_custom_target(docs
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/docs
    COMMAND ${CMAKE_COMMAND} -E env WEFM_DOCS_OUTPUT=${CMAKE_BINARY_DIR}/docs WEFM_DOCS_VERSION=${PROJECT_VERSION}
            WEFM_DOCS_WARNINGS=${CMAKE_BINARY_DIR}/docs/warnings.txt ${WEFM_DOXYGEN} Doxyfile
    COMMAND ${CMAKE_COMMAND} -E echo "API reference: ${CMAKE_BINARY_DIR}/docs/html/index.html"
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/docs
    COMMENT "Building the API reference with Doxygen" VERBATIM)
else()
  add_custom_target(docs
    COMMAND ${CMAKE_COMMAND} -E echo "Doxygen not found: install it (Debian: apt-get install doxygen) and re-run cmake"
    COMMAND ${CMAKE_COMMAND} -E false
    VERBATIM)
endif()
