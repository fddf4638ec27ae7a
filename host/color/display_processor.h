#pragma once
// The OpenColorIO processor of a display transform (color/display.h), built as Blender builds its
// own: from the working space through the look (to the look's process space) and the display's
// view (its own looks bypassed when a look was applied). Exposure is not in it: DisplayTransform
// scales the working-space values itself. Not installed (OpenColorIO's types).
#include <string>

#include <OpenColorIO/OpenColorIO.h>

#include "color/color_config.h"

namespace phongcl {

// Throws OpenColorIO's exception for names the config does not have.
OCIO_NAMESPACE::ConstProcessorRcPtr display_processor(const ColorConfig& config, const std::string& display,
                                                      const std::string& view, const std::string& look);

}  // namespace phongcl
