// The float path's kernels for the build's own instruction set
// (xsimd::default_arch: SSE2's 4 lanes on x86-64 without -march flags),
// and the choice among the sets built.
#include <xsimd/xsimd.hpp>

#include "service/contact/soft/wide/soft_wide_prepare_impl.h"

namespace contactsim {
namespace wide {

const WideKernels& BaseKernels() { return KernelTable<xsimd::default_arch>(); }

namespace {

// Whether the processor and the system run AVX. Not xsimd 8's
// available_architectures(), which reads AVX's bit from the wrong CPUID
// leaf and reports none on processors that have it.
bool ProcessorRunsAvx() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx");
#else
  return false;
#endif
}

}  // namespace

const WideKernels& ChooseKernels(int lanes) {
  const WideKernels* avx = AvxKernels();
  const bool avx_runs = avx != nullptr && ProcessorRunsAvx();
  if (avx_runs && avx->width > BaseKernels().width && (lanes == 0 || lanes == avx->width)) return *avx;
  return BaseKernels();
}

}  // namespace wide
}  // namespace contactsim
