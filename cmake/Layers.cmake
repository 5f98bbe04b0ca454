# The libraries in layers (docs/ARCHITECTURE.md): a library may link and include only libraries of lower layers,
# so data flow one way (load, classify, segment, fields, render, measure) and each layer builds without those
# above it. Libraries of one layer are siblings and use none of each other. Executables (each folder's cmd/,
# bench/, tests/, fuzz/) sit above them all. Each row: library, its folder, its layer.
set(VR_LAYERS
  "volcore        core                 0"
  "volio          io                   1"
  "voltools       tools                1"
  "volhugepages   tools                1"
  "volphantoms    datasets             1"
  "volshaders     shaders              1"
  "volrendercore  render               2"
  "volload        preprocess/load      2"
  "volloadchecks  preprocess/load      2"
  "volclassify    preprocess/classify  2"
  "volsegment     preprocess/segment   2"
  "volfields      preprocess/fields    2"
  "volpipeline    preprocess/pipeline  3"
  "volrender_vk   volrender/vulkan     4"
  "volsweep       sweep                5")

# Fails the configuration when a library of the table links one of its own layer or above (but for the
# libraries of its own folder, which are parts of one).
function(vr_check_layer_links)
  foreach(row ${VR_LAYERS})
    string(REGEX MATCHALL "[^ ]+" f "${row}")
    list(GET f 0 lib)
    list(GET f 1 folder)
    list(GET f 2 layer)
    set(layer_of_${lib} ${layer})
    set(folder_of_${lib} ${folder})
  endforeach()
  foreach(row ${VR_LAYERS})
    string(REGEX MATCHALL "[^ ]+" f "${row}")
    list(GET f 0 lib)
    if(NOT TARGET ${lib})
      message(FATAL_ERROR "cmake/Layers.cmake names ${lib}, which is no target")
    endif()
    get_target_property(direct ${lib} LINK_LIBRARIES)
    get_target_property(interface ${lib} INTERFACE_LINK_LIBRARIES)
    foreach(dep IN LISTS direct interface)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" dep "${dep}")
      if(NOT DEFINED layer_of_${dep} OR folder_of_${dep} STREQUAL folder_of_${lib})  # a part of itself
        continue()
      endif()
      if(NOT layer_of_${dep} LESS layer_of_${lib})
        message(FATAL_ERROR "${lib} (layer ${layer_of_${lib}}) links ${dep} (layer ${layer_of_${dep}}): a library "
          "may use only lower layers (cmake/Layers.cmake, docs/ARCHITECTURE.md)")
      endif()
    endforeach()
  endforeach()
endfunction()
