#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# Runs the TrainingLogger tests on the trainers' own code: gsplat's strategy modules and
# the original 3DGS GaussianModel, from copies outside the repository. Fetches nothing.
#
#   VIS4GS_GSPLAT_SRC=/path/gsplat VIS4GS_3DGS_SRC=/path/3dgs Scripts/test-upstream-trainers.sh
#
# VIS4GS_GSPLAT_SRC: a gsplat checkout (the tests were pinned on commit
#   90d7b4b349e379ccf9ee6a8cef76aa40f48bb32e; gsplat/ and tests/test_relocation.py are read).
# VIS4GS_3DGS_SRC: a folder with graphdeco-inria/gaussian-splatting's
#   scene/gaussian_model.py and utils/general_utils.py.
# A missing copy is an error here (the CTest suites skip instead). The C++ reader checks
# the logs too when the build has it (VIS4GS_BUILD_DIR, default ./build).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
: "${VIS4GS_GSPLAT_SRC:?set VIS4GS_GSPLAT_SRC to a gsplat checkout (see this script's header)}"
: "${VIS4GS_3DGS_SRC:?set VIS4GS_3DGS_SRC to a folder with the original 3DGS files (see this script's header)}"
build=${VIS4GS_BUILD_DIR:-$here/build}
if [ -x "$build/bin/TrainingLogDump" ]; then
  VIS4GS_TRAINING_LOG_DUMP="$build/bin/TrainingLogDump"
  export VIS4GS_TRAINING_LOG_DUMP
fi
export VIS4GS_GSPLAT_SRC VIS4GS_3DGS_SRC
VIS4GS_REQUIRE_UPSTREAM=1 PYTHONDONTWRITEBYTECODE=1 exec /usr/bin/python3 -m pytest -q -rs -s \
  -p no:cacheprovider "$@" \
  "$here/Applications/TrainingLogger/tests/test_gsplat_upstream.py" \
  "$here/Applications/TrainingLogger/tests/test_gs3d_upstream.py" \
  "$here/Applications/TrainingLogger/tests/test_mocks_upstream.py"
