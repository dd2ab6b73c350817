// Per-frame figures of the path-walking commands: proxima/eval/series.h (Series, fps), which
// the commands in namespace proxima::cli find by ordinary lookup.
#pragma once

#include "proxima/eval/series.h"
