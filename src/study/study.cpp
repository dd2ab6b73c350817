#include "proxima/study/study.h"

#include "proxima/core/image_io.h"
#include "proxima/core/math.h"

namespace proxima::study {

void write_image(const StudyOutput& out, Results& results, const std::string& role, const std::string& file,
                 const ImageF& image) {
  keep_image(out, role, image);
  if (!out.writes()) return;
  const std::filesystem::path path = out.dir / file;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  write_png_linear(path, image);
  results.images[role] = file;
}

void write_exr_image(const StudyOutput& out, Results& results, const std::string& role, const std::string& file,
                     const ImageF& image) {
  keep_image(out, role, image);
  if (!out.writes()) return;
  write_exr(out.dir / file, image);
  results.images[role] = file;
}

void keep_image(const StudyOutput& out, const std::string& role, const ImageF& image) {
  if (out.keeps()) (*out.kept)[role] = image;
}

ImageF triangle_ids_as_float(const ImageU32& ids) {
  ImageF out(ids.width(), ids.height(), 1);
  for (size_t i = 0; i < ids.data().size(); ++i)
    out.data()[i] = ids.data()[i] == kNoTriangle ? -1.0f : float(ids.data()[i]);
  return out;
}

}  // namespace proxima::study
