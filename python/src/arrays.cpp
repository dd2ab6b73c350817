#include "arrays.h"

#include <cmath>
#include <variant>

#include "proxima/core/camera.h"

namespace proxima::python {

void register_exceptions(py::module_& /*m*/) {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const MissingFileError& e) {
      PyErr_SetString(PyExc_FileNotFoundError, e.what());
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

py::array id_image_array(ImageU32&& ids) { return image_array<int32_t>(std::move(ids)); }

py::dict named(std::initializer_list<Named> entries) {
  py::dict out;
  for (const Named& e : entries) out[e.name] = e.value;
  return out;
}

py::array image_copy_array(const ImageF& image) { return image_array(ImageF(image), false); }

py::dict mesh_dict(Mesh&& mesh) {
  static_assert(sizeof(vec3) == 3 * sizeof(float) && sizeof(uvec3) == 3 * sizeof(uint32_t));
  const auto v = py::ssize_t(mesh.positions.size()), n = py::ssize_t(mesh.normals.size());
  const auto t = py::ssize_t(mesh.triangles.size());
  return named({{"positions", buffer_array<float>(std::move(mesh.positions), {v, 3})},
                {"normals", buffer_array<float>(std::move(mesh.normals), {n, 3})},
                {"triangles", buffer_array<uint32_t>(std::move(mesh.triangles), {t, 3})}});
}

namespace {

py::list tables_list(const std::vector<Table>& tables) {
  py::list out;
  for (const Table& t : tables) {
    py::list rows;
    for (const auto& row : t.rows) {
      py::list cells;
      for (const auto& cell : row)
        cells.append(std::visit([](const auto& v) -> py::object { return py::cast(v); }, cell));
      rows.append(cells);
    }
    out.append(named({{"title", t.title}, {"columns", t.columns}, {"rows", rows}}));
  }
  return out;
}

}  // namespace

py::dict results_dict(const Results& results, std::map<std::string, ImageF>&& arrays) {
  py::dict images;
  for (auto& [role, image] : arrays) images[py::str(role)] = image_array(std::move(image));
  return named({{"metrics", results.metrics}, {"tables", tables_list(results.tables)}, {"images", results.images},
                {"arrays", images}});
}

std::string describe(py::handle obj) {
  if (!py::isinstance<py::array>(obj)) return std::string(py::str(py::type::handle_of(obj).attr("__name__")));
  const auto a = py::reinterpret_borrow<py::array>(obj);
  std::string shape = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    shape += (d ? ", " : "") + std::to_string(a.shape(d));
  shape += a.ndim() == 1 ? ",)" : ")";
  return std::string(py::str(a.dtype())) + " array of shape " + shape;
}

template <typename T>
py::array_t<T, py::array::c_style> checked_rows(py::handle obj, const std::string& what, py::ssize_t cols) {
  const std::string expected = std::string(py::str(py::dtype::of<T>())) + " array of shape " +
                               (cols > 0 ? "(N, " + std::to_string(cols) + ")" : "(N,)");
  if (!py::isinstance<py::array>(obj)) fail_input(what + ": expected a " + expected + ", got " + describe(obj));
  const auto a = py::reinterpret_borrow<py::array>(obj);
  const bool shape_ok = cols > 0 ? a.ndim() == 2 && a.shape(1) == cols : a.ndim() == 1;
  if (!a.dtype().is(py::dtype::of<T>()) || !shape_ok)
    fail_input(what + ": expected a " + expected + ", got " + describe(obj));
  auto c = py::array_t<T, py::array::c_style>::ensure(a);
  if (!c) throw py::error_already_set();
  return c;
}

template py::array_t<float, py::array::c_style> checked_rows<float>(py::handle, const std::string&, py::ssize_t);
template py::array_t<int32_t, py::array::c_style> checked_rows<int32_t>(py::handle, const std::string&, py::ssize_t);

ImageF checked_image(py::handle obj, const std::string& what, int min_channels) {
  const std::string expected = "float32 array of shape (H, W, C) with C ≥ " + std::to_string(min_channels);
  if (!py::isinstance<py::array>(obj)) fail_input(what + ": expected a " + expected + ", got " + describe(obj));
  const auto a = py::reinterpret_borrow<py::array>(obj);
  const bool shape_ok = a.ndim() == 3 ? a.shape(2) >= min_channels && a.shape(2) <= 4
                                      : a.ndim() == 2 && min_channels == 1;
  if (!a.dtype().is(py::dtype::of<float>()) || !shape_ok)
    fail_input(what + ": expected a " + expected + ", got " + describe(obj));
  if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > kMaxImageSide || a.shape(1) > kMaxImageSide)
    fail_input(what + ": image sides must be in 1.." + std::to_string(kMaxImageSide) + ", got " + describe(obj));
  const auto c = py::array_t<float, py::array::c_style>::ensure(a);
  if (!c) throw py::error_already_set();
  ImageF image(int(a.shape(1)), int(a.shape(0)), a.ndim() == 3 ? int(a.shape(2)) : 1);
  std::copy(c.data(), c.data() + c.size(), image.data().begin());
  return image;
}

void check_finite(const float* values, size_t count, const std::string& what) {
  for (size_t i = 0; i < count; ++i)
    if (!std::isfinite(values[i])) fail_input(what + ": value " + std::to_string(i) + " is not finite");
}

vec3 to_vec3(py::handle obj, const std::string& what) {
  if (!py::isinstance<py::sequence>(obj) && !py::isinstance<py::array>(obj))
    fail_input(what + ": expected three numbers, got " + describe(obj));
  const auto seq = py::reinterpret_borrow<py::sequence>(obj);
  if (py::len(seq) != 3) fail_input(what + ": expected three numbers, got " + std::to_string(py::len(seq)));
  vec3 v;
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = seq[size_t(i)].cast<float>();
    } catch (const py::cast_error&) {
      fail_input(what + ": expected three numbers, got " + describe(seq[size_t(i)]));
    }
  }
  check_finite(&v.x, 3, what);
  return v;
}

ProgressCallback::ProgressCallback(py::object callback) : callback_(std::move(callback)) {
  if (callback_.is_none()) return;
  if (!PyCallable_Check(callback_.ptr())) fail_input("progress: expected a callable or None");
  // The listener borrows the callable (this object holds the reference), so copies of it
  // never touch reference counts without the GIL.
  const py::handle cb = callback_;
  progress_.emplace([cb](const ProgressEvent& e) {
    py::gil_scoped_acquire gil;
    cb(e.stage, e.what, e.done, e.total);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  });
}

}  // namespace proxima::python
