// voxlab: whether this build runs under AddressSanitizer (the tests'
// sanitized builds, -DVOXLAB_SANITIZE=ON), which changes what a child
// process may be limited to: ASan reserves terabytes of address space for
// its shadow memory (so an RLIMIT_AS cap stops every sanitized child at
// start), and LeakSanitizer stops the world with ptrace at exit.
#pragma once

namespace voxlab {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitized = true;  // GCC
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitized = true;  // Clang
#else
inline constexpr bool kAddressSanitized = false;
#endif
#else
inline constexpr bool kAddressSanitized = false;
#endif

}  // namespace voxlab
