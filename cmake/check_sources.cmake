# proxima_check_sources(LIST_FILE <file> DIRS <dir>... SOURCES <source>...)
# Fails the configure step when a .cpp under one of DIRS (recursively, relative to the
# source tree) is not among SOURCES, or a listed source does not exist, naming the file and
# the list to fix. The glob is CONFIGURE_DEPENDS: a new .cpp re-runs the configure step at
# the next build, which then fails until the file is listed.
function(proxima_check_sources)
  cmake_parse_arguments(ARG "" "LIST_FILE" "DIRS;SOURCES" ${ARGN})
  set(unlisted)
  foreach(dir IN LISTS ARG_DIRS)
    file(GLOB_RECURSE found CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}
         ${PROJECT_SOURCE_DIR}/${dir}/*.cpp)
    foreach(file IN LISTS found)
      if(NOT file IN_LIST ARG_SOURCES)
        string(APPEND unlisted "\n  ${file}")
      endif()
    endforeach()
  endforeach()
  set(absent)
  foreach(file IN LISTS ARG_SOURCES)
    if(NOT EXISTS ${PROJECT_SOURCE_DIR}/${file})
      string(APPEND absent "\n  ${file}")
    endif()
  endforeach()
  if(unlisted)
    message(SEND_ERROR "${ARG_LIST_FILE}: these sources are not listed (add each on its own line, "
                       "in sorted order):${unlisted}")
  endif()
  if(absent)
    message(SEND_ERROR "${ARG_LIST_FILE}: these listed sources do not exist (remove their lines):${absent}")
  endif()
endfunction()
