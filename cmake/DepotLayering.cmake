# Folders are build targets, and an include must follow the links: a source
# or header of a library's folder may include headers of its own folder and of
# the folders of the libraries it links (directly or not), never of a folder
# above it. A library is compiled only after its folder passed the check
# (cmake/CheckLayering.cmake), so an upward include fails the build with one
# line naming the file, the include and the missing link.
#
# depot_register_folder(TARGET SOURCES): called by depot_library; a library
# whose sources all lie in one folder, the only one there, owns that folder.
function(depot_register_folder name sources)
  set(folder "")
  foreach(source IN LISTS sources)
    get_filename_component(path "${source}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    get_filename_component(dir "${path}" DIRECTORY)
    file(RELATIVE_PATH dir "${DEPOT_SOURCE_DIR}" "${dir}")
    if(folder STREQUAL "")
      set(folder "${dir}")
    elseif(NOT folder STREQUAL dir)
      return()  # sources from several folders: the folder is nobody's alone
    endif()
  endforeach()
  if(folder STREQUAL "")
    return()
  endif()
  # A folder of several libraries (common/: depot_png beside depot_common;
  # tests/support) is nobody's alone and left to the linker.
  get_property(owner GLOBAL PROPERTY DEPOT_FOLDER_OWNER_${folder})
  if(owner)
    if(TARGET ${owner})
      set_property(GLOBAL PROPERTY DEPOT_FOLDER_OWNER_${folder} "shared")
      get_property(libraries GLOBAL PROPERTY DEPOT_FOLDER_LIBRARIES)
      list(REMOVE_ITEM libraries ${owner})
      set_property(GLOBAL PROPERTY DEPOT_FOLDER_LIBRARIES ${libraries})
      set_target_properties(${owner} PROPERTIES DEPOT_FOLDER "")
    endif()
    return()
  endif()
  set_property(GLOBAL PROPERTY DEPOT_FOLDER_OWNER_${folder} ${name})
  set_property(GLOBAL APPEND PROPERTY DEPOT_FOLDER_LIBRARIES ${name})
  set_target_properties(${name} PROPERTIES DEPOT_FOLDER "${folder}")
endfunction()

# The depot libraries `target` links, directly or through others (interface
# libraries included), into `out`.
function(_depot_linked_closure target out)
  set(seen "")
  set(queue ${target})
  while(queue)
    list(POP_FRONT queue current)
    get_target_property(type ${current} TYPE)
    set(links "")
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(direct ${current} LINK_LIBRARIES)
      if(direct)
        list(APPEND links ${direct})
      endif()
    endif()
    get_target_property(interface ${current} INTERFACE_LINK_LIBRARIES)
    if(interface)
      list(APPEND links ${interface})
    endif()
    foreach(link IN LISTS links)
      if(TARGET ${link} AND NOT link IN_LIST seen AND link MATCHES "^depot_")
        list(APPEND seen ${link})
        list(APPEND queue ${link})
      endif()
    endforeach()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

# Called once every target exists (end of the top-level CMakeLists.txt).
function(depot_check_layering)
  get_property(libraries GLOBAL PROPERTY DEPOT_FOLDER_LIBRARIES)
  set(folders "")
  foreach(library IN LISTS libraries)
    get_target_property(folder ${library} DEPOT_FOLDER)
    list(APPEND folders ${folder})
  endforeach()
  foreach(library IN LISTS libraries)
    get_target_property(folder ${library} DEPOT_FOLDER)
    _depot_linked_closure(${library} linked)
    set(allowed ${folder})
    foreach(other IN LISTS linked)
      get_target_property(other_folder ${other} DEPOT_FOLDER)
      if(other_folder)
        list(APPEND allowed ${other_folder})
      endif()
    endforeach()
    # The folder's library sources and every header in it (test sources
    # belong to test binaries, which may reach higher).
    get_target_property(sources ${library} SOURCES)
    get_target_property(source_dir ${library} SOURCE_DIR)
    set(files "")
    foreach(source IN LISTS sources)
      get_filename_component(path "${source}" ABSOLUTE BASE_DIR "${source_dir}")
      list(APPEND files "${path}")
    endforeach()
    file(GLOB headers CONFIGURE_DEPENDS "${DEPOT_SOURCE_DIR}/${folder}/*.h")
    list(APPEND files ${headers})
    # The rules go to a file rewritten only when they change, so a changed
    # link reruns the check as a changed source does.
    set(rules "${CMAKE_BINARY_DIR}/layering/${library}.rules.cmake")
    set(stamp "${CMAKE_BINARY_DIR}/layering/${library}.checked")
    file(CONFIGURE OUTPUT "${rules}" CONTENT
"set(LIBRARY \"${library}\")
set(SOURCE_DIR \"${DEPOT_SOURCE_DIR}\")
set(FILES \"${files}\")
set(FOLDERS \"${folders}\")
set(ALLOWED \"${allowed}\")
set(STAMP \"${stamp}\")
")
    add_custom_command(
      OUTPUT "${stamp}"
      COMMAND ${CMAKE_COMMAND} "-DRULES=${rules}" -P "${DEPOT_SOURCE_DIR}/cmake/CheckLayering.cmake"
      DEPENDS ${files} "${rules}" "${DEPOT_SOURCE_DIR}/cmake/CheckLayering.cmake"
      COMMENT "Checking the includes of ${folder}"
      VERBATIM)
    add_custom_target(${library}_layering DEPENDS "${stamp}")
    add_dependencies(${library} ${library}_layering)
  endforeach()
endfunction()
