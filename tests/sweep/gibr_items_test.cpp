// A gibr run as per-photograph sweep items (sweep/gibr_photos.h): the run's results from the
// photographs' stored mappings, merged in photograph order, are bit-identical to the study run
// in one call; a photograph's mapping round-trips through its bytes; a failed photograph fails
// its run's item, not the sweep.
#include <gtest/gtest.h>

#include <string>

#include "proxima/core/error.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/scene/load.h"
#include "proxima/study/gibr.h"
#include "proxima/sweep/gibr_photos.h"
#include "proxima/sweep/sweep.h"
#include "study/study_test_util.h"
#include "test_util.h"

namespace proxima::sweep {
namespace {

namespace fs = std::filesystem;

constexpr const char* kOptions = R"({"photos": 4, "photo_width": 40, "photo_height": 30, "supersample": 1,
    "width": 40, "height": 30, "frames": 2, "fps_repeat": 1})";

Manifest gibr_manifest() {
  return parse_manifest(std::string(R"({"runs": [{"study": "gibr", "scene": "rooms", "options": )") + kOptions + "}]}",
                        ".", "gibr.json");
}

TEST(SweepGibr, ARunBecomesOneItemPerPhotographAndTheRunsItem) {
  const Manifest m = gibr_manifest();
  ASSERT_EQ(m.items.size(), 5u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(m.items[size_t(k)].photo, k);
    EXPECT_EQ(m.items[size_t(k)].id, "i00" + std::to_string(k) + "_gibr_photo");
  }
  EXPECT_EQ(m.items[4].photo, -1);
  EXPECT_EQ(m.items[4].inputs, (std::vector<size_t>{0, 1, 2, 3}));
}

TEST(SweepGibr, PhotographItemsGiveTheStudyRunsResultsBitForBit) {
  TempDir dir;
  const Manifest m = gibr_manifest();
  const SweepSummary s = run_sweep(m, dir.path / "sweep", {"test"}, nullptr);
  EXPECT_EQ(s.failed, 0u);
  const Results items = read_results_json(dir.path / "sweep" / "items" / m.items[4].id / "results.json");
  const study::GibrOptions o = study::gibr_options(m.items[4].options);
  const Results direct = study::run_gibr(load_scene("rooms"), o, study::StudyOutput{dir.path / "direct"});
  EXPECT_GT(expect_same_metrics(direct, items), 20u);
  EXPECT_GT(expect_same_metrics(items, direct), 20u);
  expect_same_images(direct, items, dir.path / "direct", dir.path / "sweep" / "items" / m.items[4].id);
  EXPECT_GE(direct.images.size(), 4u);
}

// The manifest's model options, its prepared model and the mapping of its photograph 1.
struct MappedPhotograph {
  gibr::GibrModelOptions options = study::gibr_model_options(study::gibr_options(gibr_manifest().items[0].options));
  gibr::GibrModel model = gibr::prepare_gibr_model(load_scene("rooms"), options);
  gibr::PhotoMapping mapping = gibr::map_photograph(model, 1, options);
};

TEST(SweepGibr, PhotographMappingRoundTripsThroughItsBytes) {
  const MappedPhotograph p;
  const gibr::PhotoMapping& a = p.mapping;
  ASSERT_FALSE(a.layers.layers.empty());
  const std::string bytes = pack_photo_mapping(a);
  const gibr::PhotoMapping b = unpack_photo_mapping(bytes);
  EXPECT_EQ(pack_photo_mapping(b), bytes);
  EXPECT_TRUE(b.photo == a.photo);
  EXPECT_EQ(b.layers.layers.size(), a.layers.layers.size());
  EXPECT_EQ(b.layers.layers.front().second.rgba, a.layers.layers.front().second.rgba);
  EXPECT_THROW(unpack_photo_mapping(std::string_view(bytes).substr(0, bytes.size() - 1)), InputError);
  EXPECT_THROW(unpack_photo_mapping(bytes + "x"), InputError);
}

// photo.bin is read from a sweep directory: a layer that does not fit the model it is merged
// into is refused before the merge indexes with it.
TEST(SweepGibr, ALayerOutsideTheModelIsRefusedAtTheMerge) {
  const MappedPhotograph p;
  const gibr::GibrModel& g = p.model;
  const gibr::GibrModelOptions& mo = p.options;
  const gibr::PhotoMapping& good = p.mapping;
  ASSERT_FALSE(good.layers.layers.empty());
  auto merge = [&](void (*corrupt)(gibr::PhotoMapping&, const gibr::GibrModel&)) {
    gibr::GibrModel m;
    m.cameras = g.cameras;
    m.maps.grids = g.maps.grids;
    std::vector<gibr::PhotoMapping> photos;
    for (size_t i = 0; i < g.cameras.size(); ++i) {
      photos.push_back(unpack_photo_mapping(pack_photo_mapping(good)));
      if (i == 0) corrupt(photos.back(), g);
    }
    gibr::add_photographs(m, std::move(photos), mo);
  };
  EXPECT_NO_THROW(merge([](gibr::PhotoMapping&, const gibr::GibrModel&) {}));
  EXPECT_THROW(merge([](gibr::PhotoMapping& photo, const gibr::GibrModel& m) {
                 photo.layers.layers.front().first = uint32_t(m.maps.grids.size());
               }),
               InputError);
  EXPECT_THROW(merge([](gibr::PhotoMapping& photo, const gibr::GibrModel& m) {
                 auto& [polygon, layer] = photo.layers.layers.front();
                 layer.x0 = m.maps.grids[polygon].width - layer.width + 1;
               }),
               InputError);
  EXPECT_THROW(merge([](gibr::PhotoMapping& photo, const gibr::GibrModel& m) {
                 photo.item_layers.layers.front().second.photo = uint32_t(m.cameras.size());
               }),
               InputError);
}

TEST(SweepGibr, AFailedPhotographFailsItsRunsItemAndTheSweepGoesOn) {
  TempDir dir;
  // photo_width 0 is rejected by the model's checks: every photograph item fails.
  const Manifest m = parse_manifest(R"({"runs": [
      {"study": "gibr", "scene": "rooms", "options": {"photos": 2, "photo_width": 0}},
      {"study": "reference", "scene": "cornell", "options": {"width": 16, "height": 12}}]})",
                                    ".", "bad.json");
  ASSERT_EQ(m.items.size(), 4u);
  const SweepSummary s = run_sweep(m, dir.path, {"test"}, nullptr);
  EXPECT_EQ(s.failed, 3u);
  const ItemStatus run = stored_item(dir.path, m.items[2]);
  EXPECT_EQ(run.state, ItemState::Failed);
  EXPECT_NE(run.error.find("i000_gibr_photo"), std::string::npos) << run.error;
  EXPECT_EQ(stored_item(dir.path, m.items[3]).state, ItemState::Ok);
}

}  // namespace
}  // namespace proxima::sweep
