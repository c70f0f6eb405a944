# Run at build time (not configure time), so the commit a binary names is the one it was built
# from: writes OUTPUT from TEMPLATE, touching it only when its text changes.
# -D SOURCE_DIR, TEMPLATE, OUTPUT, VERSION, COMPILER, FLAGS, BUILD_TYPE
find_package(Git QUIET)
set(MPMSHOCK_COMMIT "unknown (not built from a git checkout)")
if(GIT_FOUND AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" describe --always --dirty --abbrev=40
                  OUTPUT_VARIABLE commit RESULT_VARIABLE status ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(status EQUAL 0 AND NOT commit STREQUAL "")
    set(MPMSHOCK_COMMIT "${commit}")
  endif()
endif()
set(MPMSHOCK_VERSION "${VERSION}")
set(MPMSHOCK_COMPILER "${COMPILER}")
string(STRIP "${FLAGS}" MPMSHOCK_FLAGS)
string(REGEX REPLACE "  +" " " MPMSHOCK_FLAGS "${MPMSHOCK_FLAGS}")
set(MPMSHOCK_BUILD_TYPE "${BUILD_TYPE}")
configure_file("${TEMPLATE}" "${OUTPUT}" @ONLY)
