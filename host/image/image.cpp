// Making output images that line up with the G-buffer they shade; the display settings' bounds.
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "exr/exr_channels.h"
#include "image/image.h"

namespace phongcl {

Image image_like(const GBuffer& gbuffer) {
  Image image(gbuffer.width, gbuffer.height);
  image.data_window = exr::data_window_for(gbuffer.data_window, gbuffer.width, gbuffer.height);
  image.display_window = exr::display_window_for(gbuffer.display_window, image.data_window);
  return image;
}

void check_exposure(double stops) {
  if (std::isfinite(stops) && std::abs(stops) <= kMaxExposureStops) return;
  std::ostringstream message;
  message << "exposure must be a finite number of stops in [" << -kMaxExposureStops << ", " << kMaxExposureStops
          << "] (got " << stops << ")";
  throw std::invalid_argument(message.str());
}

}  // namespace phongcl
