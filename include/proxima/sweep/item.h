// One sweep work item run, packed and stored. A finished item is the directory
// DIR/items/<id>/ holding item.json (the item, its resolved options, status "ok" or
// "failed", the error, seconds) and, when it succeeded, the study's results.json and images.
// A worker runs the item into scratch space and packs the directory into one byte string,
// which the rank that owns DIR unpacks: no shared file system is needed.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "proxima/sweep/manifest.h"

namespace proxima::sweep {

// Files by path relative to the item's directory, with their bytes.
struct ItemFiles {
  std::vector<std::pair<std::string, std::string>> files;
};

std::string pack_item(const ItemFiles& files);
// Throws std::runtime_error on a malformed pack (a transport error, not user input).
ItemFiles unpack_item(std::string_view packed);

// Loads the scene and runs the study into scratch/<id> (emptied first), then reads the
// directory back and removes it. A failure — a bad scene file, a limit exceeded, options out
// of range, any exception — is recorded in item.json with its message; never thrown. A gibr
// photograph item writes photo.bin (sweep/gibr_photos.h) and a frame part part.bin
// (sweep/frame_parts.h) instead of results; an item with inputs gets their photo.bin or
// part.bin bytes in `inputs` (item_inputs), in the order of item.inputs.
ItemFiles run_item(const SweepItem& item, const std::filesystem::path& scratch,
                   const std::vector<std::string>& inputs = {});

// The files of an item that failed without running: item.json with `error`.
ItemFiles failed_item(const SweepItem& item, const std::string& error);

// The photo.bin or part.bin of each of the item's inputs, stored under out/items (read by the rank that
// owns DIR and sent with the item).
std::vector<std::string> item_inputs(const Manifest& manifest, const std::filesystem::path& out,
                                     const SweepItem& item);

// Writes the files as out/items/<id>/ atomically: into a temporary directory beside it,
// then renamed over any earlier attempt.
void store_item(const std::filesystem::path& out, const SweepItem& item, const ItemFiles& files);

// The stored outcome of an item: absent (never stored, or stored for other options or
// scene), ok or failed.
enum class ItemState { Absent, Ok, Failed };
struct ItemStatus {
  ItemState state = ItemState::Absent;
  std::string error;     // of a failed item
  double seconds = 0.0;  // wall time of the study call
};
ItemStatus stored_item(const std::filesystem::path& out, const SweepItem& item);

// The status an ItemFiles carries (its item.json).
ItemStatus item_status(const ItemFiles& files);

}  // namespace proxima::sweep
