#!/usr/bin/env bash
# Writes small valid seed inputs for every fuzz target into DIR/<target>/ (fuzz/*_fuzz.cpp):
# hand-written scene files and meshes; small JPEGs (base64 below); EXR/PNG images,
# winged-pair files and results.json written by proxima itself.
# Usage: scripts/fuzz_seeds.sh DIR PROXIMA_BINARY
set -euo pipefail
dir=$1
proxima=$2
mkdir -p "$dir"/{scene_file,camera_path,gibr_cameras,photo_bin,part_bin,obj,ply,gltf,png,jpeg,exr,winged_pair,results}

# ---- JSON scene files ---------------------------------------------------------
cat >"$dir/scene_file/objects.json" <<'J'
{"name": "seed", "materials": [{"name": "m", "diffuse": [0.5, 0.4, 0.3], "specular": 0.5, "gloss": 0.2},
  {"name": "lamp", "diffuse": 0, "emission": 4}],
 "objects": [{"type": "box", "size": [1, 2, 1], "subdivisions": 2, "material": "m",
              "transform": {"translate": [0, 1, 0], "rotate_deg": [0, 30, 0], "scale": [1, 1, -1]}},
             {"type": "sphere", "radius": 0.5, "segments": 8, "rings": 4},
             {"type": "cylinder", "radius": 0.2, "height": 1, "segments": 6, "capped": false},
             {"type": "torus", "major_radius": 1, "minor_radius": 0.1, "major_segments": 6, "minor_segments": 3},
             {"type": "plane", "size": [4, 4], "subdivisions": [2, 3], "material": "lamp"},
             {"type": "teapot", "tessellation": 1}],
 "cameras": [{"name": "c", "position": [0, 1, 5], "target": [0, 1, 0], "vfov_deg": 45, "near": 0.1, "far": 100}],
 "lights": [{"type": "point", "position": [1, 3, 1], "intensity": [5, 5, 5]},
            {"type": "area", "corner": [-1, 3, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "radiance": 3}],
 "environment": {"color": [0.1, 0.1, 0.2]}, "ambient": 0.05}
J
cat >"$dir/scene_file/animated.json" <<'J'
// comment
{"objects": [{"type": "box", "size": [1, 1, 1], "name": "b",
  "animation": {"pivot": [0, 0, 0], "loop": true, "keys": [{"time": 0}, {"time": 1, "translate": [1, 0, 0], "rotate_deg": [0, 90, 0]}]}}]}
J
echo '{"objects": [{"type": "mesh", "file": "input.obj"}]}' >"$dir/scene_file/mesh.json"
echo '{"builtin": "cornell", "objects": [{"type": "sphere", "radius": 0.1, "material": "white"}]}' \
  >"$dir/scene_file/builtin.json"
cat >"$dir/camera_path/paths.json" <<'J'
{"objects": [{"type": "box", "size": [1, 1, 1]}],
 "camera_paths": [{"name": "orbit", "frames": 7, "keys": [
   {"time": 0, "position": [0, 1, 5], "target": [0, 0, 0]},
   {"time": 1, "position": [5, 1, 0], "target": [0, 0, 0], "vfov_deg": 40},
   {"time": 2, "position": [0, 1, -5], "target": [0, 0, 0]}]},
  {"frames": 1, "up": [0, 0, 1], "keys": [{"time": 3, "position": [0, 5, 0], "target": [0, 0, 0]}]}]}
J
cat >"$dir/camera_path/through.json" <<'J'
{"objects": [{"type": "plane", "size": [2, 2]}],
 "camera_paths": [{"frames": 5, "keys": [
   {"time": 0, "position": [0, 0, 0], "target": [0, 0, -1]},
   {"time": 1, "position": [0, 0, -2], "target": [0, 0, -1]}]}]}
J
cat >"$dir/gibr_cameras/cameras.json" <<'J'
{"format": "proxima-cameras", "version": 1, "photos": [
 {"image": "photo_000.png", "width": 64, "height": 48, "vfov_deg": 70, "position": [1, 1.6, 2],
  "orientation": [1, 0, 0, 0], "near": 0.01, "far": 100},
 {"image": "photo_001.png", "width": 32, "height": 24, "vfov_deg": 60, "position": [0, 1.5, 0],
  "orientation": [0.92, 0, 0.38, 0], "k1": -0.15, "k2": 0.03, "exposure": 0.7}]}
J

# ---- meshes -------------------------------------------------------------------
printf 'o quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl m\nf 1/1/1 2/2/1 3/3/1 4/4/1\n' \
  >"$dir/obj/quad.obj"
printf 'g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf -4 -2 -1\ng b\nf 2 3 4\nl 1 2\n' >"$dir/obj/groups.obj"
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n' \
  >"$dir/ply/ascii.ply"
{
  printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n'
  printf '\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00'  # (0, 0, 0)
  printf '\x00\x00\x80\x3f\x00\x00\x00\x00\x00\x00\x00\x00'  # (1, 0, 0)
  printf '\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00'  # (0, 1, 0)
  printf '\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00'
} >"$dir/ply/binary.ply"
# One triangle: 3 float positions (36 bytes) then 3 uint16 indices (6 bytes), base64 inline.
buffer=$(printf '\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x00\x00\x00\x01\x00\x02\x00' | base64 -w0)
cat >"$dir/gltf/triangle.gltf" <<J
{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"children": [1], "rotation": [0, 0.7071068, 0, 0.7071068]}, {"mesh": 0, "translation": [1, 0, 0], "scale": [1, -1, 1]}],
 "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
 "materials": [{"name": "metal", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.2, 1], "metallicFactor": 0.8, "roughnessFactor": 0.3}}],
 "buffers": [{"byteLength": 42, "uri": "data:application/octet-stream;base64,$buffer"}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
               {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}
J

# ---- JPEG images (proxima writes none): tjCompress2 of 16×8 / 8×8 gradients, quality 75
# (50 for 4:2:2): baseline 4:2:0 and 4:2:2, gray, progressive 4:4:4, CMYK (YCCK).
echo '/9j/4AAQSkZJRgABAQAAAQABAAD/2wBDAAgGBgcGBQgHBwcJCQgKDBQNDAsLDBkSEw8UHRofHh0aHBwgJC4nICIsIxwcKDcpLDAxNDQ0Hyc5PTgyPC4zNDL/2wBDAQkJCQwLDBgNDRgyIRwhMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjL/wAARCAAIABADASIAAhEBAxEB/8QAHwAAAQUBAQEBAQEAAAAAAAAAAAECAwQFBgcICQoL/8QAtRAAAgEDAwIEAwUFBAQAAAF9AQIDAAQRBRIhMUEGE1FhByJxFDKBkaEII0KxwRVS0fAkM2JyggkKFhcYGRolJicoKSo0NTY3ODk6Q0RFRkdISUpTVFVWV1hZWmNkZWZnaGlqc3R1dnd4eXqDhIWGh4iJipKTlJWWl5iZmqKjpKWmp6ipqrKztLW2t7i5usLDxMXGx8jJytLT1NXW19jZ2uHi4+Tl5ufo6erx8vP09fb3+Pn6/8QAHwEAAwEBAQEBAQEBAQAAAAAAAAECAwQFBgcICQoL/8QAtREAAgECBAQDBAcFBAQAAQJ3AAECAxEEBSExBhJBUQdhcRMiMoEIFEKRobHBCSMzUvAVYnLRChYkNOEl8RcYGRomJygpKjU2Nzg5OkNERUZHSElKU1RVVldYWVpjZGVmZ2hpanN0dXZ3eHl6goOEhYaHiImKkpOUlZaXmJmaoqOkpaanqKmqsrO0tba3uLm6wsPExcbHyMnK0tPU1dbX2Nna4uPk5ebn6Onq8vP09fb3+Pn6/9oADAMBAAIRAxEAPwDLs/A3T91+lb9n4G6fuv0oor1c7zHEa6nl8OZtitPeP//Z' | base64 -d >"$dir/jpeg/rgb420.jpg"
echo '/9j/4AAQSkZJRgABAQAAAQABAAD/2wBDABALDA4MChAODQ4SERATGCgaGBYWGDEjJR0oOjM9PDkzODdASFxOQERXRTc4UG1RV19iZ2hnPk1xeXBkeFxlZ2P/2wBDARESEhgVGC8aGi9jQjhCY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2NjY2P/wAARCAAIABADASEAAhEBAxEB/8QAHwAAAQUBAQEBAQEAAAAAAAAAAAECAwQFBgcICQoL/8QAtRAAAgEDAwIEAwUFBAQAAAF9AQIDAAQRBRIhMUEGE1FhByJxFDKBkaEII0KxwRVS0fAkM2JyggkKFhcYGRolJicoKSo0NTY3ODk6Q0RFRkdISUpTVFVWV1hZWmNkZWZnaGlqc3R1dnd4eXqDhIWGh4iJipKTlJWWl5iZmqKjpKWmp6ipqrKztLW2t7i5usLDxMXGx8jJytLT1NXW19jZ2uHi4+Tl5ufo6erx8vP09fb3+Pn6/8QAHwEAAwEBAQEBAQEBAQAAAAAAAAECAwQFBgcICQoL/8QAtREAAgECBAQDBAcFBAQAAQJ3AAECAxEEBSExBhJBUQdhcRMiMoEIFEKRobHBCSMzUvAVYnLRChYkNOEl8RcYGRomJygpKjU2Nzg5OkNERUZHSElKU1RVVldYWVpjZGVmZ2hpanN0dXZ3eHl6goOEhYaHiImKkpOUlZaXmJmaoqOkpaanqKmqsrO0tba3uLm6wsPExcbHyMnK0tPU1dbX2Nna4uPk5ebn6Onq8vP09fb3+Pn6/9oADAMBAAIRAxEAPwCrBoX+xWhBoX+xXp43F7iy3Hban//Z' | base64 -d >"$dir/jpeg/rgb422.jpg"
echo '/9j/4AAQSkZJRgABAQAAAQABAAD/2wBDAAgGBgcGBQgHBwcJCQgKDBQNDAsLDBkSEw8UHRofHh0aHBwgJC4nICIsIxwcKDcpLDAxNDQ0Hyc5PTgyPC4zNDL/wAALCAAIAAgBAREA/8QAHwAAAQUBAQEBAQEAAAAAAAAAAAECAwQFBgcICQoL/8QAtRAAAgEDAwIEAwUFBAQAAAF9AQIDAAQRBRIhMUEGE1FhByJxFDKBkaEII0KxwRVS0fAkM2JyggkKFhcYGRolJicoKSo0NTY3ODk6Q0RFRkdISUpTVFVWV1hZWmNkZWZnaGlqc3R1dnd4eXqDhIWGh4iJipKTlJWWl5iZmqKjpKWmp6ipqrKztLW2t7i5usLDxMXGx8jJytLT1NXW19jZ2uHi4+Tl5ufo6erx8vP09fb3+Pn6/9oACAEBAAA/AM/wf4P/ANX+7/Sv/9k=' | base64 -d >"$dir/jpeg/gray.jpg"
echo '/9j/4AAQSkZJRgABAQAAAQABAAD/2wBDAAgGBgcGBQgHBwcJCQgKDBQNDAsLDBkSEw8UHRofHh0aHBwgJC4nICIsIxwcKDcpLDAxNDQ0Hyc5PTgyPC4zNDL/2wBDAQkJCQwLDBgNDRgyIRwhMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjL/wgARCAAIABADAREAAhEBAxEB/8QAFAABAAAAAAAAAAAAAAAAAAAABP/EABQBAQAAAAAAAAAAAAAAAAAAAAX/2gAMAwEAAhADEAAAASunPIf/AP/EABYQAAMAAAAAAAAAAAAAAAAAAAACBP/aAAgBAQABBQJIRIT/xAAVEQEBAAAAAAAAAAAAAAAAAAAEAP/aAAgBAwEBPwEzYzb/xAAWEQADAAAAAAAAAAAAAAAAAAAAAwT/2gAIAQIBAT8BdUOqP//EABUQAQEAAAAAAAAAAAAAAAAAAAAx/9oACAEBAAY/Aoj/xAAUEAEAAAAAAAAAAAAAAAAAAAAQ/9oACAEBAAE/IQD/2gAMAwEAAgADAAAAEHP/xAAWEQADAAAAAAAAAAAAAAAAAAAAITH/2gAIAQMBAT8QiyLP/8QAFhEAAwAAAAAAAAAAAAAAAAAAACEx/9oACAECAQE/ELsuz//EABYQAAMAAAAAAAAAAAAAAAAAAAAxwf/aAAgBAQABPxBMiZP/2Q==' | base64 -d >"$dir/jpeg/progressive444.jpg"
echo '/9j/7gAOQWRvYmUAZAAAAAAC/9sAQwAIBgYHBgUIBwcHCQkICgwUDQwLCwwZEhMPFB0aHx4dGhwcICQuJyAiLCMcHCg3KSwwMTQ0NB8nOT04MjwuMzQy/9sAQwEJCQkMCwwYDQ0YMiEcITIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIyMjIy/8AAFAgACAAIBAERAAIRAQMRAQQRAP/EAB8AAAEFAQEBAQEBAAAAAAAAAAABAgMEBQYHCAkKC//EALUQAAIBAwMCBAMFBQQEAAABfQECAwAEEQUSITFBBhNRYQcicRQygZGhCCNCscEVUtHwJDNicoIJChYXGBkaJSYnKCkqNDU2Nzg5OkNERUZHSElKU1RVVldYWVpjZGVmZ2hpanN0dXZ3eHl6g4SFhoeIiYqSk5SVlpeYmZqio6Slpqeoqaqys7S1tre4ubrCw8TFxsfIycrS09TV1tfY2drh4uPk5ebn6Onq8fLz9PX29/j5+v/EAB8BAAMBAQEBAQEBAQEAAAAAAAABAgMEBQYHCAkKC//EALURAAIBAgQEAwQHBQQEAAECdwABAgMRBAUhMQYSQVEHYXETIjKBCBRCkaGxwQkjM1LwFWJy0QoWJDThJfEXGBkaJicoKSo1Njc4OTpDREVGR0hJSlNUVVZXWFlaY2RlZmdoaWpzdHV2d3h5eoKDhIWGh4iJipKTlJWWl5iZmqKjpKWmp6ipqrKztLW2t7i5usLDxMXGx8jJytLT1NXW19jZ2uLj5OXm5+jp6vLz9PX29/j5+v/aAA4EAQACEQMRBAAAPwC7rvjn73739awwmVeQ+IMk30PSK//Z' | base64 -d >"$dir/jpeg/cmyk.jpg"

# ---- images, written by proxima itself -----------------------------------------
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$proxima" render --scene cornell --width 6 --height 4 --spp 1 --light-samples 1 --glossy-rays 1 \
  --threads 1 --out "$out" >/dev/null
cp "$out/color.png" "$dir/png/color.png"
for f in color depth normal id; do cp "$out/$f.exr" "$dir/exr/$f.exr"; done

# ---- winged-pair files and results.json, written by proxima itself ----------------
"$proxima" visibility --scene rooms --frames 1 --width 16 --height 12 --no-oracle --no-images --threads 1 \
  --save "$dir/winged_pair/rooms.wp" --out "$out/vis" >/dev/null
cp "$out/vis/results.json" "$dir/results/visibility.json"
cat >"$out/box.json" <<'J'
{"objects": [{"type": "box", "size": [1, 1, 1]}],
 "camera_paths": [{"frames": 1, "keys": [{"time": 0, "position": [0, 0, 0.8], "target": [0, 0, 0]}]}]}
J
"$proxima" visibility --scene "$out/box.json" --frames 1 --width 16 --height 12 --no-oracle --no-images --threads 1 \
  --save "$dir/winged_pair/box.wp" --out "$out/box" >/dev/null
cp "$out/results.json" "$dir/results/render.json"

# ---- a GIBR photograph item's photo.bin, written by proxima sweep ----------------------
# The settings photo_bin_fuzz.cpp prepares its model with: rooms, one 32×24 photograph.
cat >"$out/gibr.json" <<'J'
{"runs": [{"study": "gibr", "scene": "rooms", "options": {"photos": 1, "photo_width": 32, "photo_height": 24,
  "supersample": 1, "width": 32, "height": 24, "frames": 1, "fps_repeat": 1}}]}
J
"$proxima" sweep "$out/gibr.json" --out "$out/sweep" --threads 1 >/dev/null
cp "$out/sweep/items/i000_gibr_photo/photo.bin" "$dir/photo_bin/rooms.bin"

# ---- frame parts' part.bin, written by proxima sweep -----------------------------------
# The runs part_bin_fuzz.cpp reduces figures with: cluster and visibility, two parts each.
cat >"$out/frames.json" <<'J'
{"runs": [
  {"study": "cluster_reflect", "scene": "room-reflector", "frame_items": 2,
   "options": {"width": 32, "height": 24, "path": "0", "frames": 3, "ss": 1, "cube_size": 16, "compare": true}},
  {"study": "visibility", "scene": "rooms", "frame_items": 2,
   "options": {"width": 32, "height": 24, "frames": 3, "selfcheck_rays": 50}}]}
J
"$proxima" sweep "$out/frames.json" --out "$out/frames" --threads 1 >/dev/null
for item in "$out"/frames/items/*_part; do cp "$item/part.bin" "$dir/part_bin/$(basename "$item").bin"; done
