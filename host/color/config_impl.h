#pragma once
// What a ColorConfig holds, for the colour room's own files (not installed): the OpenColorIO config
// and the views compiled from it so far.
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include <OpenColorIO/OpenColorIO.h>

#include "color/color_config.h"
#include "color/config_downlevel.h"

namespace phongcl {

class ViewPipeline;

struct ColorConfig::Impl {
  OCIO_NAMESPACE::ConstConfigRcPtr ocio;
  std::string description;
  // What was left out of a newer OpenColorIO's config, and why (color/config_downlevel.h): the views,
  // and every line said of it.
  std::vector<OmittedView> omitted_views;
  std::vector<std::string> notes;
  // Compiled (display, view, look) triples: building one costs milliseconds, and a server changes
  // exposure on every slider step but view rarely.
  mutable std::mutex mutex;
  mutable std::map<std::tuple<std::string, std::string, std::string>, std::shared_ptr<const ViewPipeline>> views;
};

}  // namespace phongcl
