# Script mode (cmake -DDIR=... -DOUT=... -P): writes every ${DIR}/*.json, in name order, into ${OUT} as the bytes of
# `embeddedPresetFiles()` (preprocess/classify/embedded_presets.h), so that the tools carry their presets.
file(GLOB files ${DIR}/*.json)
list(SORT files)
set(arrays "")
set(entries "")
set(index 0)
foreach(file ${files})
  get_filename_component(name ${file} NAME)
  file(READ ${file} hex HEX)
  string(LENGTH "${hex}" digits)
  math(EXPR bytes "${digits} / 2")
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," values "${hex}")
  string(APPEND arrays "const unsigned char file${index}[] = {${values}};\n")
  string(APPEND entries "        {\"${name}\", {reinterpret_cast<const char*>(file${index}), ${bytes}}},\n")
  math(EXPR index "${index} + 1")
endforeach()
if(index EQUAL 0)
  message(FATAL_ERROR "no preset (*.json) in ${DIR}")
endif()
file(WRITE ${OUT}.tmp "// Written by cmake/EmbedPresets.cmake from ${DIR}: edit those files, not this one.
#include \"preprocess/classify/embedded_presets.h\"

namespace {
${arrays}}  // namespace

namespace vr {

std::vector<EmbeddedFile> embeddedPresetFiles() {
    return {
${entries}    };
}

}  // namespace vr
")
file(RENAME ${OUT}.tmp ${OUT})
