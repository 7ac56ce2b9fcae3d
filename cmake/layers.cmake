# The library's layers (docs/architecture.md): one object library penumbra_<layer> per folder
# of src/, compiled with an include path that reaches only its own folder, the folders of the layers
# below it and their public headers. An #include of anything else finds no file and fails to compile;
# so does any Vulkan header outside the gpu layer. penumbra_lib archives every layer's objects into
# the one installed libpenumbra.
#
# The include roots live in the build tree, <build>/layers/<name>/, each holding a symbolic link
# <name> -> src/<name> and penumbra/<header> -> include/penumbra/<header> for the layer's public
# headers, so that the sources keep their `#include "gpu/device.h"` and `<penumbra/scene.h>` form.

set(PENUMBRA_LAYER_ROOT ${CMAKE_BINARY_DIR}/layers)
file(REMOVE_RECURSE ${PENUMBRA_LAYER_ROOT})  # links, not what they point to; stale ones would let an include through

# First in the include path of every layer but gpu: Vulkan's headers, each an #error.
set(PENUMBRA_NO_VULKAN_DIR ${PENUMBRA_LAYER_ROOT}/no-vulkan)
foreach(header vulkan.h vulkan_core.h vulkan.hpp vk_platform.h)
  file(WRITE ${PENUMBRA_NO_VULKAN_DIR}/vulkan/${header}
       "#error \"Vulkan is used only inside the gpu layer (src/gpu/*.cpp): docs/architecture.md\"\n")
endforeach()

# What every layer compiles with; the same definitions are public on penumbra_lib.
add_library(penumbra_layer_flags INTERFACE)
target_compile_features(penumbra_layer_flags INTERFACE cxx_std_20)
# Vulkan structs are initialised as `VkFoo info{VK_STRUCTURE_TYPE_FOO}`: the rest is zeroed on purpose.
target_compile_options(penumbra_layer_flags INTERFACE -Wall -Wextra -Wno-missing-field-initializers)
target_compile_definitions(penumbra_layer_flags INTERFACE GLM_FORCE_DEPTH_ZERO_TO_ONE GLM_FORCE_RADIANS GLM_ENABLE_EXPERIMENTAL)
target_link_libraries(penumbra_layer_flags INTERFACE glm::glm)
if(PENUMBRA_ENABLE_ASSERTS)
  target_compile_definitions(penumbra_layer_flags INTERFACE PENUMBRA_ENABLE_ASSERTS)
endif()

# An include root that reaches src/<folder> only (also used for the programs' own folders).
function(penumbra_include_root folder out_var)
  set(root ${PENUMBRA_LAYER_ROOT}/${folder})
  file(MAKE_DIRECTORY ${root})
  file(CREATE_LINK ${CMAKE_SOURCE_DIR}/src/${folder} ${root}/${folder} SYMBOLIC)
  set(${out_var} ${root} PARENT_SCOPE)
endfunction()

# penumbra_add_layer(<name> [USES <layers below>...] [PUBLIC_HEADERS <include/penumbra/ files>...]
#                    [VULKAN] [LINK <libraries>...] [INCLUDES <folders>...])
# USES: the layers it may include and call (their own uses come with them). PUBLIC_HEADERS: the
# public headers this layer implements, reachable from it and the layers above. VULKAN: it may see
# Vulkan's headers (gpu only). LINK: the third-party libraries it uses. INCLUDES: more include
# folders, public (shaders/shared).
function(penumbra_add_layer name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "VULKAN" "" "USES;PUBLIC_HEADERS;LINK;INCLUDES")
  penumbra_include_root(${name} root)
  file(MAKE_DIRECTORY ${root}/penumbra)
  foreach(header ${arg_PUBLIC_HEADERS})
    set(path ${CMAKE_SOURCE_DIR}/include/penumbra/${header})
    if(NOT EXISTS ${path})
      set(path ${CMAKE_BINARY_DIR}/include/penumbra/${header})  # generated (version.h)
    endif()
    if(NOT EXISTS ${path})
      message(FATAL_ERROR "layer ${name}: no public header penumbra/${header}")
    endif()
    get_filename_component(link_dir ${root}/penumbra/${header} DIRECTORY)
    file(MAKE_DIRECTORY ${link_dir})
    file(CREATE_LINK ${path} ${root}/penumbra/${header} SYMBOLIC)
  endforeach()
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/${name}/*.cpp)
  add_library(penumbra_${name} OBJECT ${sources})
  target_include_directories(penumbra_${name} PUBLIC ${root} ${arg_INCLUDES})
  target_include_directories(penumbra_${name} SYSTEM PRIVATE /usr/include/stb)
  if(NOT arg_VULKAN)
    target_include_directories(penumbra_${name} BEFORE PRIVATE ${PENUMBRA_NO_VULKAN_DIR})
  endif()
  list(TRANSFORM arg_USES PREPEND penumbra_ OUTPUT_VARIABLE lower)
  target_link_libraries(penumbra_${name} PUBLIC penumbra_layer_flags ${lower} PRIVATE ${arg_LINK})
  set_property(GLOBAL APPEND PROPERTY PENUMBRA_LAYERS ${name})
  set_property(GLOBAL PROPERTY PENUMBRA_LAYER_USES_${name} ${arg_USES})
endfunction()

# Every folder of src/ is a layer or a program: a new folder must be given its place.
function(penumbra_check_layer_folders)
  get_property(layers GLOBAL PROPERTY PENUMBRA_LAYERS)
  file(GLOB folders LIST_DIRECTORIES true RELATIVE ${CMAKE_SOURCE_DIR}/src ${CMAKE_SOURCE_DIR}/src/*)
  foreach(folder ${folders})
    if(IS_DIRECTORY ${CMAKE_SOURCE_DIR}/src/${folder} AND NOT folder IN_LIST layers AND NOT folder IN_LIST ARGN)
      message(FATAL_ERROR "src/${folder}/ is in no layer: add it with penumbra_add_layer in CMakeLists.txt "
                          "(docs/architecture.md)")
    endif()
  endforeach()
endfunction()

# <build>/layers/layers.json: each layer's uses and include path as compiled, and each program's
# (`programs`: the targets of penumbra_add_program), for scripts/check_layers.py (ctest's
# LayersIncludeOnlyWhatTheyUse and LayerBoundariesFailToCompile).
function(penumbra_write_layer_graph)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "" "PROGRAMS")
  get_property(layers GLOBAL PROPERTY PENUMBRA_LAYERS)
  set(layer_entries "")
  foreach(name ${layers})
    get_property(uses GLOBAL PROPERTY PENUMBRA_LAYER_USES_${name})
    list(TRANSFORM uses REPLACE "(.+)" "\"\\1\"")
    list(JOIN uses ", " uses_json)
    set(dirs "$<TARGET_PROPERTY:penumbra_${name},INCLUDE_DIRECTORIES>")
    list(APPEND layer_entries "    \"${name}\": {\"uses\": [${uses_json}], \"includeDirs\": [\"$<JOIN:${dirs},\", \">\"]}")
  endforeach()
  set(program_entries "")
  foreach(target ${arg_PROGRAMS})
    get_target_property(folder ${target} PENUMBRA_PROGRAM_FOLDER)
    set(dirs "$<TARGET_PROPERTY:${target},INCLUDE_DIRECTORIES>")
    list(APPEND program_entries "    \"${folder}\": {\"includeDirs\": [\"$<JOIN:${dirs},\", \">\"]}")
  endforeach()
  list(JOIN layer_entries ",\n" layer_body)
  list(JOIN program_entries ",\n" program_body)
  file(GENERATE OUTPUT ${PENUMBRA_LAYER_ROOT}/layers.json CONTENT
       "{\n  \"compiler\": \"${CMAKE_CXX_COMPILER}\",\n  \"sourceDir\": \"${CMAKE_SOURCE_DIR}\",\n  \"layers\": {\n${layer_body}\n  },\n  \"programs\": {\n${program_body}\n  }\n}\n")
endfunction()
