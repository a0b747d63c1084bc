# vds_embed_shaders(TARGET NAMESPACE SYMBOL FILES...): compiles the named files
# under shaders/ into TARGET as a table `const vds::ShaderFile SYMBOL[]` with
# `const std::size_t SYMBOLCount`, in C++ namespace NAMESPACE. The library
# that owns the table hands it to vds::registerShaders (<vds/gl/shader.h>) before
# building a program from it. Each layer embeds its own shaders.
function(vds_embed_shaders target namespace symbol)
  set(files ${ARGN})
  set(abs "")
  foreach(f IN LISTS files)
    list(APPEND abs ${PROJECT_SOURCE_DIR}/shaders/${f})
  endforeach()
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${symbol}.cpp)
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${PROJECT_SOURCE_DIR}/shaders "-DFILES=${files}" -DNAMESPACE=${namespace}
            -DSYMBOL=${symbol} -DOUTPUT=${out} -P ${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake
    DEPENDS ${abs} ${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake
    COMMENT "Embedding shaders into ${target}"
    VERBATIM)
  target_sources(${target} PRIVATE ${out})
endfunction()

# Installs shader files under share/vds/shaders, keeping their folders.
function(vds_install_shaders)
  foreach(f IN LISTS ARGN)
    get_filename_component(dir ${f} DIRECTORY)
    install(FILES ${PROJECT_SOURCE_DIR}/shaders/${f} DESTINATION ${CMAKE_INSTALL_DATADIR}/vds/shaders/${dir})
  endforeach()
endfunction()
