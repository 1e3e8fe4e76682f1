// RGB colour spaces by their primaries and white (CIE 1931 xy), and the matrices between them:
// the EXR's chromaticities attribute and the check that a config's working space is the space it
// names. Bradford adaptation between whites, as the ACES transforms and tools/ocio_matrices.py
// use. Depends on core only.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "core/math.h"

namespace kiln {

// red, green, blue, white as xy pairs: OpenEXR's Chromaticities order.
struct chromaticities {
  std::array<double, 8> xy{};
};

// ITU-R BT.709 / sRGB with D65: glTF's colour space.
chromaticities rec709_primaries();
// ACES AP1 (ACEScg) and AP0 (ACES2065-1), ACES white (0.32168, 0.33767).
chromaticities ap1_primaries();
chromaticities ap0_primaries();

// rgb_XYZ = M · rgb, with the space's white at Y = 1.
dmat3 xyz_from_rgb(const chromaticities& space);

// rgb_to = M · rgb_from: through XYZ, adapting from's white to to's by Bradford when they differ.
dmat3 rgb_to_rgb(const chromaticities& from, const chromaticities& to);

// The primaries of the space M maps Rec.709 into: one of the spaces above when M is its matrix
// (within 1e-5 an entry, OCIO's float processing), else the primaries that M·xyz_from_rgb(Rec.709)⁻¹
// gives with D65 kept as the white (right for a space without adaptation, a best guess otherwise).
chromaticities working_primaries(const dmat3& working_from_rec709);

}  // namespace kiln
