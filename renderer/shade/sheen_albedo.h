// The directional albedo E(μ, r) of the white Charlie sheen lobe (KHR_materials_sheen: D · V · cos
// over the hemisphere, seen at μ = cos θ with sheen roughness r), which the
// specification's albedo scaling divides the layers below by. Read from a table stored in the
// source (sheen_albedo_table.inc), so no render pays for integrating it; the integration that
// made it stays here, and a test holds the two together.
#pragma once

namespace kiln {

// The table's grid: sheen_albedo_size entries along each axis, the view axis over √μ (E changes
// fastest at grazing views, where the samples crowd), the roughness axis linear in [0, 1].
constexpr int sheen_albedo_size = 32;

// E(μ, r) seen at μ = cos θ, read bilinearly from the stored table.
float sheen_directional_albedo(float cos_theta, float sheen_roughness);

// The stored table's entry at view row m and roughness row r (r · size + m).
float stored_sheen_albedo(int r, int m);

// The integral the stored entry (r, m) holds, computed anew (about 0.1 ms each).
float integrate_sheen_albedo_entry(int r, int m);

}  // namespace kiln
