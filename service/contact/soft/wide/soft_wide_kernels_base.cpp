// The float path's kernels for the build's own instruction set
// (xsimd::default_arch: SSE2's 4 lanes on x86-64 without -march flags),
// and the choice among the sets built.
#include <xsimd/xsimd.hpp>

#include "service/contact/soft/wide/soft_wide_kernels_impl.h"

namespace contactsim {
namespace wide {

const WideKernels& BaseKernels() { return Lanes<xsimd::default_arch>::Table(); }

const WideKernels& ChooseKernels(int lanes) {
  const WideKernels* avx = AvxKernels();
  const bool avx_runs = avx != nullptr && xsimd::available_architectures().avx;
  if (avx_runs && avx->width > BaseKernels().width && (lanes == 0 || lanes == avx->width)) return *avx;
  return BaseKernels();
}

}  // namespace wide
}  // namespace contactsim
