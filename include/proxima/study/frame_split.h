// A study run over the frames of a camera path, split into contiguous frame ranges that run
// on their own (the sweep's frame items, sweep/frame_parts.h). Each range returns its
// frames' figures; the figures of every range, concatenated in frame order, reduce to the
// results of the whole run bit for bit — sums, averages, minima and maxima are taken over
// the same per-frame values in the same order as in one call, never averaged averages.
// Studies that split: cluster_reflect (study/cluster_reflect.h) and visibility
// (study/visibility.h). Temporal reuse does not: its key frames carry state from frame to
// frame and where they fall is decided by the frames before.
#pragma once

#include <utility>
#include <vector>

namespace proxima::study {

// Part `index` of `count` of a run's frames.
struct FramePart {
  int index = 0;
  int count = 1;
};

// The part's frames out of n, [first, last): [⌊index·n/count⌋, ⌊(index+1)·n/count⌋) — every
// frame in exactly one part, the parts' sizes within one of each other (empty when n < count).
std::pair<int, int> frame_span(const FramePart& part, int n);

// Per-frame figures: each series' values over the part's frames, in frame order. A study
// lists its series in a fixed order; figures of the run as a whole (not of a frame) are
// given by part 0 alone, so the concatenation holds them once.
struct FrameFigures {
  std::vector<std::vector<double>> series;
};

// Appends `part`'s values to `all`'s series (`all` takes `part`'s shape when empty).
// Throws std::runtime_error when the parts list a different number of series.
void append_figures(FrameFigures& all, const FrameFigures& part);

}  // namespace proxima::study
