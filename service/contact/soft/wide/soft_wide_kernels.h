// The float path's contact passes over bundles (soft_wide_layout.h), one
// set of functions per instruction set: the kernels are written once, over
// lanes, with xsimd (soft_wide_kernels_impl.h), and compiled for the
// build's own vectors (4 floats on x86-64's SSE2) and for AVX's 8; the
// solver takes the widest the processor runs. Every operation is a lane's
// own, with no fused multiply-add (the build's -ffp-contract=off), so a
// manifold's result does not depend on the width or on which lane holds it.
#pragma once

#include "service/contact/soft/wide/soft_wide_layout.h"

namespace contactsim {
namespace wide {

struct WideKernels {
  int width = 0;  // lanes a bundle
  // bundles [begin, end): the rows' Jacobians, responses, effective
  // masses and K^-1 from the packed anchors (soft_wide_prepare_impl.h), the
  // warm start, a solve or relax pass (the pass says which), and adding the
  // accumulated impulses to the step's totals
  void (*prepare)(const WideView& view, int begin, int end) = nullptr;
  void (*warm_start)(const WideView& view, int begin, int end) = nullptr;
  void (*solve)(const WideView& view, const WidePass& pass, int begin, int end) = nullptr;
  void (*accumulate)(const WideView& view, int begin, int end) = nullptr;
};

// The build's own instruction set (SSE2's 4 lanes on x86-64 by default).
const WideKernels& BaseKernels();
// AVX's 8 lanes; null where the build has no AVX unit.
const WideKernels* AvxKernels();
// `lanes` (4 or 8) where the processor runs it; 0: the widest it runs.
const WideKernels& ChooseKernels(int lanes);

}  // namespace wide
}  // namespace contactsim
