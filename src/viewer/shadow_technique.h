// Private to src/viewer: the soft-shadow entry of the technique registry (techniques.h).
#pragma once

#include <memory>

#include "proxima/viewer/techniques.h"

namespace proxima {

Technique shadow_technique(std::shared_ptr<ViewerScene> scene, const TechniqueSettings& settings);

}  // namespace proxima
