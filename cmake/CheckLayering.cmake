# cmake -DRULES=FILE -P script (cmake/DepotLayering.cmake): every quoted
# include of FILES that names a header in one of FOLDERS must name one in
# ALLOWED (LIBRARY's own folder and the folders of what it links). Touches
# STAMP when all do.
cmake_minimum_required(VERSION 3.22)  # IN_LIST
include("${RULES}")
set(failures 0)
foreach(file IN LISTS FILES)
  file(STRINGS "${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"[^\"]+\"")
  file(RELATIVE_PATH shown "${SOURCE_DIR}" "${file}")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([^\"]+)\".*" "\\1" header "${line}")
    get_filename_component(folder "${header}" DIRECTORY)
    if(folder IN_LIST FOLDERS AND NOT folder IN_LIST ALLOWED)
      message(NOTICE "${shown}: error: includes \"${header}\", but ${LIBRARY} does not "
                     "link the library of ${folder} (no include runs up the layers)")
      math(EXPR failures "${failures} + 1")
    endif()
  endforeach()
endforeach()
if(failures GREATER 0)
  message(FATAL_ERROR "${LIBRARY}: ${failures} include(s) against the layers")
endif()
file(TOUCH "${STAMP}")
