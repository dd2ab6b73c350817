// What every binding shares: C++ buffers → numpy arrays without copies, numpy and Python
// values → C++ with dtype, shape and value checks, exception translation, and the progress
// callback adapter.
//
// Errors: proxima's InputError becomes ValueError with the command line's one-line message
// (MissingFileError: FileNotFoundError); the checks here raise the same way, so bad input
// never reaches library code that assumes it was validated.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "proxima/core/error.h"
#include "proxima/core/image.h"
#include "proxima/core/math.h"
#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/scene/mesh.h"

namespace proxima::python {

namespace py = pybind11;

// Registers the translation of proxima's exceptions (InputError → ValueError, MissingFileError
// → FileNotFoundError).
void register_exceptions(py::module_& m);

// An array of `shape` (C order) over `data`, which `owner` owns: the owner moves into a
// capsule the array keeps alive, so nothing is copied. `data` must stay valid while the
// owner lives (a moved std::vector keeps its heap block).
template <typename T, typename Owner>
py::array_t<T> array_owning(Owner&& owner, const std::vector<py::ssize_t>& shape,
                            T* (*data_of)(std::remove_reference_t<Owner>&)) {
  using O = std::remove_reference_t<Owner>;
  auto held = std::make_unique<O>(std::forward<Owner>(owner));
  T* data = data_of(*held);
  py::capsule base(held.get(), [](void* p) { delete static_cast<O*>(p); });
  held.release();  // the capsule owns it now
  return py::array_t<T>(shape, data, base);
}

// A buffer of T (std::vector or LargeBuffer) as a 1-D array of n·k values reshaped to
// `shape`; element types are reinterpreted when `View` differs from T in type but not in
// size (uint32 ids as int32: kNoTriangle reads −1; vec3 as 3 floats).
template <typename View, typename Buffer>
py::array_t<View> buffer_array(Buffer&& buffer, const std::vector<py::ssize_t>& shape) {
  using B = std::remove_reference_t<Buffer>;
  return array_owning<View>(std::forward<Buffer>(buffer), shape,
                            +[](B& b) { return reinterpret_cast<View*>(b.data()); });
}

// An image as an H×W×C array without copying its pixels (H×W when it has one channel and
// `squeeze` is set). `View` reinterprets the pixel type as in buffer_array.
template <typename View = void, typename T>
py::array image_array(Image<T>&& image, bool squeeze = true) {
  using V = std::conditional_t<std::is_void_v<View>, T, View>;
  static_assert(sizeof(V) == sizeof(T));
  std::vector<py::ssize_t> shape = {image.height(), image.width()};
  if (!(squeeze && image.channels() == 1)) shape.push_back(image.channels());
  return array_owning<V>(std::move(image), shape,
                         +[](Image<T>& i) { return reinterpret_cast<V*>(i.data().data()); });
}

// Triangle or object ids (uint32, kNoTriangle / kNoObject where nothing) as H×W int32 with
// −1 where nothing: the same bits, no copy.
py::array id_image_array(ImageU32&& ids);

// One entry of a dict of results: a name and a value pybind11 converts (numbers, strings,
// arrays, cameras, dicts).
struct Named {
  template <typename T>
  Named(const char* n, T&& v) : name(n), value(object_of(std::forward<T>(v))) {}
  const char* name;
  py::object value;

 private:
  template <typename T>
  static py::object object_of(T&& v) {
    if constexpr (std::is_base_of_v<py::handle, std::decay_t<T>>) return py::reinterpret_borrow<py::object>(v);
    else return py::cast(std::forward<T>(v));
  }
};

// The entries as a dict, in order: named({{"beams", stats.beams}, {"ms", stats.ms}}).
py::dict named(std::initializer_list<Named> entries);

// A copy of `image` as an array (image_array of the copy), for images an object keeps.
py::array image_copy_array(const ImageF& image);

// A mesh as a dict of arrays: positions (V×3 float32, world m), normals (V×3 float32, unit;
// 0×3 when the mesh has none), triangles (T×3 uint32 vertex indices, counter-clockwise seen
// from the front).
py::dict mesh_dict(Mesh&& mesh);

// A study's results as Python holds them: metrics (name → float), tables (list of dicts with
// title, columns, rows), images (role → file name in the output directory; empty without one)
// and arrays (role → the image as an H×W×C float32 array, H×W for one channel, as the study
// kept it).
py::dict results_dict(const Results& results, std::map<std::string, ImageF>&& arrays);

// `obj` as a C-contiguous array of dtype T and shape (N, cols) (cols = 0: shape (N,)).
// ValueError naming `what` unless it is a numpy array of exactly that dtype and shape;
// copies only when it is not contiguous.
template <typename T>
py::array_t<T, py::array::c_style> checked_rows(py::handle obj, const std::string& what, py::ssize_t cols);

// An H×W×C float32 array (C ≥ min_channels; C may be absent when min_channels is 1) as an
// image (a copy). ValueError naming `what` for another dtype or shape, or a side above
// kMaxImageSide.
ImageF checked_image(py::handle obj, const std::string& what, int min_channels);

// Fails with ValueError naming `what` unless every value is finite.
void check_finite(const float* values, size_t count, const std::string& what);

// A sequence of three finite numbers (tuple, list, array) as a vec3; ValueError naming `what`.
vec3 to_vec3(py::handle obj, const std::string& what);

// The description of an array's dtype and shape for messages: "float64 array of shape (5, 2)".
std::string describe(py::handle obj);

// The optional `progress` argument of long calls: a Python callable
// progress(stage: str, what: str, done: int, total: int), called with the GIL held from
// whichever thread reports (the call itself runs with the GIL released), or None. Ctrl-C
// and an exception raised by the callback stop the call and propagate. Create and destroy
// it with the GIL held.
class ProgressCallback {
 public:
  explicit ProgressCallback(py::object callback);
  // The Progress to pass to the library; null when there is no callback.
  Progress* get() { return progress_ ? &*progress_ : nullptr; }

 private:
  py::object callback_;
  std::optional<Progress> progress_;
};

}  // namespace proxima::python
