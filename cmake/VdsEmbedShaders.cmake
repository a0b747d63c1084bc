# vds_embed_shaders(TARGET NAMESPACE SYMBOL [SHADER_DIR DIR] FILES...): compiles
# the named files, paths relative to DIR (default: the calling project's
# shaders/ folder), into TARGET as a table `const vds::ShaderFile SYMBOL[]` with
# `const std::size_t SYMBOLCount`, in C++ namespace NAMESPACE. The library
# or program that owns the table hands it to vds::registerShaders
# (<vds/gl/shader.h>) before building a program from it, so TARGET links
# vds::gl. Each layer of vds embeds its own shaders; installed with the package
# config, so a program that finds vds embeds its own the same way.
set_property(GLOBAL PROPERTY VDS_EMBED_SHADERS_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/embed_shaders.cmake)

function(vds_embed_shaders target namespace symbol)
  cmake_parse_arguments(PARSE_ARGV 3 arg "" "SHADER_DIR" "")
  set(files ${arg_UNPARSED_ARGUMENTS})
  set(dir ${arg_SHADER_DIR})
  if(NOT dir)
    set(dir ${PROJECT_SOURCE_DIR}/shaders)
  endif()
  get_filename_component(dir ${dir} ABSOLUTE)
  get_property(script GLOBAL PROPERTY VDS_EMBED_SHADERS_SCRIPT)
  set(abs "")
  foreach(f IN LISTS files)
    list(APPEND abs ${dir}/${f})
  endforeach()
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${symbol}.cpp)
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${dir} "-DFILES=${files}" -DNAMESPACE=${namespace}
            -DSYMBOL=${symbol} -DOUTPUT=${out} -P ${script}
    DEPENDS ${abs} ${script}
    COMMENT "Embedding shaders into ${target}"
    VERBATIM)
  target_sources(${target} PRIVATE ${out})
endfunction()

# Installs vds's own shader files under share/vds/shaders, keeping their folders.
function(vds_install_shaders)
  foreach(f IN LISTS ARGN)
    get_filename_component(dir ${f} DIRECTORY)
    install(FILES ${PROJECT_SOURCE_DIR}/shaders/${f} DESTINATION ${CMAKE_INSTALL_DATADIR}/vds/shaders/${dir})
  endforeach()
endfunction()
