// The float path's kernels for AVX's 8 lanes. CMake compiles this file
// alone with -mavx on x86-64 (service/CMakeLists.txt); ChooseKernels takes
// it only where the processor reports AVX.
#include "service/contact/soft/wide/soft_wide_kernels.h"

#if defined(__AVX__)
#include "service/contact/soft/wide/soft_wide_prepare_impl.h"
#endif

namespace contactsim {
namespace wide {

#if defined(__AVX__)
const WideKernels* AvxKernels() { return &KernelTable<xsimd::avx>(); }
#else
const WideKernels* AvxKernels() { return nullptr; }
#endif

}  // namespace wide
}  // namespace contactsim
