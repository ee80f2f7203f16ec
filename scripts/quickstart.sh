#!/usr/bin/env bash
# From a fresh Debian 12 clone to a first result: install the packages, build, and run the
# default case (data/cases/default.toml: three red cells in a tube), writing ParaView files,
# diagnostics and a rendered picture under out/default/.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRBCFLOW_WERROR=ON   # as scripts/test.sh: one build
cmake --build build -j "$(nproc)"

build/bin/rbcflow info
build/bin/rbcflow run data/cases/default.toml --overwrite   # a rerun replaces out/default
echo "quickstart: open out/default/rbcflow.xdmf (or rbcflow.pvd) in ParaView;" \
     "the last frame is rendered in out/default/renders/, the diagnostics plotted in out/default/diagnostics.png"
