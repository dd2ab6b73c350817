// Private to src/viewer: the GIBR novel-view entry of the technique registry (techniques.h).
#pragma once

#include <memory>

#include "proxima/viewer/techniques.h"

namespace proxima {

// Unavailable (with the reason) unless the scene is a visibility model with a camera path.
Technique gibr_technique(std::shared_ptr<ViewerScene> scene, const TechniqueSettings& settings);

}  // namespace proxima
