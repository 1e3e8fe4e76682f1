#include "render/deep_pixel.h"

#include <algorithm>

namespace kiln {

uint64_t deep_tile_bytes(const deep_tile& t) {
  return uint64_t(t.samples.capacity()) * sizeof(deep_sample) +
         uint64_t(t.first.capacity()) * sizeof(uint32_t);
}

void merge_deep_samples(std::vector<deep_sample>& samples) {
  std::stable_sort(samples.begin(), samples.end(), [](const deep_sample& a, const deep_sample& b) {
    if (a.z != b.z) return a.z < b.z;
    if (a.z_back != b.z_back) return a.z_back < b.z_back;
    return a.instance < b.instance;
  });
  // In place: the merged samples [0, kept) never outrun the one being read.
  size_t kept = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const deep_sample s = samples[i];
    // The nearest merged sample of the same instance whose back s starts within the tolerance of.
    size_t into = kept;
    for (size_t m = kept; m-- > 0;)
      if (samples[m].instance == s.instance && s.z <= samples[m].z_back * (1.0f + deep_merge_tolerance)) {
        into = m;
        break;
      }
    if (into == kept) {
      samples[kept++] = s;
      continue;
    }
    samples[into].rgba += s.rgba;
    samples[into].z_back = std::max(samples[into].z_back, s.z_back);
  }
  samples.resize(kept);
}

void to_over_form(std::vector<deep_sample>& samples) {
  // Folding first, in additive form, where adding is exact (in place, like the merge).
  size_t kept = 0;
  float covered = 0.0f;
  for (size_t i = 0; i < samples.size(); ++i) {
    const deep_sample s = samples[i];
    if (kept > 0 && 1.0f - covered < deep_min_transmittance) {
      samples[kept - 1].rgba += s.rgba;
      samples[kept - 1].z_back = std::max(samples[kept - 1].z_back, s.z_back);
    } else {
      samples[kept++] = s;
    }
    covered += s.rgba.a;
  }
  samples.resize(kept);
  // Then each sample over what is in front of it: (1 - a1)(1 - a2/(1 - a1)) = 1 - a1 - a2, so the
  // transmittance compositing leaves is the additive 1 - Σ alpha and each colour comes out as added.
  covered = 0.0f;
  for (deep_sample& s : samples) {
    const float transmittance = 1.0f - covered;
    covered += s.rgba.a;
    s.rgba /= transmittance;
    s.rgba.a = std::clamp(s.rgba.a, 0.0f, 1.0f);  // rounding can take Σ alpha a hair past 1
  }
}

bool deep_samples_tidy(const std::vector<deep_sample>& samples) {
  for (size_t i = 1; i < samples.size(); ++i)
    if (samples[i].z < samples[i - 1].z_back || samples[i].z == samples[i - 1].z) return false;
  return true;
}

}  // namespace kiln
