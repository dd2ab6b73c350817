// llvmpipe harness: renders the frame proxima's rasterizer benchmark renders (a scene's
// camera, depth + primitive-id output) with Mesa's llvmpipe through EGL (surfaceless
// platform, OpenGL 3.3 core) and prints its timing as one JSON object on stdout, so
// `proxima bench raster` can run it as a subprocess side by side with its own figures.
//
//   proxima_llvmpipe_bench [--scene NAME|FILE] [--camera NAME] [--width W] [--height H]
//                          [--threads N] [--repetitions R]
//
// --threads sets LP_NUM_THREADS (llvmpipe's rasterizer threads; its setup and binning run
// on the calling thread). Output: {"renderer", "threads", "width", "height", "triangles",
// "ms_depth_id" (median over repetitions: clear + draw + glFinish), "ms_samples",
// "readback_ms", "id_agreement_with_proxima_pct"}. Exit 2 on bad arguments, 1 when EGL /
// OpenGL / llvmpipe are unavailable.
//
// Output buffers: an R32UI color attachment written from gl_PrimitiveID (= scene triangle
// id: the whole scene is one draw call over Scene::triangles) and a 32-bit float depth
// attachment, GL_LESS; no culling, as proxima's default.
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/scene/load.h"

namespace {

using namespace proxima;

[[noreturn]] void die(int code, const std::string& message) {
  std::fprintf(stderr, "proxima_llvmpipe_bench: %s\n", message.c_str());
  std::exit(code);
}

struct Args {
  std::string scene = "living-room";  // built-in name or scene/mesh file (load_scene)
  std::string camera;                 // empty = the scene's first camera
  int width = 1024, height = 1024, threads = 0, repetitions = 7;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) die(2, "missing value for " + flag);
    const std::string value = argv[++i];
    auto number = [&]() {
      char* end = nullptr;
      const long v = std::strtol(value.c_str(), &end, 10);
      if (*end != '\0' || v <= 0 || v > 16384) die(2, "bad value for " + flag + ": " + value);
      return int(v);
    };
    if (flag == "--scene")
      a.scene = value;
    else if (flag == "--camera")
      a.camera = value;
    else if (flag == "--width")
      a.width = number();
    else if (flag == "--height")
      a.height = number();
    else if (flag == "--threads")
      a.threads = number();
    else if (flag == "--repetitions")
      a.repetitions = number();
    else
      die(2, "unknown flag " + flag);
  }
  return a;
}

GLuint compile(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    die(1, std::string("shader compile failed: ") + log);
  }
  return shader;
}

// EGL display + OpenGL 3.3 core context without any surface.
void make_context() {
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) die(1, "eglGetPlatformDisplayEXT unavailable");
  EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr))
    die(1, "cannot initialize the EGL surfaceless display");
  if (!eglBindAPI(EGL_OPENGL_API)) die(1, "eglBindAPI(EGL_OPENGL_API) failed");
  // Rendering goes to a framebuffer object, so no config is needed
  // (EGL_KHR_no_config_context, which Mesa's surfaceless platform offers).
  const EGLConfig config = EGL_NO_CONFIG_KHR;
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    3,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
  if (context == EGL_NO_CONTEXT) die(1, "cannot create an OpenGL 3.3 core context");
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
    die(1, "eglMakeCurrent without surface failed (EGL_KHR_surfaceless_context)");
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse_args(argc, argv);
  // Before EGL loads Mesa: software rendering with llvmpipe, with the requested threads.
  setenv("EGL_PLATFORM", "surfaceless", 1);
  setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
  setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  if (args.threads > 0) setenv("LP_NUM_THREADS", std::to_string(args.threads).c_str(), 1);

  Scene scene;
  try {
    scene = load_scene(args.scene);
  } catch (const InputError& e) {
    die(2, e.what());
  }
  if (scene.cameras.empty()) die(2, "scene " + args.scene + " has no camera");
  Camera camera = scene.cameras.front().camera;
  if (!args.camera.empty()) {
    const auto named = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                                    [&](const NamedCamera& c) { return c.name == args.camera; });
    if (named == scene.cameras.end()) die(2, "scene " + args.scene + " has no camera " + args.camera);
    camera = named->camera;
  }
  camera.width = args.width;
  camera.height = args.height;

  make_context();
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!renderer || !std::strstr(renderer, "llvmpipe"))
    die(1, std::string("renderer is not llvmpipe: ") + (renderer ? renderer : "(none)"));

  // Render target: triangle id (R32UI) + 32-bit float depth.
  GLuint fbo, color, depth;
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glGenRenderbuffers(1, &color);
  glBindRenderbuffer(GL_RENDERBUFFER, color);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_R32UI, args.width, args.height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
  glGenRenderbuffers(1, &depth);
  glBindRenderbuffer(GL_RENDERBUFFER, depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, args.width, args.height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) die(1, "incomplete framebuffer");

  const GLuint program = glCreateProgram();
  glAttachShader(program, compile(GL_VERTEX_SHADER,
                                  "#version 330 core\n"
                                  "layout(location = 0) in vec3 position;\n"
                                  "uniform mat4 view_projection;\n"
                                  "void main() { gl_Position = view_projection * vec4(position, 1.0); }\n"));
  glAttachShader(program, compile(GL_FRAGMENT_SHADER,
                                  "#version 330 core\n"
                                  "out uint id;\n"
                                  "void main() { id = uint(gl_PrimitiveID); }\n"));
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked) die(1, "program link failed");
  glUseProgram(program);
  const mat4 view_projection = projection_matrix(camera) * view_matrix(camera);
  glUniformMatrix4fv(glGetUniformLocation(program, "view_projection"), 1, GL_FALSE, &view_projection[0][0]);

  GLuint vao, vbo, ebo;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(scene.positions.size() * sizeof(vec3)), scene.positions.data(),
               GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(vec3), nullptr);
  glEnableVertexAttribArray(0);
  glGenBuffers(1, &ebo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(scene.triangles.size() * sizeof(uvec3)),
               scene.triangles.data(), GL_STATIC_DRAW);

  glViewport(0, 0, args.width, args.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  const GLsizei index_count = GLsizei(scene.triangles.size() * 3);
  auto frame = [&]() {
    const GLuint no_triangle[4] = {kNoTriangle, 0, 0, 0};
    const GLfloat far_depth = 1.0f;
    glClearBufferuiv(GL_COLOR, 0, no_triangle);
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
    glFinish();
  };
  frame();  // warm-up: shader JIT, buffer uploads
  std::vector<double> samples;
  for (int r = 0; r < args.repetitions; ++r) {
    Stopwatch watch;
    frame();
    samples.push_back(watch.elapsed_ms());
  }
  if (glGetError() != GL_NO_ERROR) die(1, "OpenGL error while rendering");

  // Read back the ids (GL rows are bottom-up) and compare with proxima's rasterizer.
  std::vector<uint32_t> ids(size_t(args.width) * size_t(args.height));
  Stopwatch readback;
  glReadPixels(0, 0, args.width, args.height, GL_RED_INTEGER, GL_UNSIGNED_INT, ids.data());
  const double readback_ms = readback.elapsed_ms();
  const RasterImages raster = rasterize(scene, camera);
  size_t agree = 0;
  for (int y = 0; y < args.height; ++y)
    for (int x = 0; x < args.width; ++x)
      agree += ids[size_t(args.height - 1 - y) * size_t(args.width) + size_t(x)] == raster.triangle.at(x, y);

  std::string samples_json;
  for (double s : samples) samples_json += (samples_json.empty() ? "" : ", ") + std::to_string(s);
  const char* lp_threads = std::getenv("LP_NUM_THREADS");
  std::printf(
      "{\"renderer\": \"%s\", \"threads\": %s, \"width\": %d, \"height\": %d, \"triangles\": %zu, "
      "\"ms_depth_id\": %.4f, \"ms_samples\": [%s], \"readback_ms\": %.4f, "
      "\"id_agreement_with_proxima_pct\": %.4f}\n",
      renderer, lp_threads ? lp_threads : "null", args.width, args.height, scene.triangles.size(),
      median(samples), samples_json.c_str(), readback_ms, 100.0 * double(agree) / double(ids.size()));
  return 0;
}
