// Checks every GIBR test model must pass: each quad merges into one polygon, a walk of
// ≥ 100 frames, the name among the visibility models, and every map of 6 small photographs
// passing its self-check.
#pragma once

#include <gtest/gtest.h>

#include "proxima/gibr/gibr_model.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/visibility/polygons.h"

namespace proxima::gibr {

// The photographs' silhouette edges per map, for the caller's own bound.
inline double check_gibr_test_model(const Scene& s, size_t polygons) {
  const visibility::ModelPolygons m = visibility::extract_polygons(s);
  EXPECT_EQ(m.polygons.size(), polygons);
  EXPECT_EQ(m.polygons.size() * 2, s.triangles.size()) << "every quad merges into one polygon";
  EXPECT_FALSE(s.camera_paths.empty());
  if (s.camera_paths.empty()) return 0.0;
  EXPECT_GE(s.camera_paths.front().frames, 100);
  EXPECT_TRUE(is_visibility_model(s.name));
  GibrModelOptions o;
  o.photos = 6;
  o.photo_width = 80;
  o.photo_height = 60;
  o.supersample = 1;
  const GibrModel g = build_gibr_model(s, o);
  EXPECT_EQ(g.stats.maps_failed_selfcheck, 0u);
  return g.stats.silhouette_edges_avg;
}

}  // namespace proxima::gibr
