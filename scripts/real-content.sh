#!/usr/bin/env bash
# Builds proxima's real-content corpus (docs/real-content.md): installs the Debian packages
# that ship real models (only the missing ones; root or sudo), converts or unpacks the
# models into DIR (default build/real-content, outside git; $PROXIMA_REAL_CONTENT or
# --out DIR) and writes the JSON scene files that use them:
#   house.json         the FZK-Haus (IFC, converted by assimp) furnished with Sweet Home 3D
#                      furniture, a mirror sphere, a wall mirror and glossy floors
#   house-sphere.json  the same house, unfurnished, with the mirror sphere as its only
#                      reflector (the configuration the env-map methods are measured on)
#   trees.json         Sweet Home 3D trees and plants on a ground
#   gallery.json       bunny, armadillo, elephant, dragon and an engine on plinths in a room
#   tree-*.json, plant-*.json   one tree or plant each, framed by one camera (sampling)
# Idempotent: models already converted are kept; the scene files are rewritten.
# Exit codes: 0 done; 3 the packages are not installed and cannot be installed here (the
# caller skips the real-content tier: "real-content: unavailable: …" on stderr); 2 bad flag;
# 1 anything else failed.
set -euo pipefail

out="${PROXIMA_REAL_CONTENT:-build/real-content}"
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    *) echo "real-content: unknown option $1 (--out DIR)" >&2; exit 2 ;;
  esac
done
[ -n "$out" ] || { echo "real-content: --out: empty directory name" >&2; exit 2; }
[ "$out" = / ] || out="${out%/}"  # model paths in the scene files are relative to it

# --- packages (scripts/install-deps.sh --real-content lists them) ------------------------
if ! bash "$(dirname "$0")/install-deps.sh" --real-content >&2; then
  echo "real-content: unavailable: its Debian packages cannot be installed here" >&2
  exit 3
fi

fzk=/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc
engine=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
bunny=/usr/share/glmark2/models/bunny.obj
cgal=/usr/share/doc/libcgal-dev/data.tar.gz
sh3d=/usr/share/sweethome3d/furniture
for f in "$fzk" "$engine" "$bunny" "$cgal" "$sh3d/Scopia.sh3f"; do
  if [ ! -f "$f" ]; then
    echo "real-content: unavailable: $f is missing although its package is installed" >&2
    exit 3
  fi
done

mkdir -p "$out/models"
models="$out/models"

# --- models -----------------------------------------------------------------------------
# assimp's exporter writes beside the target; a temporary name keeps a failed run from
# leaving a half-written model that the next run would take as done.
convert() {  # convert SRC DST (any format assimp reads → .obj/.glb)
  local src="$1" dst="$2"
  [ -s "$dst" ] && return 0
  local tmp="${dst%.*}.tmp.${dst##*.}"
  assimp export "$src" "$tmp" >/dev/null 2>&1 || { echo "real-content: assimp could not convert $src" >&2; exit 1; }
  [ -f "${tmp%.*}.mtl" ] && { sed -i "s/$(basename "${tmp%.*}").mtl/$(basename "${dst%.*}").mtl/" "$tmp"; mv "${tmp%.*}.mtl" "${dst%.*}.mtl"; }
  mv "$tmp" "$dst"
}
# OBJ bakes the glTF node transforms into the vertices, so `assimp info` reports the bounds
# proxima sees (it reports the glTF's untransformed ones).
convert "$engine" "$models/2CylinderEngine.obj"
[ -s "$models/bunny.obj" ] || cp "$bunny" "$models/bunny.obj"
for m in armadillo elephant ChineseDragon-10kv; do
  if [ ! -s "$models/$m.obj" ]; then
    tar -xzf "$cgal" -C "$models" "data/meshes/$m.off"
    convert "$models/data/meshes/$m.off" "$models/$m.obj"
  fi
done
rm -rf "$models/data"

# Sweet Home 3D models: one folder per model (OBJ + MTL + textures + licence), cm, +Y up.
sh3d_model() {  # sh3d_model CATALOG DIR → the .obj path
  local catalog="$1" dir="$2" name
  name=$(basename "$dir")
  if [ ! -s "$models/$dir/$name.obj" ]; then
    unzip -o -q "$sh3d/$catalog.sh3f" "$dir/*" -d "$models" || { echo "real-content: cannot unpack $dir from $catalog.sh3f" >&2; exit 1; }
  fi
  echo "$models/$dir/$name.obj"
}

# --- placement --------------------------------------------------------------------------
# bounds FILE → "minx miny minz maxx maxy maxz" of the file's vertices, as `assimp info`
# reports them (node transforms not applied: used on OBJ files only).
bounds() {
  assimp info "$1" 2>/dev/null | tr '()' '  ' |
    awk '/Minimum point/ {a=$3" "$4" "$5} /Maximum point/ {b=$3" "$4" "$5} END {print a" "b}'
}

# transform FILE HEIGHT PITCH YAW X FLOOR Z → a scene-file "transform" object that scales
# the model uniformly to HEIGHT m, turns it upright (PITCH −90 for a +Z-up file, 0 for +Y
# up), then YAW degrees about +Y, and stands it on y = FLOOR centred on (X, Z).
transform() {
  local b
  b=$(bounds "$1")
  awk -v b="$b" -v H="$2" -v pitch="$3" -v yaw="$4" -v px="$5" -v fl="$6" -v pz="$7" 'BEGIN {
    split(b, v, " "); cx = (v[1] + v[4]) / 2; cy = (v[2] + v[5]) / 2; cz = (v[3] + v[6]) / 2
    if (pitch == -90) { h = v[6] - v[3]; ymin = v[3]; rz = -cy }
    else if (pitch == 90) { h = v[6] - v[3]; ymin = -v[6]; rz = cy }
    else { h = v[5] - v[2]; ymin = v[2]; rz = cz }
    s = H / h; t = yaw * 3.14159265358979 / 180
    x2 = cx * cos(t) + rz * sin(t); z2 = -cx * sin(t) + rz * cos(t)
    printf "{\"translate\": [%.5f, %.5f, %.5f], \"rotate_deg\": [%g, %g, 0], \"scale\": %.7g}",
      px - s * x2, fl - s * ymin, pz - s * z2, pitch, yaw, s }'
}

# mesh NAME FILE HEIGHT PITCH YAW X FLOOR Z [EXTRA] → one scene-file object (EXTRA: more keys)
mesh() {
  local extra="${9:-}"
  printf '    {"type": "mesh", "name": "%s", "file": "%s",\n     "transform": %s%s}' \
    "$1" "${2#"$out"/}" "$(transform "$2" "$3" "$4" "$5" "$6" "$7" "$8")" "${extra:+, $extra}"
}

# Atomic write: a scene file is either the old or the new one.
write_scene() {  # write_scene NAME (content on stdin)
  cat >"$out/$1.tmp"
  mv "$out/$1.tmp" "$out/$1"
}

# --- gallery: scanned sculptures on plinths in a room ---------------------------------------
# A 12 × 8 × 4 m room of inward-facing planes, five plinths (1 m), a mirror sphere on a
# sixth, a wall mirror and a glossy floor, lit by a ceiling panel.
room() {  # room W D H FLOOR_MATERIAL: floor, ceiling and four walls facing inward
  local w="$1" d="$2" h="$3" fm="$4"
  cat <<ROOM
    {"type": "plane", "name": "floor", "size": [$w, $d], "subdivisions": [4, 4], "material": "$fm"},
    {"type": "plane", "name": "ceiling", "size": [$w, $d], "material": "wall",
     "transform": {"translate": [0, $h, 0], "rotate_deg": [180, 0, 0]}},
    {"type": "plane", "name": "wall_back", "size": [$w, $h], "material": "wall",
     "transform": {"translate": [0, $(awk "BEGIN{print $h/2}"), $(awk "BEGIN{print -$d/2}")], "rotate_deg": [90, 0, 0]}},
    {"type": "plane", "name": "wall_front", "size": [$w, $h], "material": "wall",
     "transform": {"translate": [0, $(awk "BEGIN{print $h/2}"), $(awk "BEGIN{print $d/2}")], "rotate_deg": [-90, 0, 0]}},
    {"type": "plane", "name": "wall_left", "size": [$h, $d], "material": "wall",
     "transform": {"translate": [$(awk "BEGIN{print -$w/2}"), $(awk "BEGIN{print $h/2}"), 0], "rotate_deg": [0, 0, -90]}},
    {"type": "plane", "name": "wall_right", "size": [$h, $d], "material": "wall",
     "transform": {"translate": [$(awk "BEGIN{print $w/2}"), $(awk "BEGIN{print $h/2}"), 0], "rotate_deg": [0, 0, 90]}},
ROOM
}
plinth() {  # plinth NAME X Z
  printf '    {"type": "box", "name": "%s", "size": [0.7, 1.0, 0.7], "material": "plinth", "transform": {"translate": [%s, 0.5, %s]}},\n' "$1" "$2" "$3"
}
{
  cat <<JSON
{
  // Generated by scripts/real-content.sh (docs/real-content.md): scanned models from
  // glmark2-data (bunny), CGAL's data (armadillo, elephant, Chinese dragon) and assimp's
  // test models (2CylinderEngine), on plinths in a room.
  "name": "gallery",
  "materials": [
    {"name": "floor", "diffuse": [0.35, 0.3, 0.25], "specular": 0.25, "gloss": 0.15},
    {"name": "wall", "diffuse": [0.75, 0.73, 0.7]},
    {"name": "plinth", "diffuse": [0.6, 0.6, 0.62]},
    {"name": "marble", "diffuse": [0.82, 0.8, 0.76]},
    {"name": "clay", "diffuse": [0.7, 0.42, 0.3]},
    {"name": "stone", "diffuse": [0.45, 0.47, 0.5]},
    {"name": "jade", "diffuse": [0.25, 0.5, 0.35]},
    {"name": "mirror", "diffuse": 0.02, "specular": 1.0, "gloss": 0.0},
    {"name": "frame", "diffuse": [0.2, 0.15, 0.1]},
    {"name": "panel", "diffuse": 0, "emission": [6, 6, 5.5]}
  ],
  "objects": [
JSON
  room 12 8 4 floor
  plinth plinth_bunny -4 -1.5
  plinth plinth_armadillo -1.5 -2
  plinth plinth_elephant 1.5 -2
  plinth plinth_dragon 4 -1.5
  plinth plinth_engine -3 1.5
  plinth plinth_sphere 3 1.5
  mesh bunny "$models/bunny.obj" 0.6 0 30 -4 1.0 -1.5 '"material": "marble"'; echo ,
  mesh armadillo "$models/armadillo.obj" 0.8 0 180 -1.5 1.0 -2 '"material": "clay"'; echo ,
  mesh elephant "$models/elephant.obj" 0.6 0 -30 1.5 1.0 -2 '"material": "stone"'; echo ,
  mesh dragon "$models/ChineseDragon-10kv.obj" 0.6 0 0 4 1.0 -1.5 '"material": "jade"'; echo ,
  mesh engine "$models/2CylinderEngine.obj" 0.25 0 0 -3 1.0 1.5; echo ,
  cat <<JSON
    {"type": "sphere", "name": "mirror_sphere", "radius": 0.35, "segments": 64, "rings": 32,
     "material": "mirror", "transform": {"translate": [3, 1.35, 1.5]}},
    {"type": "box", "name": "wall_mirror_frame", "size": [2.2, 1.6, 0.04], "material": "frame",
     "transform": {"translate": [0, 1.9, -3.98]}},
    {"type": "box", "name": "wall_mirror", "size": [2.0, 1.4, 0.02], "material": "mirror",
     "transform": {"translate": [0, 1.9, -3.95]}},
    {"type": "box", "name": "panel", "size": [3, 0.02, 1.5], "material": "panel",
     "transform": {"translate": [0, 3.985, 0]}}
  ],
  "lights": [
    {"type": "area", "corner": [-1.5, 3.97, -0.75], "edge_u": [3, 0, 0], "edge_v": [0, 0, 1.5],
     "radiance": [6, 6, 5.5]},
    {"type": "point", "position": [-4, 3.2, 2.5], "intensity": 6}
  ],
  "ambient": 0.03,
  "cameras": [
    {"name": "main", "position": [0, 1.7, 3.6], "target": [0, 1.1, -1.5], "vfov_deg": 60},
    {"name": "mirror", "position": [1.2, 1.6, 3.2], "target": [3, 1.3, 1.5], "vfov_deg": 45},
    {"name": "corner", "position": [-5.5, 2.2, 3.5], "target": [1, 1, -1.5], "vfov_deg": 60}
  ],
  "camera_paths": [
    {"name": "walk", "frames": 100, "keys": [
      {"time": 0, "position": [-4.5, 1.65, 3.2], "target": [-2, 1.2, -1.5]},
      {"time": 1, "position": [-1.5, 1.65, 2.6], "target": [0, 1.2, -1.8]},
      {"time": 2, "position": [1.5, 1.65, 2.6], "target": [3, 1.3, 0]},
      {"time": 3, "position": [4.5, 1.65, 3.2], "target": [3, 1.2, -1.5]}]},
    {"name": "pan", "frames": 100, "keys": [
      {"time": 0, "position": [1.0, 1.65, 2.9], "target": [3, 1.2, 1.0]},
      {"time": 1, "position": [2.6, 1.65, 3.0], "target": [2.5, 1.2, 0.0]}]}
  ]
}
JSON
} | write_scene gallery.json

# --- trees: Sweet Home 3D trees and plants on a ground ----------------------------------
# name catalog folder height(m) x z yaw  (Scopia and BlendSwap models; heights from the catalogs)
trees=(
  "maple Scopia scopia/japaneseMaple 7.0 -6 -9 0"
  "poplar Scopia scopia/poplar 7.3 0.5 -14 40"
  "pine Scopia scopia/pine 5.46 6.5 -9 0"
  "cypress Scopia scopia/cypress 5.6 -10.5 -4 0"
  "ficus Scopia scopia/ficusTree 5.0 9.5 -3 70"
  "bush Scopia scopia/bush 1.31 -4 -3 0"
)
plants=(
  "yucca BlendSwap-CC-BY blendswap-cc-by/yuccaPlant 1.8 -1.6 -1.8 0"
  "indoor_plant BlendSwap-CC-BY blendswap-cc-by/mediumIndoorPlant 0.68 1.2 -0.6 0"
  "plant BlendSwap-CC-0 blendswap-cc-0/plant 1.17 2.6 -2.6 0"
  "decorative_plant BlendSwap-CC-0 blendswap-cc-0/decorativePlant 1.03 -0.2 -3.6 0"
)
outdoor_header() {  # outdoor_header NAME COMMENT
  cat <<JSON
{
  // Generated by scripts/real-content.sh (docs/real-content.md). $2
  "name": "$1",
  "materials": [{"name": "ground", "diffuse": [0.28, 0.32, 0.18]}],
  "lights": [
    {"type": "area", "corner": [-5, 30, -5], "edge_u": [10, 0, 0], "edge_v": [0, 0, 10],
     "radiance": [30, 29, 26]}
  ],
  "environment": {"color": [0.45, 0.55, 0.75]},
  "ambient": 0.1,
JSON
}
{
  outdoor_header trees "Sweet Home 3D trees (Scopia, CC-BY 3.0) and plants (Blend Swap, CC-BY 3.0 / CC0) on a ground."
  cat <<JSON
  "objects": [
    {"type": "plane", "name": "ground", "size": [40, 40], "subdivisions": [8, 8], "material": "ground"},
JSON
  first=1
  for e in "${trees[@]}" "${plants[@]}"; do
    read -r name catalog dir h x z yaw <<<"$e"
    [ $first = 1 ] || echo ,
    first=0
    mesh "$name" "$(sh3d_model "$catalog" "$dir")" "$h" 0 "$yaw" "$x" 0 "$z"
  done
  cat <<JSON

  ],
  "cameras": [
    {"name": "main", "position": [0, 1.7, 6], "target": [0, 2.5, -6], "vfov_deg": 60},
    {"name": "low", "position": [-3, 0.6, 2.5], "target": [1, 0.8, -3], "vfov_deg": 60},
    {"name": "high", "position": [8, 9, 10], "target": [0, 1.5, -6], "vfov_deg": 55}
  ],
  "camera_paths": [
    {"name": "walk", "frames": 100, "keys": [
      {"time": 0, "position": [-4, 1.7, 6], "target": [-1, 2.2, -6]},
      {"time": 1, "position": [0, 1.7, 4.5], "target": [1, 2.2, -6]},
      {"time": 2, "position": [4, 1.7, 3], "target": [0, 2.2, -7]}]}
  ]
}
JSON
} | write_scene trees.json

# One model each, framed by camera "main" (its whole height, from the front), for the
# depth-image sampling study beside the procedural tree, grass and nest.
for e in "${trees[@]}" "${plants[@]}"; do
  read -r name catalog dir h x z yaw <<<"$e"
  kind=tree; case " ${plants[*]} " in *" $name "*) kind=plant ;; esac
  d=$(awk "BEGIN{printf \"%.3f\", 1.15 * $h / 2 / 0.57735}")
  {
    cat <<JSON
{
  // Generated by scripts/real-content.sh (docs/real-content.md): $dir from $catalog.sh3f.
  "name": "$kind-$name",
  "objects": [
JSON
    mesh "$name" "$(sh3d_model "$catalog" "$dir")" "$h" 0 0 0 0 0
    cat <<JSON

  ],
  "lights": [
    {"type": "area", "corner": [-5, 30, -5], "edge_u": [10, 0, 0], "edge_v": [0, 0, 10],
     "radiance": [30, 29, 26]}
  ],
  "environment": {"color": [0.45, 0.55, 0.75]},
  "ambient": 0.1,
  "cameras": [
    {"name": "main", "position": [0, $(awk "BEGIN{print $h/2}"), $d], "target": [0, $(awk "BEGIN{print $h/2}"), 0], "vfov_deg": 60}
  ]
}
JSON
  } | write_scene "$kind-$name.json"
done

# --- house: the FZK-Haus, furnished ------------------------------------------------------
# glTF keeps the IFC's 294 building elements as separate objects (OBJ merges them by
# material). The ground floor's living room spans x 0.3..8.3, z −4.1..−0.3 (floor y = 0),
# the bedroom x 4.2..8.3, z −9.8..−6.2, the kitchen x 8.7..11.8, z −9.8..−4.4.
convert "$fzk" "$models/fzk-haus.glb"
furniture=(
  "sofa BlendSwap-CC-0 blendswap-cc-0/sofa2 0.848 0 3.0 -3.55"
  "coffee_table BlendSwap-CC-BY blendswap-cc-by/coffeeTable 0.45 0 3.0 -2.3"
  "armchair BlendSwap-CC-0 blendswap-cc-0/armchair2 0.783 -90 5.4 -2.4"
  "shelves BlendSwap-CC-0 blendswap-cc-0/verticalShelves 1.961 90 0.55 -1.3"
  "plant BlendSwap-CC-0 blendswap-cc-0/plant 1.17 0 7.6 -3.5"
  "table BlendSwap-CC-BY blendswap-cc-by/cafe_set_mota_table 0.74 0 1.6 -1.2"
  "chair_a BlendSwap-CC-0 blendswap-cc-0/sillaBlanca 0.85 180 1.6 -0.6"
  "chair_b BlendSwap-CC-0 blendswap-cc-0/sillaBlanca 0.85 90 0.95 -1.9"
  "bed BlendSwap-CC-0 blendswap-cc-0/bed2 1.077 0 6.2 -8.8"
  "fridge BlendSwap-CC-0 blendswap-cc-0/refrigerator 1.723 -90 11.3 -9.0"
)
house_cameras() {
  cat <<JSON
  "cameras": [
    {"name": "main", "position": [7.9, 1.6, -0.6], "target": [3, 0.9, -3.2], "vfov_deg": 65},
    {"name": "sphere", "position": [3.2, 1.3, -0.7], "target": [5.6, 0.45, -1.6], "vfov_deg": 50},
    {"name": "mirror", "position": [5.0, 1.5, -0.8], "target": [6.5, 1.3, -4.1], "vfov_deg": 60},
    {"name": "bedroom", "position": [4.6, 1.6, -6.6], "target": [7, 0.6, -9], "vfov_deg": 65}
  ],
  "camera_paths": [
    {"name": "walk", "frames": 100, "keys": [
      {"time": 0, "position": [0.9, 1.6, -0.7], "target": [5, 1.0, -3.5]},
      {"time": 1, "position": [3.5, 1.6, -0.8], "target": [6.5, 1.0, -3.2]},
      {"time": 2, "position": [6.5, 1.6, -0.9], "target": [4.5, 1.0, -3.6]},
      {"time": 3, "position": [7.8, 1.6, -1.8], "target": [2, 1.0, -2.5]}]},
    {"name": "pan", "frames": 100, "keys": [
      {"time": 0, "position": [3.5, 1.6, -0.8], "target": [6.5, 1.0, -3.2]},
      {"time": 1, "position": [5.1, 1.6, -0.7], "target": [5.6, 0.6, -3.0]}]}
  ],
JSON
}
house_header() {  # house_header NAME COMMENT
  cat <<JSON
{
  // Generated by scripts/real-content.sh (docs/real-content.md). $2
  "name": "$1",
  "materials": [
    {"name": "mirror", "diffuse": 0.02, "specular": 1.0, "gloss": 0.0},
    {"name": "glossy_floor", "diffuse": [0.42, 0.3, 0.2], "specular": 0.3, "gloss": 0.1},
    {"name": "frame", "diffuse": [0.2, 0.15, 0.1]}
  ],
  "lights": [
    {"type": "point", "position": [4.2, 2.3, -2.2], "intensity": 8},
    {"type": "point", "position": [6.3, 2.3, -8.0], "intensity": 5},
    {"type": "area", "corner": [-20, 40, -20], "edge_u": [10, 0, 0], "edge_v": [0, 0, 10],
     "radiance": [20, 19, 17]}
  ],
  "environment": {"color": [0.45, 0.55, 0.75]},
  "ambient": 0.08,
JSON
  house_cameras
}
house_object='    {"type": "mesh", "name": "fzk_haus", "file": "models/fzk-haus.glb"}'
sphere_object='    {"type": "sphere", "name": "mirror_sphere", "radius": 0.4, "segments": 48, "rings": 24,
     "material": "mirror", "transform": {"translate": [5.6, 0.4, -1.6]}}'
{
  house_header house "The FZK-Haus (KIT/IAI) furnished with Sweet Home 3D furniture (Blend Swap, CC0 / CC-BY 3.0), a mirror sphere, a wall mirror and glossy floors."
  printf '  "objects": [\n%s,\n%s,\n' "$house_object" "$sphere_object"
  cat <<JSON
    {"type": "box", "name": "wall_mirror_frame", "size": [1.6, 1.4, 0.03], "material": "frame",
     "transform": {"translate": [6.3, 1.35, -4.07]}},
    {"type": "box", "name": "wall_mirror", "size": [1.4, 1.2, 0.02], "material": "mirror",
     "transform": {"translate": [6.3, 1.35, -4.05]}},
    {"type": "plane", "name": "living_floor", "size": [7.9, 3.7], "material": "glossy_floor",
     "transform": {"translate": [4.3, 0.004, -2.2]}},
    {"type": "plane", "name": "bedroom_floor", "size": [4.0, 3.5], "material": "glossy_floor",
     "transform": {"translate": [6.25, 0.004, -8.0]}},
JSON
  first=1
  for e in "${furniture[@]}"; do
    read -r name catalog dir h yaw x z <<<"$e"
    [ $first = 1 ] || echo ,
    first=0
    mesh "$name" "$(sh3d_model "$catalog" "$dir")" "$h" 0 "$yaw" "$x" 0 "$z"
  done
  printf '\n  ]\n}\n'
} | write_scene house.json
{
  house_header house-sphere "The FZK-Haus (KIT/IAI) with a mirror sphere, its only reflector."
  printf '  "objects": [\n%s,\n%s\n  ]\n}\n' "$house_object" "$sphere_object"
} | write_scene house-sphere.json
{
  house_header house-bare "The FZK-Haus (KIT/IAI) alone: the building for exact visibility."
  printf '  "objects": [\n%s\n  ]\n}\n' "$house_object"
} | write_scene house-bare.json

echo "real-content: corpus ready in $out" >&2
