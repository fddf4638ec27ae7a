#include "color/display_processor.h"

#include "color/config_impl.h"

namespace phongcl {

namespace OCIO = OCIO_NAMESPACE;

OCIO::ConstProcessorRcPtr display_processor(const ColorConfig& color, const std::string& display,
                                            const std::string& view, const std::string& look) {
  const OCIO::ConstConfigRcPtr& config = color.impl().ocio;
  auto group = OCIO::GroupTransform::Create();
  std::string source = OCIO::ROLE_SCENE_LINEAR;
  bool looks_applied = false;
  if (!look.empty()) {
    const std::string look_space = OCIO::LookTransform::GetLooksResultColorSpace(config, config->getCurrentContext(), look.c_str());
    if (!look_space.empty()) {  // a look with no process space changes nothing (Blender skips it too)
      auto transform = OCIO::LookTransform::Create();
      transform->setSrc(source.c_str());
      transform->setDst(look_space.c_str());
      transform->setLooks(look.c_str());
      group->appendTransform(transform);
      source = look_space;
      looks_applied = true;
    }
  }
  auto display_view = OCIO::DisplayViewTransform::Create();
  display_view->setSrc(source.c_str());
  display_view->setDisplay(display.c_str());
  display_view->setView(view.c_str());
  display_view->setLooksBypass(looks_applied);
  group->appendTransform(display_view);
  return config->getProcessor(group);
}

}  // namespace phongcl
