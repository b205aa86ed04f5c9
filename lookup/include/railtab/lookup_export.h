// SPDX-License-Identifier: Apache-2.0
/* Symbol visibility of railtab::lookup: the library is built with hidden visibility, so only
 * what is marked RAILTAB_LOOKUP_API (the C and C++ API) is exported from the shared library
 * (RAILTAB_LOOKUP_SHARED, docs/lookup.md). Harmless for the static library. */
#ifndef RAILTAB_LOOKUP_EXPORT_H
#define RAILTAB_LOOKUP_EXPORT_H

#if defined(__GNUC__) || defined(__clang__)
#define RAILTAB_LOOKUP_API __attribute__((visibility("default")))
#else
#define RAILTAB_LOOKUP_API
#endif

#endif /* RAILTAB_LOOKUP_EXPORT_H */
