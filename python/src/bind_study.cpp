// proxima.study: each study of the command line as a function returning its metrics,
// tables and images. The functions are generated from the study catalog
// (study/catalog.h): one per entry, its keyword options and docstring from the entry's
// option table, so a new study or option needs no binding code.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <pybind11/stl/filesystem.h>

#include "arrays.h"
#include "bindings.h"
#include "proxima/study/catalog.h"
#include "scene_handle.h"

namespace proxima::python {

namespace {

py::object option_object(const study::OptionValue& value) {
  return std::visit([](const auto& v) -> py::object { return py::cast(v); }, value);
}

// A keyword argument as the catalog's value: bool, int (64-bit), float or str; numpy
// scalars of those kinds too. Anything else is a ValueError naming the option.
study::OptionValue option_value(const std::string& name, py::handle value) {
  if (PyBool_Check(value.ptr())) return value.cast<bool>();
  if (PyFloat_Check(value.ptr()) || py::isinstance(value, py::module_::import("numpy").attr("floating")))
    return value.cast<double>();
  if (PyLong_Check(value.ptr()) || py::isinstance(value, py::module_::import("numpy").attr("integer"))) {
    const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
    if (overflow != 0) fail_input("option '" + name + "': " + std::string(py::str(value)) + " is out of range");
    return std::int64_t(v);
  }
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  fail_input("option '" + name + "': expected bool, int, float or str, got " + describe(value));
}

study::OptionValues option_values(const py::kwargs& kwargs) {
  study::OptionValues values;
  for (const auto& [key, value] : kwargs) {
    const auto name = key.cast<std::string>();
    values[name] = option_value(name, value);
  }
  return values;
}

py::dict run(const std::string& name, const SceneHandle& handle, const std::optional<std::filesystem::path>& out_dir,
             py::object progress, const py::kwargs& kwargs) {
  const study::OptionValues values = option_values(kwargs);
  study::resolved_options(name, values);  // unknown options and wrong types, before anything runs
  if (out_dir && out_dir->empty()) fail_input(name + ": out_dir: must not be empty (None writes no images)");
  ProgressCallback callback(std::move(progress));
  Results results;
  std::map<std::string, ImageF> arrays;
  {
    py::gil_scoped_release release;
    const auto lock = handle.read_lock();
    results = study::run_study(name, handle.scene(), values, study::StudyOutput{out_dir.value_or(""), &arrays},
                               callback.get());
  }
  return results_dict(results, std::move(arrays));
}

// A default as Python writes it: 'text', True / False, numbers to float precision.
std::string default_text(const study::OptionValue& value) {
  if (const auto* text = std::get_if<std::string>(&value)) return "'" + *text + "'";
  if (const auto* b = std::get_if<bool>(&value)) return *b ? "True" : "False";
  if (const auto* d = std::get_if<double>(&value); d && std::isfinite(*d)) {
    char text[32];  // the float fields' precision: 0.3, not 0.30000001192092896
    std::snprintf(text, sizeof text, "%.7g", *d);
    return text;
  }
  return study::option_text(value);
}

// The docstring of one study: its summary, the call, then one line per option with its
// type, default and meaning.
std::string study_doc(const study::StudyInfo& info) {
  std::string doc = info.summary + ".\n\n" + info.name +
                    "(scene, out_dir=None, progress=None, **options) -> dict with 'metrics' (name → float), "
                    "'tables' (list of dicts with 'title', 'columns', 'rows'), 'images' (role → file name "
                    "in out_dir; empty when out_dir is None, which writes nothing) and 'arrays' (role → the "
                    "image as an H×W×C float32 array (H×W for one channel): linear RGB where the file is a PNG, the EXR's "
                    "channels where it is an EXR; with or without out_dir). progress(stage, what, done, "
                    "total) is called as the study advances. Runs with the GIL released.\n\nOptions:\n";
  for (const study::OptionInfo& o : info.options) {
    doc += "  " + o.name + " (" + o.type + ", default " + default_text(o.default_value) + "): " + o.doc;
    if (!o.choices.empty()) {
      doc += " [";
      for (size_t i = 0; i < o.choices.size(); ++i) doc += (i ? ", " : "") + o.choices[i];
      doc += "]";
    }
    doc += "\n";
  }
  return doc;
}

py::list catalog_list() {
  py::list out;
  for (const study::StudyInfo& info : study::study_catalog()) {
    py::list options;
    for (const study::OptionInfo& o : info.options)
      options.append(named({{"name", o.name}, {"type", o.type}, {"default", option_object(o.default_value)},
                            {"doc", o.doc}, {"choices", o.choices}}));
    out.append(named({{"name", info.name}, {"summary", info.summary}, {"options", options}}));
  }
  return out;
}

}  // namespace

void bind_studies(py::module_& m) {
  py::module_ s = m.def_submodule("study",
                                  "The studies of the command line (study/catalog.h), one function per study: "
                                  "proxima.study.<name>(scene, out_dir=None, progress=None, **options).");
  s.def("catalog", &catalog_list,
        "Every study: a list of dicts with 'name', 'summary' and 'options' (dicts with 'name', 'type' — "
        "'bool', 'int', 'float' or 'string' —, 'default', 'doc' and 'choices', the valid names of an enum).");
  s.def(
      "options",
      [](const std::string& name, const py::kwargs& kwargs) {
        py::dict out;
        for (const auto& [key, value] : study::resolved_options(name, option_values(kwargs)))
          out[py::str(key)] = option_object(value);
        return out;
      },
      py::arg("name"),
      "Every option of study `name` with the keyword arguments applied over the defaults, as the study "
      "sees them; ValueError for an unknown study or option or a value of the wrong type.");
  for (const study::StudyInfo& info : study::study_catalog()) {
    const std::string name = info.name;
    s.def(
        name.c_str(),
        [name](const SceneHandle& scene, const std::optional<std::filesystem::path>& out_dir, py::object progress,
               const py::kwargs& kwargs) { return run(name, scene, out_dir, std::move(progress), kwargs); },
        py::arg("scene"), py::arg("out_dir") = py::none(), py::arg("progress") = py::none(), study_doc(info).c_str());
  }
  // `import proxima.study` and `from proxima.study import …` find the submodule.
  py::module_::import("sys").attr("modules")["proxima.study"] = s;
}

}  // namespace proxima::python
