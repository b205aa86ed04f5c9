// SPDX-License-Identifier: Apache-2.0
// The donor of the precompiled headers (cmake/RailtabModule.cmake, railtab_pch_donors): it only
// compiles them; the generator's libraries and the test programs reuse them. Nothing else here.
