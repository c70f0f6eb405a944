# cmake --install BUILD --prefix P:
#   P/bin/mpmshock, P/bin/mpmshock-plot, P/bin/mpmshock-converge
#   P/lib/mpmshock/python/mpmshock_post         the post-processing package (PYTHONPATH for notebooks)
#   P/include/mpmshock, P/lib/libmpmshock_core.a and P/lib/cmake/mpmshock (find_package(mpmshock),
#                                                then target_link_libraries(app PRIVATE mpmshock::core))
#   P/share/mpmshock/configs, P/share/doc/mpmshock, P/share/man/man1/mpmshock.1
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(MPMSHOCK_PYTHON_DIR lib/mpmshock/python)  # relative to the prefix; the commands find it from bin/
set(MPMSHOCK_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/mpmshock)

install(TARGETS mpmshock RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS mpmshock_core EXPORT mpmshockTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/mpmshock DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_BINARY_DIR}/include/mpmshock/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/mpmshock)
install(EXPORT mpmshockTargets NAMESPACE mpmshock:: DESTINATION ${MPMSHOCK_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/mpmshockConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/mpmshockConfig.cmake INSTALL_DESTINATION ${MPMSHOCK_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mpmshockConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/mpmshockConfig.cmake ${PROJECT_BINARY_DIR}/mpmshockConfigVersion.cmake
        DESTINATION ${MPMSHOCK_CMAKE_DIR})

# The Python package and its two commands, which put the package beside them on their path.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scripts/mpmshock_post DESTINATION ${MPMSHOCK_PYTHON_DIR}
        PATTERN __pycache__ EXCLUDE PATTERN "*.pyc" EXCLUDE)
foreach(command plot:mpmshock_post.cli converge:mpmshock_post.converge)
  string(REPLACE ":" ";" parts ${command})
  list(GET parts 0 MPMSHOCK_COMMAND)
  list(GET parts 1 MPMSHOCK_MODULE)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/python_command.in
                 ${PROJECT_BINARY_DIR}/installed/mpmshock-${MPMSHOCK_COMMAND} @ONLY)
  install(PROGRAMS ${PROJECT_BINARY_DIR}/installed/mpmshock-${MPMSHOCK_COMMAND} DESTINATION ${CMAKE_INSTALL_BINDIR})
endforeach()

install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mpmshock/configs)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CHANGELOG.md
              ${PROJECT_SOURCE_DIR}/CITATION.cff DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs PATTERN "*.1" EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/docs/mpmshock.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
