#include "gbuffer/channel_map.h"

#include <array>

#include "common/error.h"

namespace phongcl {

namespace {

struct PassInfo {
  Pass pass;
  const char* name;
  std::size_t width;
};
constexpr std::array<PassInfo, 9> kPasses{{{Pass::position, "position", 3},
                                           {Pass::normal, "normal", 3},
                                           {Pass::depth, "depth", 1},
                                           {Pass::material, "material", 1},
                                           {Pass::alpha, "alpha", 1},
                                           {Pass::ka, "ka", 3},
                                           {Pass::kd, "kd", 3},
                                           {Pass::ks, "ks", 3},
                                           {Pass::shininess, "shininess", 1}}};

const PassInfo& info(Pass pass) {
  for (const auto& entry : kPasses)
    if (entry.pass == pass) return entry;
  return kPasses.front();  // unreachable: every enumerator has an entry
}

std::string known_pass_names() {
  std::string names;
  for (const auto& entry : kPasses) names += (names.empty() ? "" : ", ") + std::string(entry.name);
  return names;
}

}  // namespace

const char* pass_name(Pass pass) { return info(pass).name; }

std::pair<Pass, std::vector<std::string>> parse_channel_assignment(std::string_view text) {
  const std::string what = "--channel " + std::string(text);
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos)
    throw InputError(what + ": expected PASS=CHANNEL[,CHANNEL,CHANNEL], e.g. position=P.X,P.Y,P.Z");
  const std::string_view name = text.substr(0, equals);
  const PassInfo* pass = nullptr;
  for (const auto& entry : kPasses)
    if (name == entry.name) pass = &entry;
  if (pass == nullptr) throw InputError(what + ": unknown pass '" + std::string(name) + "' (passes: " + known_pass_names() + ")");

  // Channel names may hold spaces (Blender's "Diffuse Color"), so only commas separate them.
  std::vector<std::string> channels;
  std::string_view rest = text.substr(equals + 1);
  while (true) {
    const std::size_t comma = rest.find(',');
    channels.emplace_back(rest.substr(0, comma));
    if (channels.back().empty()) throw InputError(what + ": empty channel name");
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  if (channels.size() != pass->width)
    throw InputError(what + ": " + pass->name + " takes " + std::to_string(pass->width) + " channel" +
                     (pass->width == 1 ? "" : "s") + ", got " + std::to_string(channels.size()));
  return {pass->pass, channels};
}

}  // namespace phongcl
