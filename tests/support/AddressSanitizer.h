// Whether the test is built with AddressSanitizer, which reserves terabytes of address space: a
// test that bounds its own memory with RLIMIT_AS cannot run under it.
#pragma once

// GCC says so with __SANITIZE_ADDRESS__, clang (the sanitizer build) with __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define TIDEPOOL_TEST_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TIDEPOOL_TEST_ADDRESS_SANITIZER 1
#endif
#endif
