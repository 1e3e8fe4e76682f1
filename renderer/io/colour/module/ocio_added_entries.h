// The entries OpenColorIO added while reading a config, each of a kind it checks against all
// before it: what the config scan's count (ocio_config_text.h) must never fall below. For the
// scan's test and fuzz target; kiln itself counts before OpenColorIO reads.
#pragma once

#include <OpenColorIO/OpenColorIO.h>

#include <cstdint>

namespace kiln::colour_module {

inline uint64_t ocio_added_entries(const OCIO_NAMESPACE::Config& cfg) {
  namespace OCIO = OCIO_NAMESPACE;
  uint64_t n = 0;
  const int spaces = cfg.getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL);
  for (int i = 0; i < spaces; ++i) {
    const auto cs = cfg.getColorSpace(
        cfg.getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL, i));
    n += 1 + cs->getNumAliases() + uint64_t(cs->getNumCategories());
  }
  for (int i = 0; i < cfg.getNumNamedTransforms(OCIO::NAMEDTRANSFORM_ALL); ++i) {
    const auto nt = cfg.getNamedTransform(cfg.getNamedTransformNameByIndex(OCIO::NAMEDTRANSFORM_ALL, i));
    n += 1 + nt->getNumAliases() + uint64_t(nt->getNumCategories());
  }
  n += uint64_t(cfg.getNumLooks() + cfg.getNumViewTransforms() + cfg.getNumRoles());
  for (int d = 0; d < cfg.getNumDisplaysAll(); ++d) {
    const char* display = cfg.getDisplayAll(d);
    n += 1 + uint64_t(cfg.getNumViews(OCIO::VIEW_DISPLAY_DEFINED, display) +
                      cfg.getNumViews(OCIO::VIEW_SHARED, display));
  }
  n += uint64_t(cfg.getNumViews(OCIO::VIEW_SHARED, nullptr));
  n += uint64_t(cfg.getFileRules()->getNumEntries() - 1);  // the default rule is always there
  n += uint64_t(cfg.getViewingRules()->getNumEntries());
  return n;
}

}  // namespace kiln::colour_module
