# Run by cmake --install (component python), after python/CMakeLists.txt's
# install(CODE) has set vds_python_install_dir, vds_python_executable,
# vds_python_site_dir_script and vds_python_files. CMAKE_INSTALL_PREFIX is the
# prefix of this install (--prefix), so the folder is chosen for it.
if(vds_python_install_dir STREQUAL "")
  execute_process(COMMAND "${vds_python_executable}" "${vds_python_site_dir_script}" "${CMAKE_INSTALL_PREFIX}"
                  OUTPUT_VARIABLE vds_python_install_dir OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE vds_python_result)
  if(NOT vds_python_result EQUAL 0 OR vds_python_install_dir STREQUAL "")
    message(FATAL_ERROR "vds: ${vds_python_executable} could not name a site folder under ${CMAKE_INSTALL_PREFIX}: "
                        "set -DVDS_PYTHON_INSTALL_DIR=FOLDER")
  endif()
endif()
if(IS_ABSOLUTE "${vds_python_install_dir}")
  set(vds_python_destination "${vds_python_install_dir}/vds")
else()
  set(vds_python_destination "${CMAKE_INSTALL_PREFIX}/${vds_python_install_dir}/vds")
endif()
# file(INSTALL) prefixes DESTDIR and records the files in install_manifest.txt.
list(GET vds_python_files 0 vds_python_module)
list(REMOVE_AT vds_python_files 0)
file(INSTALL DESTINATION "${vds_python_destination}" TYPE MODULE FILES "${vds_python_module}")
file(INSTALL DESTINATION "${vds_python_destination}" TYPE FILE FILES ${vds_python_files})
