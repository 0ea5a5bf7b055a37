// hotmesh tests: HOTMESH_TEST_UNDER_ASAN is 1 in a program built with AddressSanitizer, by
// GCC (which defines __SANITIZE_ADDRESS__) or by clang (which says so through __has_feature
// only), and 0 otherwise.
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define HOTMESH_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HOTMESH_TEST_UNDER_ASAN 1
#endif
#endif
#ifndef HOTMESH_TEST_UNDER_ASAN
#define HOTMESH_TEST_UNDER_ASAN 0
#endif
