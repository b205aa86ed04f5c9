// SPDX-License-Identifier: Apache-2.0
// Whether this test program is built with a sanitizer (ASan or TSan, scripts/sanitize.sh): a few
// slow measurement tests then run fewer cases through the same code, which is what a sanitizer
// checks; the Release build (CI's test stage) runs every case.
#pragma once

namespace railtab::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)  // GCC
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace railtab::test
