#include "proxima/study/study.h"

#include "proxima/core/image_io.h"

namespace proxima::study {

void write_image(const StudyOutput& out, Results& results, const std::string& role, const std::string& file,
                 const ImageF& image) {
  if (!out.writes()) return;
  const std::filesystem::path path = out.dir / file;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  write_png_linear(path, image);
  results.images[role] = file;
}

}  // namespace proxima::study
