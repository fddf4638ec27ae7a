#include "color/config_downlevel.h"

#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include <OpenColorIO/OpenColorIO.h>
#include <yaml-cpp/yaml.h>

#include "common/joined.h"

namespace phongcl {

namespace OCIO = OCIO_NAMESPACE;

namespace {

// The config's sections whose entries have names that other entries refer to, and what an entry of
// each is called in a message.
const std::pair<const char*, const char*> kNamedSections[] = {
    {"colorspaces", "colour space"}, {"display_colorspaces", "colour space"}, {"view_transforms", "view transform"},
    {"looks", "look"},               {"named_transforms", "named transform"},
};

std::pair<int, int> profile_version(const YAML::Node& root) {
  const YAML::Node version = root["ocio_profile_version"];
  int major = 1, minor = 0;
  if (version && version.IsScalar()) std::sscanf(version.Scalar().c_str(), "%d.%d", &major, &minor);
  return {major, minor};
}

std::pair<int, int> library_version() {
  const int hex = OCIO::GetVersionHex();
  return {hex >> 24, (hex >> 16) & 0xff};
}

std::set<std::string> library_builtins() {
  std::set<std::string> styles;
  const OCIO::ConstBuiltinTransformRegistryRcPtr registry = OCIO::BuiltinTransformRegistry::Get();
  for (std::size_t i = 0; i < registry->getNumBuiltins(); ++i) styles.insert(registry->getBuiltinStyle(i));
  return styles;
}

std::string scalar(const YAML::Node& map, const char* key) {
  const YAML::Node value = map[key];
  return value && value.IsScalar() ? value.Scalar() : "";
}

// A look list ("+A, -B" or "A:B") as names, as OpenColorIO splits it.
std::vector<std::string> look_names(const std::string& looks) {
  std::vector<std::string> names;
  std::string name;
  const auto flush = [&] {
    const std::size_t first = name.find_first_not_of(" \t+-");
    const std::size_t last = name.find_last_not_of(" \t");
    if (first != std::string::npos) names.push_back(name.substr(first, last - first + 1));
    name.clear();
  };
  for (const char c : looks) {
    if (c == ',' || c == ':')
      flush();
    else
      name += c;
  }
  flush();
  return names;
}

// What keeps an entry from this library, or "": a built-in style it lacks, or a reference to
// something already left out. Walks every transform under `node`.
class Blockers {
 public:
  explicit Blockers(std::set<std::string> builtins) : builtins_(std::move(builtins)) {}

  void leave_out(const std::string& name, const std::string& why) { left_out_.emplace(name, why); }
  bool left_out(const std::string& name) const { return left_out_.count(name) != 0; }
  std::string why(const std::string& name) const { return left_out_.at(name); }

  std::string of(const YAML::Node& node) const {
    if (node.IsSequence()) {
      for (const YAML::Node& child : node)
        if (std::string reason = of(child); !reason.empty()) return reason;
    }
    if (!node.IsMap()) return "";
    const std::string& tag = node.Tag();
    if (tag == "BuiltinTransform") {
      const std::string style = scalar(node, "style");
      if (!builtins_.count(style)) return "it needs the built-in transform '" + style + "'";
    }
    std::vector<std::string> names;
    if (tag == "ColorSpaceTransform" || tag == "LookTransform" || tag == "DisplayViewTransform")
      names = {scalar(node, "src"), scalar(node, "dst"), scalar(node, "display"), scalar(node, "view")};
    if (tag == "LookTransform") names = look_names(scalar(node, "looks"));
    if (tag == "Look") names.push_back(scalar(node, "process_space"));
    for (const std::string& name : names)
      if (left_out(name)) return "it uses '" + name + "', left out: " + why(name);
    for (const auto& entry : node)
      if (std::string reason = of(entry.second); !reason.empty()) return reason;
    return "";
  }

 private:
  std::set<std::string> builtins_;
  std::map<std::string, std::string> left_out_;  // a name (or alias, or role) -> why it was left out
};

// Removes a sequence's entries that `keep` refuses, in place.
template <typename Keep>
void filter(YAML::Node sequence, Keep keep) {
  if (!sequence || !sequence.IsSequence()) return;
  YAML::Node kept(YAML::NodeType::Sequence);
  kept.SetStyle(sequence.Style());
  for (const YAML::Node& entry : sequence)
    if (keep(entry)) kept.push_back(entry);
  sequence = kept;
}

// Named entries first, to a fixed point: a colour space may refer to another that is left out later in
// the file. Then roles, views and the lists that name views and spaces.
void leave_out_what_cannot_run(YAML::Node root, Blockers& blockers, std::map<std::string, std::vector<std::string>>& kinds) {
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& [section, kind] : kNamedSections) {
      filter(root[section], [&, kind = kind](const YAML::Node& entry) {
        const std::string reason = blockers.of(entry);
        if (reason.empty()) return true;
        const std::string name = scalar(entry, "name");
        blockers.leave_out(name, reason);
        for (const YAML::Node& alias : entry["aliases"])
          if (alias.IsScalar()) blockers.leave_out(alias.Scalar(), reason);
        kinds[kind].push_back(name);
        changed = true;
        return false;
      });
    }
  }
  if (YAML::Node roles = root["roles"]; roles && roles.IsMap()) {
    YAML::Node kept(YAML::NodeType::Map);
    for (const auto& role : roles) {
      const std::string space = role.second.IsScalar() ? role.second.Scalar() : "";
      if (!blockers.left_out(space)) {
        kept[role.first] = role.second;
        continue;
      }
      blockers.leave_out(role.first.Scalar(), blockers.why(space));
      kinds["role"].push_back(role.first.Scalar());
    }
    root["roles"] = kept;
  }
}

}  // namespace

std::optional<DownlevelledConfig> downlevel_config(const std::string& yaml) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(std::string("not YAML: ") + error.what());
  }
  if (!root.IsMap()) throw std::runtime_error("not an OCIO config: its top level is not a map");
  const auto [major, minor] = library_version();
  if (profile_version(root) <= std::make_pair(major, minor)) return std::nullopt;

  Blockers blockers(library_builtins());
  std::map<std::string, std::vector<std::string>> kinds;
  leave_out_what_cannot_run(root, blockers, kinds);

  DownlevelledConfig result;
  const std::string library = std::string("OpenColorIO ") + OCIO::GetVersion();
  const auto view_blocker = [&](const YAML::Node& view) {
    for (const char* key : {"view_transform", "colorspace", "display_colorspace"})
      if (blockers.left_out(scalar(view, key))) return scalar(view, key);
    for (const std::string& look : look_names(scalar(view, "looks")))
      if (blockers.left_out(look)) return look;
    return std::string();
  };
  std::set<std::string> views_left;
  if (YAML::Node displays = root["displays"]; displays && displays.IsMap()) {
    for (auto display : displays)
      filter(display.second, [&](const YAML::Node& view) {
        const std::string blocker = view.Tag() == "View" ? view_blocker(view) : "";
        if (blocker.empty()) {
          views_left.insert(scalar(view, "name"));
          return true;
        }
        result.views.push_back({display.first.Scalar(), scalar(view, "name"),
                                "it uses '" + blocker + "', which " + library + " cannot run (" + blockers.why(blocker) + ")"});
        return false;
      });
  }
  filter(root["shared_views"], [&](const YAML::Node& view) { return view_blocker(view).empty(); });
  filter(root["active_views"], [&](const YAML::Node& name) { return name.IsScalar() && views_left.count(name.Scalar()); });
  filter(root["inactive_colorspaces"], [&](const YAML::Node& name) { return !blockers.left_out(name.Scalar()); });
  filter(root["viewing_rules"], [&](const YAML::Node& rule) { return blockers.of(rule).empty(); });
  filter(root["file_rules"], [&](const YAML::Node& rule) { return !blockers.left_out(scalar(rule, "colorspace")); });
  for (const auto& [kind, names] : kinds)
    result.others.push_back(std::to_string(names.size()) + " " + kind + (names.size() == 1 ? "" : "s") +
                            " left out, needing what " + library + " lacks: " + joined(names));

  root["ocio_profile_version"] = std::to_string(major) + "." + std::to_string(minor);
  YAML::Emitter out;
  out << root;
  result.yaml = out.c_str();
  return result;
}

}  // namespace phongcl
