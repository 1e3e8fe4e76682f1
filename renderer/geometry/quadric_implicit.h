// The implicit function of a quadric's side surface as a matrix form, shared by the intersector
// and the surface reconstruction inside geometry/ (not a public interface). Built once per query
// and reused for every evaluation: a Newton projection evaluates F and ∇F several times.
#pragma once

#include "scene/scene.h"

namespace kiln {

// F(p) = pᵀ·A·p + 2·b·p + c with A symmetric: the side surface of every quadric kind.
struct implicit_form {
  dmat3 a{0.0};
  dvec3 b{0.0};
  double c = 0.0;
};

// Each kind's F, scaled so its coefficients are of the primitive's size (good conditioning), with
// F < 0 inside, so the gradient points out of the solid. Disk and torus give the zero form.
implicit_form implicit_of(const quadric& q);

// F(p) and ∇F(p) of the form, in the evaluation order quadric_implicit / quadric_gradient use.
inline double implicit_value(const implicit_form& f, const dvec3& p) {
  return glm::dot(p, f.a * p) + 2.0 * glm::dot(f.b, p) + f.c;
}
inline dvec3 implicit_gradient(const implicit_form& f, const dvec3& p) { return 2.0 * (f.a * p + f.b); }

}  // namespace kiln
