# Precompiled headers (PROXIMA_PCH, on by default): per target, the third-party and standard
# headers most of its sources include, parsed once instead of once per source. Only headers
# that outside code cannot change: proxima's own headers stay out, so an edit to one of them
# rebuilds only its includers. nlohmann/json (6 library sources) and Embree (3, and cheap to
# parse) stay out too: every other source would load them with the precompiled header.
# docs/build.md has the measured effect and the ccache setting it needs.
option(PROXIMA_PCH "Precompile the heavy third-party and standard headers of each target" ON)
# The instrumented clang fuzz builds compile without: built once from scratch per CI run,
# where a precompiled header saves little, and the one configuration GCC does not cover.
if(PROXIMA_FUZZ)
  set(PROXIMA_PCH OFF)
endif()

# ccache caches compiles that use a precompiled header only with this sloppiness (ccache
# manual, "Precompiled headers"); set here, for proxima's compiles only, when CMake runs
# the compiler through ccache (CMAKE_CXX_COMPILER_LAUNCHER=ccache).
if(PROXIMA_PCH AND CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache")
  execute_process(COMMAND ccache --get-config sloppiness OUTPUT_VARIABLE proxima_sloppiness
    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT proxima_sloppiness MATCHES "pch_defines" OR NOT proxima_sloppiness MATCHES "time_macros")
    string(REGEX REPLACE "^,|,$" "" proxima_sloppiness "${proxima_sloppiness},pch_defines,time_macros")
    set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env CCACHE_SLOPPINESS=${proxima_sloppiness}
        ${CMAKE_CXX_COMPILER_LAUNCHER})
  endif()
endif()

# proxima_precompile_headers(<target> <header>...): precompiles the headers for <target>
# when PROXIMA_PCH is on.
function(proxima_precompile_headers target)
  if(PROXIMA_PCH)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

# Sources compiled with options of their own (a different -f flag than the precompiled
# header's) include their headers as usual: GCC would reject the header (-Winvalid-pch).
function(proxima_skip_precompiled_headers)
  set_source_files_properties(${ARGN} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
endfunction()
