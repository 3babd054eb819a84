// The scene's [rtl] table (ref::RtlDesc, docs/scenes.md) as the cycle model's
// RtlConfig: the one place where scene keys become scheduler, refresh,
// layout, traversal and controller settings.
#pragma once

#include "refmodel/scene/scene.hpp"
#include "rtl_model/engine.hpp"

namespace voxcast::rtl {

// Throws voxcast::Error naming the rtl.* key and the known values for a name
// the model does not know (the scene parser checks first; this guards
// descriptions built in code).
RtlConfig rtl_config(const ref::RtlDesc& desc);

}  // namespace voxcast::rtl
