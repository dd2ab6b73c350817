// The viewer's GIBR technique (`proxima gibr`'s phases 1–3 once, phase 4 per frame), in its
// own file like the shadow technique: the model is large and only this entry needs gibr/.
#include "gibr_technique.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <optional>

#include "proxima/gibr/gibr_model.h"
#include "proxima/gibr/novel_view.h"
#include "proxima/gibr/photo_set.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima {

namespace {

// The black frame shown while there is nothing to show yet.
TechniqueFrame placeholder(const Camera& camera, std::string note) {
  TechniqueFrame out;
  out.color = ImageF(camera.width, camera.height, 3, 0.0f);
  out.pending = true;
  out.note = std::move(note);
  return out;
}

}  // namespace

// Built on the first frame after the technique is first selected: that frame only shows
// "building…" (so the window says what the next, blocking frame does), the next one builds
// phases 1–3 with the quick settings (photographs along the scene's first path) and renders.
Technique gibr_technique(std::shared_ptr<ViewerScene> vs, const TechniqueSettings& settings) {
  struct State {
    TechniqueSettings settings;
    std::optional<gibr::GibrModel> model;
    gibr::NovelViewScratch scratch;  // the raster's buffers, kept between frames
    bool announced = false;
    std::string error;  // a failed build: shown instead of frames
  };
  auto st = std::make_shared<State>();
  st->settings = settings;

  Technique t;
  t.name = "gibr";
  t.label = "GIBR novel view";
  if (!is_visibility_model(vs->scene.name))
    t.unavailable = "needs a visibility model scene (rooms, maze, arena, vcity, floor, building)";
  else if (vs->scene.camera_paths.empty())
    t.unavailable = "needs a camera path to place its photographs";
  t.render = [vs, st](const Camera& camera) {
    const TechniqueSettings& s = st->settings;
    if (!st->error.empty()) return placeholder(camera, "GIBR build failed: " + st->error);
    TechniqueFrame out;
    if (!st->model) {
      if (!st->announced) {
        st->announced = true;
        return placeholder(camera, "building the GIBR model (" + std::to_string(s.gibr_model.photos) +
                                       " photographs " + std::to_string(s.gibr_model.photo_width) + "x" +
                                       std::to_string(s.gibr_model.photo_height) + ")...");
      }
      gibr::GibrModelOptions o = s.gibr_model;
      o.seed = s.seed;
      try {
        st->model = gibr::build_gibr_model(vs->scene, o);
      } catch (const std::exception& e) {
        st->error = e.what();
        return placeholder(camera, "GIBR build failed: " + st->error);
      }
      const gibr::GibrModelStats& bs = st->model->stats;
      out.steps.push_back({"photographs (once)", bs.photos_ms});
      out.steps.push_back({"BSP + visibility maps (once)", bs.bsp.build_ms + bs.vismap_ms});
      out.steps.push_back({"radiance maps (once)", st->model->maps.stats.ms});
    }
    const gibr::GibrModel& g = *st->model;
    gibr::NovelViewOptions nvo;
    nvo.k = s.gibr_k;
    gibr::NovelView nv = gibr::render_novel_view(g.scene, g.model, g.maps, camera, nvo, &st->scratch);
    out.steps.push_back({"rasterize", nv.raster_ms});
    out.steps.push_back({"blend + holes", nv.blend_ms});
    char note[96];
    std::snprintf(note, sizeof note, "%zu photographs, unseen %.1f%% of surface pixels", g.cameras.size(),
                  100.0 * double(nv.holes) / double(std::max<size_t>(1, nv.covered)));
    out.note = note;
    out.color = std::move(nv.color);
    return out;
  };
  // The ground truth is the photographs' renderer on their textured scene (what `proxima
  // gibr` compares against), not the plain scene the other techniques show.
  t.reference = [st](const Camera& camera, int row_begin, int row_end) {
    if (!st->model) return ImageF(camera.width, camera.height, 3, 0.0f);  // no frame was refined yet
    ReferenceOptions o = gibr::photo_render_options(st->settings.gibr_model.supersample, st->settings.seed);
    o.row_begin = row_begin;
    o.row_end = row_end;
    return render_reference(st->model->scene, *st->model->rays, camera, o);
  };
  t.adjust = [st](int step) {
    int& k = st->settings.gibr_k;
    k = std::clamp(step > 0 ? k * 2 : k / 2, 1, 16);
    return "photographs blended per pixel k " + std::to_string(k);
  };
  return t;
}

}  // namespace proxima
