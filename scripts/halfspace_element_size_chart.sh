#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Draws docs/validation/halfspace_element_size.png from docs/validation/halfspace_element_size.dat
# with gnuplot (no arguments; run from anywhere inside the repository).
set -eu
cd "$(dirname "$0")/.."
exec gnuplot scripts/halfspace_element_size.gp
