#include "cli/shade_over.h"

#include <cstdio>
#include <map>
#include <utility>

#include "composite/relight_over.h"

namespace phongcl::cli {

namespace {

std::string factors(const glm::dvec3& scale) {
  char text[96];
  std::snprintf(text, sizeof text, "x(%g, %g, %g)", scale.r, scale.g, scale.b);
  return text;
}

std::string describe(const GroupEdit& edit, const std::map<std::string, GroupFit>& fits) {
  switch (edit.change) {
    case GroupChange::unchanged: return edit.group + " unchanged";
    case GroupChange::scaled: return edit.group + " scaled " + factors(edit.scale);
    case GroupChange::reshaded: break;
  }
  const auto fit = fits.find(edit.group);
  if (fit == fits.end()) return edit.group + " shaded by phongcl";
  char residual[32];
  std::snprintf(residual, sizeof residual, "%.3g", fit->second.residual);
  return edit.group + " changed by phongcl's change (fit: diffuse " + factors(fit->second.diffuse_gain) + ", specular " +
         factors(fit->second.specular_gain) + ", residual " + residual + ")";
}

}  // namespace

OverResult shade_over(const std::string& render_file, const Scene& scene, Relighter& relighter) {
  RelitOver relit = relight_over(relighter, render_file, scene);
  std::string groups;
  for (const GroupEdit& edit : relit.edits) groups += (groups.empty() ? "" : ", ") + describe(edit, relit.fits);
  const std::string layer = relit.view_layer.empty() ? "" : " (view layer " + relit.view_layer + ")";
  return {std::move(relit.image),
          render_file + layer + (groups.empty() ? ": no light groups, the render as it is" : ": " + groups)};
}

}  // namespace phongcl::cli
