# Adds every immediate subfolder of `parent` that has a CMakeLists.txt, in
# sorted order, so a new area (a test suite, a peer engine) is one new
# folder and no edit to a shared list.
function(talus_add_subdirectories parent)
  file(GLOB children LIST_DIRECTORIES true RELATIVE ${parent} CONFIGURE_DEPENDS ${parent}/*)
  list(SORT children)
  foreach(child IN LISTS children)
    if(IS_DIRECTORY ${parent}/${child} AND EXISTS ${parent}/${child}/CMakeLists.txt)
      add_subdirectory(${parent}/${child})
    endif()
  endforeach()
endfunction()
