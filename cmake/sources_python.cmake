# The Python module's C++ sources (cmake/python.cmake), one per line, sorted; a .cpp under
# python/src missing here fails the configure step.
set(PROXIMA_PYTHON_SOURCES
  python/src/arrays.cpp
  python/src/bind_depth_images.cpp
  python/src/bind_eval.cpp
  python/src/bind_gibr.cpp
  python/src/bind_rays.cpp
  python/src/bind_render.cpp
  python/src/bind_scene.cpp
  python/src/bind_study.cpp
  python/src/bind_techniques.cpp
  python/src/bind_visibility.cpp
  python/src/module.cpp
  python/src/scene_handle.cpp
)
# The pure-Python files of the package (python/proxima/), copied beside the extension.
set(PROXIMA_PYTHON_FILES
  python/proxima/__init__.py
)
