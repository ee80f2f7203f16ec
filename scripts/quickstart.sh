#!/usr/bin/env bash
# From a fresh Debian 12 clone to a first result: install the packages, build, and run the
# default case (data/cases/default.toml), writing ParaView files under out/.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"

build/bin/rbcflow info
mkdir -p out/quickstart
build/bin/rbcflow shape rbc --order 16 -o out/quickstart/rbc.vtp
echo "quickstart: wrote out/quickstart/rbc.vtp (open it in ParaView)"
