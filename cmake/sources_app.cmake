# The sources of the `proxima` command line: one file per line, sorted. A .cpp under
# apps/proxima/ that is not listed here fails the configure step (cmake/check_sources.cmake).
set(PROXIMA_APP_SOURCES
  apps/proxima/cmd_bench.cpp
  apps/proxima/cmd_bench_view.cpp
  apps/proxima/cmd_demo.cpp
  apps/proxima/cmd_gibr.cpp
  apps/proxima/cmd_info.cpp
  apps/proxima/cmd_reflect.cpp
  apps/proxima/cmd_reflect_cluster.cpp
  apps/proxima/cmd_reflect_temporal.cpp
  apps/proxima/cmd_render.cpp
  apps/proxima/cmd_results.cpp
  apps/proxima/cmd_sample.cpp
  apps/proxima/cmd_scenes.cpp
  apps/proxima/cmd_shadows.cpp
  apps/proxima/cmd_sweep.cpp
  apps/proxima/cmd_view.cpp
  apps/proxima/cmd_visibility.cpp
  apps/proxima/command.cpp
  apps/proxima/llvmpipe_columns.cpp
  apps/proxima/main.cpp
  apps/proxima/scene_study.cpp
  apps/proxima/view_flags.cpp
)
# The window of `proxima view`: one of the two, by whether SDL2 is found.
set(PROXIMA_APP_WINDOW_SDL_SOURCES apps/proxima/sdl/view_window_sdl.cpp)
set(PROXIMA_APP_WINDOW_NONE_SOURCES apps/proxima/sdl/view_window_none.cpp)
# The MPI transport of `proxima sweep`: one of the two, by whether MPI is found (PROXIMA_MPI).
set(PROXIMA_APP_MPI_SOURCES apps/proxima/mpi/sweep_mpi.cpp)
set(PROXIMA_APP_NO_MPI_SOURCES apps/proxima/mpi/sweep_no_mpi.cpp)
