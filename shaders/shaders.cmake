# Every shader file, relative to shaders/. Embedded into vds::vds at build time
# and installed for users (share/vds/shaders). Keep the list explicit.
set(VDS_SHADER_FILES
  vds/vpt.glsl
  vds/bake_common.glsl
  vds/bake.vert
  vds/peel.frag
  vds/lists.frag
  vds/lists_sort.comp
  vds/classify.comp
  samples/clip.vert
  samples/clip.frag
)
