// Which arbitrary output variables (AOVs) a render produces and writes, parsed from `--aovs`.
// Depends on core only.
#pragma once

#include <optional>
#include <string>

namespace kiln {

// One flag per AOV. The default is what kiln has always written: beauty, Z and N.
struct aov_set {
  bool beauty = true;     // R G B A: premultiplied colour, filtered
  bool depth = true;      // Z: ray distance of the nearest sample
  bool normal = true;     // N.X N.Y N.Z: world shading normal of the nearest sample
  bool position = false;  // P.X P.Y P.Z: world position of the nearest sample's hit
  bool albedo = false;    // albedo.R albedo.G albedo.B: base colour after textures and vertex colours
  bool uv = false;        // uv.U uv.V: TEXCOORD_0 of the nearest sample's hit
  bool ids = false;       // id.object id.material id.instance: glTF node, material, scene instance
};

// Parses a comma-separated list of names (beauty, Z, N, P, albedo, uv, id; case-sensitive, each at
// most once, at least one). Returns empty and sets *bad to the offending item otherwise.
std::optional<aov_set> parse_aov_list(const std::string& text, std::string* bad);

// The canonical comma-separated list, in channel order: "beauty,Z,N" for the default.
std::string aov_list_name(const aov_set& aovs);

}  // namespace kiln
