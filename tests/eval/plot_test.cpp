#include "proxima/eval/plot.h"

#include <cmath>

#include <gtest/gtest.h>

#include "proxima/core/error.h"

namespace proxima {
namespace {

TEST(Plot, NiceTicksCoverTheRangeInRoundSteps) {
  EXPECT_EQ(nice_ticks(0.0, 10.0, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  const std::vector<double> t = nice_ticks(0.13, 0.87, 4);
  EXPECT_LE(t.front(), 0.13);
  EXPECT_GE(t.back(), 0.87);
  EXPECT_NEAR(t[1] - t[0], 0.2, 1e-12);
}

TEST(Plot, LineChartHasAxesLegendAndOnePointPerValue) {
  Chart c;
  c.title = "error vs size";
  c.x_label = "size";
  c.y_label = "MAE";
  c.x = {64, 128, 256};
  c.series = {{"plain", {20, 19, 18}}, {"rectified", {3, std::nan(""), 0.8}}};
  const std::string svg = svg_chart(c);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find(">error vs size</text>"), std::string::npos);
  EXPECT_NE(svg.find(">MAE</text>"), std::string::npos);
  EXPECT_NE(svg.find(">rectified</text>"), std::string::npos);  // legend
  size_t points = 0;
  for (size_t p = svg.find("<circle"); p != std::string::npos; p = svg.find("<circle", p + 1)) ++points;
  EXPECT_EQ(points, 5u);  // the NaN is a gap, not a point
  EXPECT_NE(svg.find("<title>rectified: 256, 0.8</title>"), std::string::npos);
  EXPECT_EQ(svg.find("http"), std::string::npos);  // no external references
}

TEST(Plot, BarChartFromTableColumns) {
  Table t{"times", {"scene", "a_ms", "b_ms"}, {{std::string("nest"), 1.0, 2.0}, {std::string("tree"), 3.0, 4.0}}};
  PlotSpec spec{"t", "times", "bar", "scene", {"a_ms", "b_ms"}, "", "ms"};
  const Chart c = chart_from_table(spec, t);
  EXPECT_EQ(c.categories, (std::vector<std::string>{"nest", "tree"}));
  ASSERT_EQ(c.series.size(), 2u);
  EXPECT_EQ(c.series[1].y, (std::vector<double>{2.0, 4.0}));
  const std::string svg = svg_chart(c);
  size_t bars = 0;
  for (size_t p = svg.find("<rect x"); p != std::string::npos; p = svg.find("<rect x", p + 1)) ++bars;
  EXPECT_EQ(bars, 1u + 4u + 2u);  // background, 4 bars, 2 legend swatches
  spec.y = {"c_ms"};
  EXPECT_THROW(chart_from_table(spec, t), InputError);
}

}  // namespace
}  // namespace proxima
